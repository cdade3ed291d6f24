"""Recording knows no scenarios: no module of ``seatwin.recording`` imports the scenario, the world,
the sensors or the simulation loop (anywhere in the module, function-level imports included)."""

from __future__ import annotations

import ast
from pathlib import Path

import seatwin.recording

FORBIDDEN = ("seatwin.scenario", "seatwin.sim", "seatwin.world", "seatwin.sensors")


def _imports(path: Path, package: str) -> list[str]:
    """Every module name ``path`` imports (``from a import b`` gives ``a`` and ``a.b``; relative ones resolved)."""
    names = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf8"), str(path))):
        if isinstance(node, ast.Import):
            names += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                base = f"{parent}.{base}" if base else parent
            names.append(base)
            names += [f"{base}.{a.name}" for a in node.names]
    return names


def test_recording_imports_nothing_scenario_aware() -> None:
    root = Path(seatwin.recording.__file__).parent
    modules = sorted(root.rglob("*.py"))
    assert len(modules) > 10
    bad = []
    for path in modules:
        package = ".".join(("seatwin", "recording", *path.relative_to(root).parent.parts))
        for name in _imports(path, package):
            if name in FORBIDDEN or name.startswith(tuple(f + "." for f in FORBIDDEN)):
                bad.append(f"{path.relative_to(root)}: {name}")
    assert not bad, "recording must not know scenarios:\n" + "\n".join(bad)


def test_the_check_sees_function_level_and_relative_imports(tmp_path: Path) -> None:
    src = tmp_path / "m.py"
    src.write_text("def f():\n    from seatwin.scenario.load import load_scenario\nfrom ... import sim\n")
    assert "seatwin.scenario.load" in _imports(src, "seatwin.recording.storage")
    assert "seatwin.sim" in _imports(src, "seatwin.recording.storage")
