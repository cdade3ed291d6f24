"""Command-line usage errors: one line on stderr starting ``seatwin: error:``, exit status 2, no traceback.

Through :func:`seatwin.cli.main.run` (in process) and through the installed ``seatwin`` script
(a fresh process: what a user sees, including imports that only fail there).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from seatwin.cli.main import run


def _one_line_error(err: str, *needles: str) -> str:
    """``err`` is exactly one line ``seatwin: error: …`` that names every needle."""
    assert "Traceback" not in err, err
    lines = err.strip("\n").split("\n")
    assert len(lines) == 1, err
    assert lines[0].startswith("seatwin: error: "), err
    for needle in needles:
        assert needle in lines[0], (needle, err)
    return lines[0]


def _usage_error(capsys: pytest.CaptureFixture[str], argv: list[str], *needles: str) -> str:
    code = run(argv)
    out, err = capsys.readouterr()
    assert code == 2, (argv, code, out, err)
    assert out == "", out
    return _one_line_error(err, *needles)


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A short real recording (half a second of the built-in ferry crossing)."""
    rd = tmp_path_factory.mktemp("rec") / "run"
    assert run(["simulate", "ferry_crossing", "--out", str(rd), "--duration", "0.5", "--quiet"]) == 0
    return rd


# ---- option values the parser rejects -----------------------------------------------------


def test_invalid_choice_lidar_mode(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    _usage_error(capsys, ["simulate", "ferry_crossing", "--out", str(out), "--lidar-mode", "laser"], "laser", "--lidar-mode")
    assert not out.exists()


def test_invalid_choice_format(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    _usage_error(capsys, ["simulate", "ferry_crossing", "--out", str(out), "--format", "zip"], "zip", "--format")
    assert not out.exists()


def test_not_a_number(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    _usage_error(capsys, ["simulate", "ferry_crossing", "--out", str(out), "--duration", "abc"], "--duration", "number")
    assert not out.exists()


def test_missing_required_option(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    _usage_error(capsys, ["track", str(tmp_path / "run")], "--out")


def test_unknown_verb(capsys: pytest.CaptureFixture[str]) -> None:
    _usage_error(capsys, ["frobnicate"], "frobnicate")


def test_unknown_option(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    _usage_error(capsys, ["simulate", "ferry_crossing", "--out", str(out), "--bogus"], "--bogus")
    assert not out.exists()


# ---- output paths that cannot be written --------------------------------------------------


def test_scenario_plot_output_is_a_directory(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    d = tmp_path / "figs"
    d.mkdir()
    _usage_error(capsys, ["scenario", "plot", "ferry_crossing", "-o", str(d)], str(d))
    assert d.is_dir() and not any(d.iterdir())


def test_track_output_is_a_directory(recording: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Checked before any tracking is done: the directory is named and left as it was."""
    d = tmp_path / "tracks"
    d.mkdir()
    _usage_error(capsys, ["track", str(recording), "--out", str(d)], str(d))
    assert d.is_dir() and not any(d.iterdir())


def test_simulate_output_cannot_be_created(capsys: pytest.CaptureFixture[str]) -> None:
    _usage_error(capsys, ["simulate", "ferry_crossing", "--out", "/proc/nope", "--duration", "0.5", "--quiet"], "/proc/nope")


# ---- the installed script, in a fresh process ---------------------------------------------


def _script() -> str:
    exe = Path(sys.executable).with_name("seatwin")
    if exe.is_file():
        return str(exe)
    found = shutil.which("seatwin")
    if found is None:
        pytest.skip("the seatwin script is not installed beside this Python (pip install -e '.[test]')")
    return found


@pytest.mark.parametrize(
    ("args", "needles"),
    [
        (["simulate", "ferry_crossing", "--out", "{tmp}/run", "--lidar-mode", "laser"], ["laser"]),
        (["frobnicate"], ["frobnicate"]),
        (["track", "{tmp}/run"], ["--out"]),
        (["simulate", "ferry_crossing", "--out", "{tmp}/run", "--duration", "abc"], ["--duration", "number"]),
    ],
)
def test_usage_errors_from_the_installed_script(tmp_path: Path, args: list[str], needles: list[str]) -> None:
    argv = [_script(), *(a.replace("{tmp}", str(tmp_path)) for a in args)]
    env = dict(os.environ, COLUMNS="80", PYTHONWARNINGS="ignore")
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=120, env=env)
    assert proc.returncode == 2, (proc.returncode, proc.stdout, proc.stderr)
    assert proc.stdout == "", proc.stdout
    _one_line_error(proc.stderr, *needles)
    assert not (tmp_path / "run").exists()
