"""The seatwin command: version, help on every verb, the demo end to end."""

from __future__ import annotations

import json

import pytest

from seatwin import __version__
from seatwin.cli.main import app, run


def test_version(capsys):
    assert run(["--version"]) == 0
    assert __version__ in capsys.readouterr().out


def _commands(group, prefix=()):
    import typer.main

    cmd = typer.main.get_command(group)
    stack = [(prefix, cmd)]
    while stack:
        path, c = stack.pop()
        yield path
        for name, sub in getattr(c, "commands", {}).items():
            stack.append((path + (name,), sub))


def test_help_on_every_verb(capsys):
    paths = list(_commands(app))
    assert len(paths) > 10
    for path in paths:
        assert run([*path, "--help"]) == 0, path
        out = capsys.readouterr().out
        assert "Usage" in out, path


@pytest.mark.slow
def test_demo_end_to_end(tmp_path, capsys):
    out = tmp_path / "demo"
    assert run(["demo", "--out", str(out), "--duration", "6"]) == 0
    printed = capsys.readouterr().out
    assert "report" in printed
    assert (out / "report" / "index.html").stat().st_size > 10_000
    table = json.loads((out / "comparison.json").read_text())
    assert {t["tuning"] for t in table["targets"]} == {"synthetic", "real"}
    assert len(list((out / "scenarios").glob("*.png"))) >= 5
    # a second demo into the same folder is refused with a clear message
    assert run(["demo", "--out", str(out)]) == 2
