"""Every verb's ``--help`` shows its help text as written: no bracketed unit lost to Rich markup.

Bare ``seatwin`` and bare groups print their help and exit 0, with nothing on stderr.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

import pytest
import typer

from seatwin.cli.main import app, run

# ``[deg]``, ``[s]``, ``[m/s]``: a bracketed word in a help text, escaped (``\\[deg]``) or not.
_BRACKETED = re.compile(r"\\?\[([^\[\]\n]+)\]")


def _commands(command: Any, path: tuple[str, ...] = ()) -> Iterator[tuple[tuple[str, ...], Any]]:
    yield path, command
    for name, sub in getattr(command, "commands", {}).items():
        if not sub.hidden:
            yield from _commands(sub, (*path, name))


def _help_texts(command: Any) -> list[str]:
    texts = [command.help or ""]
    texts += [getattr(p, "help", None) or "" for p in command.params if not getattr(p, "hidden", False)]
    return texts


ALL = list(_commands(typer.main.get_command(app)))


def test_every_verb_is_walked() -> None:
    paths = {" ".join(p) for p, _ in ALL}
    assert {"", "simulate", "bag info", "scenario info", "radar simulate", "cosim run", "serve"} <= paths


@pytest.mark.parametrize("path,command", ALL, ids=[" ".join(p) or "seatwin" for p, _ in ALL])
def test_help_keeps_bracketed_units(
    path: tuple[str, ...], command: Any, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("COLUMNS", "2000")  # one line per paragraph: a unit is never wrapped apart
    assert run([*path, "--help"]) == 0
    out, err = capsys.readouterr()
    assert err == ""
    shown = " ".join(out.replace("│", " ").split())
    for text in _help_texts(command):
        for word in _BRACKETED.findall(text):
            assert f"[{word}]" in shown, (path, word, text)
    assert "<bool>" not in shown  # a flag takes no value


def test_units_of_the_issue_are_shown(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "2000")
    run(["simulate", "--help"])
    assert "horizontal field of view [deg]" in capsys.readouterr().out
    run(["cosim", "run", "--help"])
    assert re.search(r"Fixed step \[s\]", capsys.readouterr().out)


@pytest.mark.parametrize("argv", [[], ["scenario"], ["bag"], ["radar"]])
def test_bare_group_prints_help_and_exits_0(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert run(argv) == 0
    out, err = capsys.readouterr()
    assert "Usage: seatwin" in out
    assert "Commands" in out
    assert err == ""


def test_one_progress_vocabulary() -> None:
    """Every verb with a progress bar spells it --progress/--no-progress; simulate's --quiet/-q is a hidden old spelling."""
    spellings = set()
    for _, command in ALL:
        for p in getattr(command, "params", []):
            if p.name in ("progress", "quiet"):
                spellings.add((tuple(p.opts), tuple(p.secondary_opts), p.hidden))
    assert (("--progress",), ("--no-progress",), False) in spellings
    assert all(s == (("--progress",), ("--no-progress",), False) or s[2] for s in spellings), spellings


def test_placeholders_are_one_vocabulary(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "2000")
    for argv in (["simulate", "--help"], ["sweep", "--help"], ["lidar", "snapshot", "--help"]):
        assert run(argv) == 0
        out = capsys.readouterr().out
        assert "<float>" not in out and "<int>" not in out and "<path>" not in out and "[[" not in out, argv
    assert run(["lidar", "snapshot", "--help"]) == 0
    out = capsys.readouterr().out
    assert all(m in out for m in ("raycast", "depthbuffer-legacy", "depthbuffer-plane")) and "(required)" in out
