"""``seatwin scenario list|info|plot|export``."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from seatwin.cli.main import run
from seatwin.scenario import builtin_names, load_scenario


def test_list(capsys):
    assert run(["scenario", "list", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["name"] for r in rows] == builtin_names()
    assert run(["scenario", "list"]) == 0
    assert "emerging_target" in capsys.readouterr().out


def test_info_json_and_table(capsys):
    assert run(["scenario", "info", "targets_in_line", "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["name"] == "targets_in_line" and len(s["vessels"]) == 3
    assert run(["scenario", "info", "targets_in_line"]) == 0
    out = capsys.readouterr().out
    assert "Closest approach" in out and "Havfruen" in out


def test_info_table_is_never_cut_and_says_the_environment_in_words(capsys, monkeypatch):
    """Issue 25, item 13: on a narrow terminal the table cut "Havfr…", "ownsh…"; the environment was a Python dict."""
    monkeypatch.setenv("COLUMNS", "40")
    assert run(["scenario", "info", "ferry_crossing"]) == 0
    out = capsys.readouterr().out
    assert "…" not in out and "{" not in out
    assert "environment: harbour default, water flat" in out
    rows: dict[str, list[str]] = {}
    for ln in out.splitlines():
        if ln.split():
            rows.setdefault(ln.split()[0], ln.split())  # the vessels table comes before the closest approaches
    assert rows["Havfruen"][:3] == ["Havfruen", "target", "havfruen"]
    assert rows["milliAmpere"][:3] == ["milliAmpere", "ownship", "milliampere"]


def test_plot_writes_a_png(tmp_path: Path, capsys):
    out = tmp_path / "fig" / "cb.png"
    assert run(["scenario", "plot", "constant_bearing", "-o", str(out)]) == 0
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000
    assert run(["scenario", "plot", "constant_bearing", "-o", str(tmp_path / "x.jpg")]) == 2
    assert "PNG" in capsys.readouterr().err


def test_export_then_load(tmp_path: Path, capsys):
    assert run(["scenario", "export", "emerging_target", "--out", str(tmp_path), "--time-format", "time-of-day"]) == 0
    assert (tmp_path / "emerging_target.csv").read_text().startswith("TimeOfDay,")
    sc = load_scenario(tmp_path / "emerging_target.yaml")
    assert sc.ownship.name == "milliAmpere" and sc.duration == pytest.approx(70.0)
    assert run(["scenario", "info", str(tmp_path / "emerging_target.csv"), "--date", "2020-09-15", "--json"]) == 0


@pytest.mark.parametrize(
    ("argv", "pattern"),
    [
        (["scenario", "info", "nope"], "built-ins are: ferry_crossing"),
        (["scenario", "info", "ferry_crossing", "--date", "15.9.2020"], "--date: expected YYYY-MM-DD"),
    ],
)
def test_bad_input_exits_2_with_one_line(argv, pattern, capsys):
    assert run(argv) == 2
    err = capsys.readouterr().err.strip()
    assert pattern in err and len(err.splitlines()) == 1


def test_plot_a_csv_outside_the_default_harbour(tmp_path: Path):
    import numpy as np

    from seatwin.scenario.gemini_csv import write_gemini_csv
    from seatwin.scenario.model import Trajectory

    t = 1600171200.0 + np.arange(30) / 10.0
    far = [Trajectory(t, -300.0 + 2 * np.arange(30), np.full(30, e), np.zeros(30)) for e in (-300.0, -250.0, 10.0)]
    write_gemini_csv(tmp_path / "far.csv", far)
    assert run(["scenario", "plot", str(tmp_path / "far.csv"), "-o", str(tmp_path / "far.png")]) == 0
    assert (tmp_path / "far.png").stat().st_size > 10_000
