"""Faults: a run killed with SIGKILL, a full disk, bags cut at an arbitrary byte."""

from __future__ import annotations

import errno
import json
import os
import signal
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest
from recording_helpers import T0, sweep, write_run

from seatwin.cli.main import run
from seatwin.recording import RecordingError, RecordingWriter, open_bag

CHILD = Path(__file__).with_name("_killed_writer.py")


def _kill_after(run_dir: Path, fmt: str, sweeps: int, timeout: float = 60.0) -> None:
    proc = subprocess.Popen([sys.executable, str(CHILD), str(run_dir), fmt], stdout=subprocess.PIPE, text=True)
    reached = threading.Event()

    def watch() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            if int(line) >= sweeps:
                reached.set()
                return

    threading.Thread(target=watch, daemon=True).start()
    ok = reached.wait(timeout)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert ok, "the child did not record enough sweeps in time"
    assert proc.returncode == -signal.SIGKILL


def test_sigkill_leaves_readable_prefix(tmp_path: Path, fmt: str, capsys: pytest.CaptureFixture[str]) -> None:
    run_dir = tmp_path / "run"
    _kill_after(run_dir, fmt, sweeps=12)
    manifest = json.loads((run_dir / "manifest.json").read_text())
    assert manifest["completed"] is False
    flushed = manifest["topics"]["/lidar/points"]["count"]
    assert flushed >= 10
    with open_bag(run_dir) as rec:
        assert rec.recovered and rec.complete is False
        clouds = list(rec.point_clouds("/lidar/points"))
        assert len(clouds) >= flushed
        assert all(c.width == 2000 and c.points["ring"].max() < 16 for c in clouds)
        stamps = np.array([c.stamp for c in clouds])
        np.testing.assert_allclose(np.diff(stamps), 0.1, atol=1e-6)
        truth = rec.ground_truth()["own"]
        assert len(truth.time) >= flushed - 1
    assert run(["bag", "info", str(run_dir)]) == 0
    out = capsys.readouterr().out
    assert "NO (run did not finish)" in out and "recovered" in out


class _FullDisk:
    """A file object that accepts ``budget`` more bytes, then fails like a full disk."""

    def __init__(self, f, budget: int) -> None:
        self.f, self.budget = f, budget

    def write(self, b) -> int:
        b = bytes(b)
        if len(b) > self.budget:
            self.f.write(b[: self.budget])
            self.budget = 0
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        self.budget -= len(b)
        return self.f.write(b)

    def __getattr__(self, name: str):
        return getattr(self.f, name)


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
def test_out_of_disk(tmp_path: Path, fmt: str) -> None:
    w = RecordingWriter(tmp_path / "run", fmt, flush_interval_s=0.2)
    w.storage.writer.bio = _FullDisk(w.storage.writer.bio, 150_000)  # the MCAP file / the ROS 1 bag
    written = 0
    with pytest.raises(RecordingError, match="No space left"):
        for k in range(100):
            w.write_sweep("/lidar/points", "lidar", T0 + 0.1 * k, **sweep(k, n=1000))
            written += 1
    manifest = json.loads((tmp_path / "run" / "manifest.json").read_text())
    assert manifest["completed"] is False and "No space left" in manifest["error"]
    with open_bag(tmp_path / "run") as rec:
        assert rec.complete is False and rec.recovered
        clouds = list(rec.point_clouds())
    assert 1 <= len(clouds) < written + 1
    for k, c in enumerate(clouds):
        np.testing.assert_array_equal(c.points["x"], sweep(k, n=1000)["x"])
    with pytest.raises(RecordingError, match="closed"):
        w.write_sweep("/lidar/points", "lidar", T0, **sweep(0, n=10))


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
@pytest.mark.parametrize("fraction", [0.3, 0.7, 0.999])
def test_bag_cut_at_any_byte(tmp_path: Path, fmt: str, fraction: float) -> None:
    """Copy a finished bag's first bytes only: the reader returns the complete chunks before the cut."""
    write_run(tmp_path / "run", fmt, n_sweeps=40, flush_interval_s=0.3)
    src = tmp_path / "run" / ("recording.bag" if fmt == "ros1" else "recording/recording.mcap")
    data = src.read_bytes()
    cut = tmp_path / ("cut.bag" if fmt == "ros1" else "cut.mcap")
    cut.write_bytes(data[: int(len(data) * fraction)])
    with open_bag(cut) as rec:
        assert rec.recovered and rec.complete is False
        clouds = list(rec.point_clouds("/lidar/points"))
    # The 40 sweeps are nearly all of the bag's bytes and spread evenly over it; a chunk is
    # closed at every flush (0.3 s of recorded time: at most 5 sweeps of 0.1 s). So the cut
    # loses the sweeps after it and at most the one unfinished chunk before it, and cutting
    # only the index at the end (0.999) loses no sweep at all.
    if fraction > 0.99:
        assert len(clouds) == 40
    else:
        assert fraction * 40 - 6 <= len(clouds) <= fraction * 40 + 1, len(clouds)
    for k, c in enumerate(clouds):
        np.testing.assert_array_equal(c.points["time"], sweep(k)["time"])


