"""The static import graph of ``seatwin``: every import statement of every module, at the top
and inside functions (and under ``TYPE_CHECKING``), read from the source with ``ast``.

* no cycles between packages (``seatwin.<package>``; a top-level module counts as one);
* no cycles between modules (importing a package runs its ``__init__``, so an import of a
  package stands for the modules its ``__init__`` imports);
* no library module imports ``seatwin.cli``;
* ``geo`` imports nothing else of seatwin; ``dynamics`` only ``geo`` and ``errors``; ``scenario`` and ``world`` do not
  import each other.
"""

from __future__ import annotations

import ast
from functools import cache
from pathlib import Path

import seatwin

SRC = Path(seatwin.__file__).parent


@cache
def modules() -> dict[str, Path]:
    """Module name → file, for every module of the package."""
    out = {}
    for path in SRC.rglob("*.py"):
        parts = ["seatwin", *path.relative_to(SRC).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _imported(module: str, path: Path) -> set[str]:
    """The seatwin modules (or packages) ``module`` names in its import statements."""
    mods = modules()
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
            else:
                name = node.module or ""
            subs = [f"{name}.{a.name}" for a in node.names if f"{name}.{a.name}" in mods]
            names = subs if len(subs) == len(node.names) else [*subs, name]
        else:
            continue
        for name in names:
            while name and name not in mods:  # ``import seatwin.a.b`` of a name inside a module
                name = name.rpartition(".")[0]
            if name.startswith("seatwin"):
                out.add(name)
    out.discard(module)
    return out


@cache
def graph() -> dict[str, frozenset[str]]:
    return {m: frozenset(_imported(m, p)) for m, p in modules().items()}


def package_of(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def _loaded(module: str) -> set[str]:
    """The non-``__init__`` modules that importing ``module`` runs (a package: what its ``__init__`` imports)."""
    mods, g = modules(), graph()
    out, todo, seen = set(), [module], set()
    while todo:
        m = todo.pop()
        if m in seen:
            continue
        seen.add(m)
        if mods[m].name == "__init__.py":
            todo += [o for o in g[m] if o.startswith(m + ".")]
        else:
            out.add(m)
    return out


def cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one node (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges.get(root, ()))))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    x = stack.pop()
                    on.discard(x)
                    comp.append(x)
                    if x == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def _why(edges: dict[str, set[str]], comp: list[str], via: dict[tuple[str, str], list[str]]) -> str:
    return "; ".join(f"{a} → {b} ({', '.join(sorted(via[a, b])[:3])})" for a in comp for b in sorted(edges[a] & set(comp)))


def test_no_cycles_between_packages() -> None:
    edges: dict[str, set[str]] = {}
    via: dict[tuple[str, str], list[str]] = {}
    for m, targets in graph().items():
        a = package_of(m)
        for t in targets:
            b = package_of(t)
            if a and b and a != b:
                edges.setdefault(a, set()).add(b)
                via.setdefault((a, b), []).append(f"{m} imports {t}")
    found = cycles(edges)
    assert not found, "package cycles: " + " | ".join(_why(edges, c, via) for c in found)


def test_no_cycles_between_modules() -> None:
    mods = modules()
    edges = {
        m: set().union(*(_loaded(t) for t in g)) - {m} if g else set()
        for m, g in graph().items()
        if mods[m].name != "__init__.py"
    }
    via = {(a, b): [a] for a, bs in edges.items() for b in bs}
    found = cycles(edges)
    assert not found, "module cycles: " + " | ".join(_why(edges, c, via) for c in found)


def test_no_library_module_imports_the_cli() -> None:
    bad = sorted(f"{m} imports {t}" for m, ts in graph().items() if package_of(m) != "cli" for t in ts if package_of(t) == "cli")
    assert not bad


def test_geo_is_a_leaf() -> None:
    bad = sorted(f"{m} imports {t}" for m, ts in graph().items() if package_of(m) == "geo" for t in ts if package_of(t) != "geo")
    assert not bad


def test_scenario_and_world_are_independent() -> None:
    bad = sorted(
        f"{m} imports {t}" for m, ts in graph().items() for t in ts if {package_of(m), package_of(t)} == {"scenario", "world"}
    )
    assert not bad  # the 2-D harbour layout both need lives below them, in seatwin.layout


def test_the_graph_sees_function_level_and_relative_imports() -> None:
    g = graph()
    assert "seatwin.engine.embree" in g["seatwin.engine.backends"]  # imported inside make_caster
    assert "seatwin.layout.model" in g["seatwin.layout"]
    assert package_of("seatwin.errors") == "errors" and package_of("seatwin") == ""


def test_dynamics_is_pure():
    """``dynamics`` (vessel models, thrusters, autopilot) imports only ``geo`` and ``errors`` of seatwin."""
    bad = sorted(
        f"{m} imports {t}"
        for m, ts in graph().items()
        if package_of(m) == "dynamics"
        for t in ts
        if package_of(t) not in ("dynamics", "geo", "errors")
    )
    assert not bad
