"""Error messages name the flag the user typed and say what is expected in words (issue 25, item 7).

No pydantic internals ("Value error,", "Field required", "1: Input should be"), no Python reprs
(``('fog',)``, ``0.0``), no library parameter names (``--camera-hfov-deg``, ``--time``).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from seatwin.cli.main import run

LEAKS = ("Value error", "Field required", "Input should", "('", "',)", "Tuple should", "_deg", "--time")


def _error(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    assert run(argv) == 2, argv
    err = capsys.readouterr().err.strip()
    assert err.startswith("seatwin: error: ") and "\n" not in err, err
    for leak in LEAKS:
        assert leak not in err, (leak, err)
    return err.removeprefix("seatwin: error: ")


@pytest.mark.parametrize(
    "args,expected",
    [
        (["--camera-hfov", "0"], "--camera-hfov: expected a value greater than 1, got 0"),
        (["--offset", "-10"], "--offset: -10 s is outside the scenario: expected 0 to 75 s after its start"),
        (["--start", "5"], "--start: 5.000 is outside the scenario: expected a POSIX time from 1600171200.000 to 1600171275.000"),
        (["--camera-distortion", "1,2"], "--camera-distortion: expected 5 values, got 2"),
        (["--camera-distortion", "1,2,3,4,5,6"], "--camera-distortion: expected 5 values, got 6"),
        (["--camera-distortion", "1,x,3,4,5"], "--camera-distortion: item 2: expected a valid number"),
        (["--sensors", "lidar,sonar"], "--sensors: item 2: expected 'lidar', 'radar' or 'camera', got 'sonar'"),
        (["--ray-drop", "2"], "--ray-drop: expected a value less than 1, got 2"),
    ],
)
def test_simulate_messages(args: list[str], expected: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    assert _error(capsys, ["simulate", "ferry_crossing", "--out", str(out), "--quiet", *args]).startswith(expected)
    assert not out.exists()


def test_camera_snapshot_offset_names_offset(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "snap"
    err = _error(capsys, ["camera", "snapshot", "ferry_crossing", "--offset", "9999", "-o", str(out)])
    assert err == "--offset: 9999 s is outside the scenario: expected 0 to 75 s after its start"


def test_sweep_kinds_no_python_repr(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    err = _error(capsys, ["sweep", "ferry_crossing", "--out", str(tmp_path / "s"), "--kinds", "fog"])
    assert err == "--kinds: unknown degradation 'fog'; expected some of noise, drop, dissipation, mount"


def test_sweep_strength_at_the_reference_says_the_reference(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from seatwin.sweep.degradations import DEGRADATIONS

    ref = DEGRADATIONS["noise"].reference
    err = _error(capsys, ["sweep", "ferry_crossing", "--out", str(tmp_path / "s"), "--kinds", "noise", "--strengths", f"{ref:g}"])
    assert err.startswith("--strengths: ") and f"differ from the reference {ref:g}" in err


def test_sweep_help_shows_the_code_s_numbers(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """One source: the help's reference model and default strengths are those of DEGRADATIONS."""
    from seatwin.sweep.degradations import DEGRADATIONS

    monkeypatch.setenv("COLUMNS", "2000")
    assert run(["sweep", "--help"]) == 0
    shown = " ".join(capsys.readouterr().out.replace("│", " ").split())
    noise, drop = DEGRADATIONS["noise"], DEGRADATIONS["drop"]
    assert f"noise {noise.reference:g} m, drop {drop.reference:g}" in shown
    assert f"noise {','.join(f'{s:g}' for s in noise.default_strengths)} m" in shown
    assert f"drop {','.join(f'{s:g}' for s in drop.default_strengths)}" in shown
    assert "0.05 m" not in shown


@pytest.mark.parametrize("duration", ["0", "-1", "9999"])
def test_radar_simulate_refused_writes_nothing(duration: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 25, item 9: a refused ``radar simulate`` left a header-only CSV; its help showed [x>=0.0] while 0 is refused."""
    out, spokes = tmp_path / "X.csv", tmp_path / "spokes"
    err = _error(
        capsys, ["radar", "simulate", "ferry_crossing", "--duration", duration, "--out", str(out), "--spokes-dir", str(spokes)]
    )
    assert err.startswith("--duration: ")
    assert not out.exists() and not spokes.exists()


def test_radar_simulate_help_shows_no_bound_that_admits_0(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("COLUMNS", "2000")
    assert run(["radar", "simulate", "--help"]) == 0
    out = capsys.readouterr().out
    assert "x>=0.0" not in out and "more than 0" in out


def test_simulate_summary_in_words(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 25, item 11: the frames per sensor in words, not a Python dict."""
    argv = ["simulate", "ferry_crossing", "--out", str(tmp_path / "r"), "--offset", "30", "--duration", "0.5", "--no-progress"]
    assert run([*argv, "--sensors", "lidar,radar"]) == 0
    out = capsys.readouterr().out
    assert "frames: ground truth 5, lidar 5" in out and "{" not in out


def test_a_parameter_is_named_by_the_verbs_own_flag(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``vessels`` is ``--vessels`` in ``serve`` (a list) and ``--vessel`` in ``groundtruth`` (one a flag)."""
    err = _error(capsys, ["serve", "--vessels", "A,A", "--ownship", "A", "--out", str(tmp_path / "run")])
    assert err == "--vessels: vessel names must be unique, got ['A', 'A']"