def test_rosbag2_without_metadata_yaml(tmp_path: Path) -> None:
    write_run(tmp_path / "run", "sqlite3", n_sweeps=3)
    (tmp_path / "run" / "recording" / "metadata.yaml").unlink()
    with open_bag(tmp_path / "run" / "recording") as rec:
        assert rec.recovered
        assert len(list(rec.point_clouds("/lidar/points"))) == 3


def test_a_manifest_is_finished_with_the_error_even_on_a_full_disk(tmp_path: Path, monkeypatch) -> None:
    """The temporary manifest cannot be written (disk full): the manifest is rewritten in its own blocks, no .part."""
    from seatwin.recording.manifest import write_manifest

    write_manifest(tmp_path, {"completed": False, "error": None, "notes": ["x" * 200]})
    real = Path.write_text

    def full(self: Path, data: str, *args, **kwargs) -> int:
        if self.name.endswith(".part"):
            real(self, "")
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(self))
        return real(self, data, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", full)
    write_manifest(tmp_path, {"completed": False, "error": "OSError: [Errno 28] No space left on device"})
    assert json.loads((tmp_path / "manifest.json").read_text())["error"].endswith("No space left on device")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["manifest.json"]
    before = (tmp_path / "manifest.json").read_text()
    with pytest.raises(OSError, match="No space left"):  # more than its blocks hold: refused, the old one intact
        write_manifest(tmp_path, {"notes": ["y" * 20_000]})
    assert (tmp_path / "manifest.json").read_text() == before and sorted(p.name for p in tmp_path.iterdir()) == ["manifest.json"]


def _disk_full_from(monkeypatch: pytest.MonkeyPatch, storage_cls: type, after: int) -> None:
    """From the ``after``-th call on, the storage's writes and every new file (the manifest's ``.part``) fail
    with ENOSPC, as on a full disk (a new file is left empty, as the kernel leaves it)."""
    import pathlib

    calls = [0]
    full = [False]
    write_many, write_text = storage_cls.write_many, pathlib.Path.write_text

    def failing_write_many(self, items, timestamp):
        calls[0] += 1
        if calls[0] >= after:
            full[0] = True
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return write_many(self, items, timestamp)

    def failing_write_text(self, *args, **kwargs):
        if full[0] and self.name.endswith(".part"):
            self.touch()
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(self))
        return write_text(self, *args, **kwargs)

    monkeypatch.setattr(storage_cls, "write_many", failing_write_many)
    monkeypatch.setattr(pathlib.Path, "write_text", failing_write_text)


def test_full_disk_finishes_the_manifest_with_the_error(tmp_path: Path, fmt: str, monkeypatch: pytest.MonkeyPatch) -> None:
    from seatwin.recording.storage import STORAGES

    w = RecordingWriter(tmp_path / "run", fmt, flush_interval_s=0.2, manifest_wall_s=0.0)
    _disk_full_from(monkeypatch, STORAGES[fmt], after=20)
    with pytest.raises(RecordingError, match="No space left on device") as e:
        for k in range(100):
            w.write_sweep("/lidar/points", "lidar", T0 + 0.1 * k, **sweep(k, n=100))
    assert str(e.value).startswith(str(w.bag))
    manifest = json.loads((tmp_path / "run" / "manifest.json").read_text())
    assert manifest["completed"] is False and "No space left on device" in manifest["error"]
    assert manifest["finished_utc"] is not None
    assert not (tmp_path / "run" / "manifest.json.part").exists()
    monkeypatch.undo()
    with open_bag(tmp_path / "run") as rec:
        assert rec.complete is False and len(list(rec.point_clouds())) >= 10


def test_simulate_on_a_full_disk_is_one_line_and_exit_2(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from seatwin.recording.storage import McapStorage

    _disk_full_from(monkeypatch, McapStorage, after=50)
    code = run(["simulate", "ferry_crossing", "--out", str(tmp_path / "r"), "--sensors", "lidar", "--duration", "10", "-q"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "No space left on device" in err and "Traceback" not in err
    assert err.startswith(f"seatwin: error: {tmp_path / 'r' / 'recording'}: recording stopped")
    manifest = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert manifest["completed"] is False and "No space left on device" in manifest["error"]
    assert not (tmp_path / "r" / "manifest.json.part").exists()


@pytest.mark.parametrize("framed", [True, False])
def test_a_frame_reaches_the_disk_whole(tmp_path: Path, framed: bool) -> None:
    """A flush falling due inside ``writer.frame()`` waits for its end: the bag's flushed prefix (what a
    SIGKILL leaves) ends at a frame boundary."""
    import contextlib

    w = RecordingWriter(tmp_path / "run", "sqlite3", flush_interval_s=0.05, flush_wall_s=1e9, manifest_wall_s=0.0)
    flushed_at: list[int] = []
    flush = w.storage.flush
    w.storage.flush = lambda: (flushed_at.append(sum(w.counts.values())), flush())[1]  # type: ignore[method-assign]
    for k in range(10):
        with w.frame() if framed else contextlib.nullcontext():
            for m in range(9):
                w.write_sweep(f"/cam{m}/points", "cam", T0 + 0.1 * k, **sweep(k, n=10))
    w.close()
    assert len(flushed_at) >= 8
    assert all(n % 9 == 0 for n in flushed_at) == framed, flushed_at
