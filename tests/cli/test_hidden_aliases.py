"""Old option spellings (``--time``, ``--output``, ``--preset``, ``--range-model``, ``--drop``) still work
but are hidden: ``--help`` shows one vocabulary."""

from __future__ import annotations

import click
import pytest
import typer

from seatwin.cli.main import app, run

OLD = ("--time", "--output", "--preset", "--range-model", "--drop")


def _commands(cmd: click.Command, path: tuple[str, ...] = ()):  # noqa: ANN202
    yield path, cmd
    if isinstance(cmd, click.Group):
        for name, sub in cmd.commands.items():
            yield from _commands(sub, (*path, name))


def test_no_visible_option_uses_an_old_spelling() -> None:
    for path, cmd in _commands(typer.main.get_command(app)):
        for p in cmd.params:
            if isinstance(p, click.Option) and not p.hidden:
                assert not set(p.opts + p.secondary_opts) & set(OLD), (path, p.opts)


@pytest.mark.parametrize("verb", [["lidar", "snapshot"], ["camera", "snapshot"]])
def test_help_does_not_show_old_spellings(verb, capsys) -> None:
    assert run([*verb, "--help"]) == 0
    out = capsys.readouterr().out
    assert "--offset" in out and "--out" in out
    for old in OLD:
        assert old not in out, old


def test_old_spellings_still_work(tmp_path) -> None:
    png = tmp_path / "a.png"
    args = ["lidar", "snapshot", "ferry_crossing", "--time", "1", "--output", str(png)]
    assert run([*args, "--preset", "vlp16-thesis", "--range-model", "raycast", "--drop", "0.5"]) == 0
    assert png.stat().st_size > 1000


@pytest.mark.parametrize(
    "args",
    [
        ["lidar", "snapshot", "ferry_crossing", "--time", "1", "--offset", "2", "--out", "x.png"],
        ["camera", "snapshot", "ferry_crossing", "--time", "1", "--offset", "2", "--out", "d"],
        ["lidar", "snapshot", "ferry_crossing", "--drop", "0.5", "--ray-drop", "0.4", "--out", "x.png"],
    ],
)
def test_a_flag_and_its_old_spelling_together_is_an_error(args, capsys, tmp_path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    assert run(args) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "given twice" in err and "old spelling" in err, err
