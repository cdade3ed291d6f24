"""Nothing a user has is overwritten: every verb that writes refuses, before any work and with one line (exit 2),
an output that is an input or inside one, that exists (unless --overwrite), or that cannot be written; and the
CLI's last-resort boundary turns an OSError, RecursionError, MemoryError or OverflowError into one line."""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest

import seatwin.outputs
from seatwin.cli.main import run
from seatwin.recording import RecordingError

GT = Path(__file__).resolve().parents[2] / "src" / "seatwin" / "groundtruth" / "examples"


def _error(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert err.startswith("seatwin: error: ") and "\n" not in err and "Traceback" not in err, err
    return err


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def recording(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("rec") / "run"
    assert run(["simulate", "ferry_crossing", "--out", str(out), "--duration", "0.3", "--sensors", "lidar", "-q"]) == 0
    return out


@pytest.fixture
def no_work(monkeypatch):
    """Tracking fails the test if it starts: the refusals must come first."""
    import seatwin.pipeline.track

    def work(*_a, **_k):
        raise AssertionError("the work started before the outputs were checked")

    monkeypatch.setattr(seatwin.pipeline.track, "track_recording", work)


def test_track_never_writes_over_its_input(recording, tmp_path, capsys, no_work):
    before = _snapshot(recording)
    bag = recording / "recording"
    (tmp_path / "alias").symlink_to(recording)
    for out, says in (
        (recording, "is the input"),
        (recording / "manifest.json", "inside the input"),
        (bag, "inside the input"),
        (tmp_path / "alias" / "tracks.csv", "inside the input"),
    ):
        assert run(["track", str(recording), "--out", str(out), "--overwrite"]) == 2
        err = _error(capsys)
        assert says in err and str(out) in err and str(recording) in err
    assert run(["track", str(bag / "recording.mcap"), "--out", str(recording / "manifest.json"), "--overwrite"]) == 2
    assert "run or bag folder of the input" in _error(capsys)
    assert run(["track", str(bag), "--out", str(bag), "--overwrite"]) == 2
    assert "is the input" in _error(capsys)
    assert _snapshot(recording) == before


def test_track_refuses_an_existing_or_unwritable_output_before_the_work(recording, tmp_path, capsys, no_work, monkeypatch):
    out = tmp_path / "tracks.csv"
    out.write_text("mine")
    assert run(["track", str(recording), "--out", str(out)]) == 2
    assert "exists already" in (err := _error(capsys)) and "--overwrite" in err and str(out) in err
    assert out.read_text() == "mine"
    long_name = tmp_path / ("t" * 300 + ".csv")
    assert run(["track", str(recording), "--out", str(long_name)]) == 2
    assert "longer than the 255 allowed" in _error(capsys)
    assert run(["track", str(recording), "--out", str(out / "x.csv")]) == 2  # ENOTDIR
    assert "is not a folder" in _error(capsys)

    def read_only(folder):  # what creating a file in a folder of a read-only file system raises
        raise OSError(errno.EROFS, os.strerror(errno.EROFS), str(folder))

    monkeypatch.setattr(seatwin.outputs, "probe_folder", read_only)
    assert run(["track", str(recording), "--out", str(tmp_path / "new.csv")]) == 2
    err = _error(capsys)
    assert "--out: cannot write" in err and "new.csv" in err and "Read-only file system" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tracks.csv"]


def test_track_overwrite_replaces_only_the_output(recording, tmp_path, capsys):
    out = tmp_path / "tracks.csv"
    out.write_text("mine")
    assert run(["track", str(recording), "--out", str(out), "--overwrite", "--no-progress"]) == 0
    assert out.read_text().startswith("time,track_id") and sorted(p.name for p in tmp_path.iterdir()) == ["tracks.csv"]


def test_labels_export_checks_its_folder_before_reading(recording, tmp_path, capsys, monkeypatch):
    import seatwin.recording

    def work(*_a, **_k):
        raise AssertionError("the recording was read before the outputs were checked")

    monkeypatch.setattr(seatwin.recording, "open_bag", work)
    out = tmp_path / "coco"
    out.mkdir()
    (out / "annotations.json").write_text("{}")
    assert run(["labels", "export", str(recording), "--out", str(out)]) == 2
    assert "annotations.json exists already" in _error(capsys)
    assert run(["labels", "export", str(recording), "--out", str(recording / "coco"), "--overwrite"]) == 2
    assert "inside the input" in _error(capsys)
    assert run(["labels", "export", str(recording), "--out", str(tmp_path / ("c" * 260))]) == 2
    assert "longer than" in _error(capsys)


def test_groundtruth_never_writes_over_a_log(tmp_path, capsys):
    logs = tmp_path / "logs"
    logs.mkdir()
    for name in ("havfruen_bow.pos", "havfruen_stern.pos", "finn.gpx"):
        (logs / name).write_bytes((GT / name).read_bytes())
    before = _snapshot(logs)
    base = ["groundtruth", "--origin", "63.4346,10.3977", "--vessel", f"H={logs}/havfruen_bow.pos,{logs}/havfruen_stern.pos"]
    base += ["--vessel", f"Finn={logs}/finn.gpx"]
    for extra, flag in (
        (["--out", str(logs / "finn.gpx")], "--out"),
        (["--out", str(tmp_path / "s.csv"), "--quality", str(logs / "havfruen_bow.pos")], "--quality"),
        (["--out", str(tmp_path / "s.csv"), "--quality", str(tmp_path / "s.csv")], "--quality"),
    ):
        assert run([*base, *extra, "--overwrite"]) == 2
        err = _error(capsys)
        assert err.startswith(f"seatwin: error: {flag}: ") and ("is the input" in err or "given twice" in err)
    assert _snapshot(logs) == before and not (tmp_path / "s.csv").exists()
    assert run([*base, "--out", str(tmp_path / "s.csv"), "--plots", str(tmp_path / "fig")]) == 0
    assert run([*base, "--out", str(tmp_path / "t.csv"), "--plots", str(tmp_path / "fig")]) == 2
    assert "fig/V1_H_" in _error(capsys) and not (tmp_path / "t.csv").exists()


def test_simulate_never_replaces_a_users_file(tmp_path, capsys):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "scenario.csv").write_text("a user's scenario")
    args = ["simulate", "ferry_crossing", "--duration", "0.2", "--sensors", "lidar", "-q", "--out", str(mine)]
    assert run(args) == 2
    assert "exists and is not empty" in _error(capsys)
    assert run([*args, "--overwrite"]) == 2
    assert "scenario.csv was not written by seatwin" in _error(capsys)
    assert _snapshot(mine) == {"scenario.csv": b"a user's scenario"}


def test_simulate_overwrite_replaces_seatwins_run_and_keeps_other_files(tmp_path, capsys):
    out = tmp_path / "run"
    args = ["simulate", "ferry_crossing", "--duration", "0.2", "--sensors", "lidar", "-q", "--out", str(out)]
    assert run(args) == 0
    (out / "notes.txt").write_text("mine")
    assert run(args) == 2
    assert "not empty" in _error(capsys)
    assert run([*args, "--overwrite", "--format", "ros1"]) == 0
    names = ["manifest.json", "notes.txt", "recording.bag", "scenario.csv", "scenario.yaml"]
    assert sorted(p.name for p in out.iterdir()) == names
    assert (out / "notes.txt").read_text() == "mine"
    # its own scenario as input, into the same run: refused (it would be replaced)
    assert run(["simulate", str(out / "scenario.yaml"), "--duration", "0.2", "-q", "--out", str(out), "--overwrite"]) == 2
    assert "run or bag folder of the input" in _error(capsys)


def test_scenario_export_and_plot_refuse_existing_files(tmp_path, capsys):
    out = tmp_path / "exp"
    assert run(["scenario", "export", "emerging_target", "--out", str(out)]) == 0
    before = _snapshot(out)
    assert run(["scenario", "export", "emerging_target", "--out", str(out)]) == 2
    assert "exists already" in _error(capsys)
    yaml = next(out.glob("*.yaml"))
    assert run(["scenario", "export", str(yaml), "--out", str(out), "--overwrite"]) == 2
    assert "would replace the input" in _error(capsys)
    assert run(["scenario", "plot", str(yaml), "-o", str(next(out.glob("*.csv"))), "--overwrite"]) == 2
    assert "is the input" in _error(capsys)
    assert _snapshot(out) == before
    assert run(["scenario", "export", "emerging_target", "--out", str(out), "--overwrite"]) == 0


def test_a_refused_radar_simulation_writes_nothing(tmp_path, capsys):
    out = tmp_path / "X.csv"
    assert run(["radar", "simulate", "ferry_crossing", "--duration", "0", "--out", str(out)]) == 2
    assert "--duration" in _error(capsys) and not out.exists()
    out.write_text("mine")
    assert run(["radar", "simulate", "ferry_crossing", "--duration", "0", "--out", str(out), "--overwrite"]) == 2
    _error(capsys)
    assert out.read_text() == "mine" and sorted(p.name for p in tmp_path.iterdir()) == ["X.csv"]
    assert run(["radar", "simulate", "ferry_crossing", "--duration", "1", "--out", str(out)]) == 2
    assert "exists already" in _error(capsys)


@pytest.mark.parametrize(
    ("exc", "says"),
    [
        (OSError(errno.ENOSPC, "No space left on device", "/data/o.csv"), "seatwin: error: /data/o.csv: No space left on device"),
        (PermissionError(errno.EACCES, "Permission denied"), "seatwin: error: Permission denied"),
        (RecursionError("maximum recursion depth exceeded"), "nested too deeply"),
        (MemoryError(), "out of memory"),
        (RecordingError("run/recording", "recording stopped: OSError: [Errno 28] No space left on device"), "No space left"),
        (OverflowError("int too large to convert to float"), "too large"),
    ],
)
def test_the_last_resort_boundary_prints_one_line(monkeypatch, capsys, exc, says):
    import seatwin.scenario.summary

    def boom(*_a, **_k):
        raise exc

    monkeypatch.setattr(seatwin.scenario.summary, "scenario_summary", boom)
    assert run(["scenario", "info", "ferry_crossing"]) == 2
    assert says in _error(capsys)


def test_a_bug_keeps_its_traceback(monkeypatch):
    import seatwin.scenario.summary

    def bug(*_a, **_k):
        raise KeyError("a bug")

    monkeypatch.setattr(seatwin.scenario.summary, "scenario_summary", bug)
    with pytest.raises(KeyError, match="a bug"):
        run(["scenario", "info", "ferry_crossing"])


def test_every_verb_that_writes_has_overwrite():
    """--overwrite on every command with an output option (one flag name everywhere)."""
    import typer.main

    from seatwin.cli.main import app

    def commands(group, prefix=()):
        for name, cmd in getattr(group, "commands", {}).items():
            yield from commands(cmd, (*prefix, name)) if hasattr(cmd, "commands") else [((*prefix, name), cmd)]

    writers = {"--out", "-o", "--report", "--plots", "--quality", "--out-bag", "--spokes-dir", "--keep-tracks"}
    missing = []
    for path, cmd in commands(typer.main.get_command(app)):
        flags = {opt for p in cmd.params for opt in getattr(p, "opts", [])}
        json_file = any("--json" in p.opts and not getattr(p, "is_flag", False) for p in cmd.params)
        if (flags & writers or json_file) and "--overwrite" not in flags:
            missing.append(" ".join(path))
    assert missing == []


def test_demo_refuses_an_earlier_demo_before_any_work(tmp_path, capsys):
    out = tmp_path / "demo"
    (out / "reality").mkdir(parents=True)
    (out / "notes.txt").write_text("mine")
    assert run(["demo", "--out", str(out), "--duration", "1"]) == 2
    err = _error(capsys)
    assert f"{out / 'reality'} exists already" in err and "--overwrite" in err
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt", "reality"]


def test_labels_export_overwrite_replaces_only_the_earlier_export(tmp_path, capsys):
    rec = tmp_path / "cam"
    args = ["simulate", "ferry_crossing", "--out", str(rec), "--offset", "39", "--duration", "0.2", "--sensors", "camera", "-q"]
    assert run(args) == 0
    out = tmp_path / "coco"
    assert run(["labels", "export", str(rec), "--out", str(out)]) == 0
    images = sorted(p.name for p in (out / "images").iterdir())
    assert images and (out / "annotations.json").is_file()
    (out / "images" / "mine.png").write_bytes(b"a user's image")
    (out / "images" / images[0]).unlink()  # an earlier export's image gone: nothing to remove, no error
    assert run(["labels", "export", str(rec), "--out", str(out)]) == 2
    assert "exists already" in _error(capsys)
    assert run(["labels", "export", str(rec), "--out", str(out), "--overwrite"]) == 0
    assert sorted(p.name for p in (out / "images").iterdir()) == sorted([*images, "mine.png"])
    assert (out / "images" / "mine.png").read_bytes() == b"a user's image"
