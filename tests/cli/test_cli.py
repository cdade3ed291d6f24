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
    assert run(["demo", "--out", str(out), "--duration", "10"]) == 0
    captured = capsys.readouterr()
    printed = captured.out
    assert "report" in printed
    html = (out / "report" / "index.html").read_text()
    assert len(html) > 10_000
    assert html.count("“Real” dataset:") == 1  # once, not once per tuning
    table = json.loads((out / "comparison.json").read_text())
    assert {t["tuning"] for t in table["targets"]} == {"synthetic", "real"}
    # the demo's window (from 25 s): both targets tracked in both datasets, under both tunings
    assert {t["target"] for t in table["targets"]} == {"Havfruen", "Finn"}
    assert all(t["ahed"] is not None and t["n_common"] > 0 for t in table["targets"]), table["targets"]
    assert "undefined" not in printed
    assert "warning" not in captured.err  # reality and simulator do not share a seed
    assert len(list((out / "scenarios").glob("*.png"))) >= 5
    # a second demo into the same folder is refused with a clear message
    assert run(["demo", "--out", str(out)]) == 2
