"""Ctrl-C and SIGTERM stop a run the same way, never in the middle of a frame; its bag opens in standard readers."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from seatwin.interrupts import Interrupted, deferred_interrupts, interrupts_raise, interrupts_set_event
from seatwin.recording import open_bag
from seatwin.recording.storage import bag_path
from seatwin.sim.loop import simulate

T0 = 1.6e9


class _FrameOfNine:
    """A sensor whose frame is nine messages on nine topics; ``signal_at`` (frame, message): SIGTERM to this process
    there, in the middle of recording the frame."""

    name = "nine"

    def __init__(self, signal_at: tuple[int, int] | None, signum: int = signal.SIGTERM) -> None:
        self.signal_at, self.signum = signal_at, signum

    def frame_times(self, t0: float, t1: float) -> np.ndarray:
        return np.arange(t0, t1, 0.1)[: int(round((t1 - t0) / 0.1))]

    def static_transforms(self, topics: object) -> list:
        return []

    def parameters(self) -> dict:
        return {"kind": "test"}

    def capture(self, t: float, frame: int) -> int:
        return frame

    def record(self, writer, t: float, frame: int) -> None:
        for m in range(9):
            if self.signal_at == (frame, m):
                os.kill(os.getpid(), self.signum)
            z = np.zeros(3)
            writer.write_sweep(f"/cam{m}/points", "cam", t, z, z, z, z, z.astype(np.uint16), z)


@pytest.mark.parametrize("fmt", ["mcap", "sqlite3", "ros1"])
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_inside_a_frame_takes_effect_after_it(tmp_path: Path, fmt: str, signum: int, standard_readers) -> None:
    result = simulate([_FrameOfNine((3, 4), signum)], tmp_path / "r", T0, T0 + 1.0, fmt=fmt, progress=False)
    assert not result.completed and result.frames == {"nine": 4}  # frames 0..3 whole, none after
    manifest = json.loads((tmp_path / "r" / "manifest.json").read_text())
    label = "SIGTERM" if signum == signal.SIGTERM else "Ctrl-C"
    assert manifest["completed"] is False and manifest["error"] == f"interrupted ({label})"
    with open_bag(tmp_path / "r") as bag:
        assert not bag.recovered  # finished: index, footer, metadata.yaml
        counts = {t: i.count for t, i in bag.topics.items() if t.startswith("/cam")}
    assert counts == {f"/cam{m}/points": 4 for m in range(9)}
    assert standard_readers(bag_path(tmp_path / "r", fmt)) == 4 * 9 + 1


def test_deferred_blocks_nest_and_discard(tmp_path: Path) -> None:
    with interrupts_raise():
        with pytest.raises(Interrupted, match="SIGTERM"), deferred_interrupts():
            with deferred_interrupts():
                os.kill(os.getpid(), signal.SIGTERM)
            reached = True  # the inner block's end does not raise: the outer one is still open
        assert reached
        with deferred_interrupts(discard=True):
            os.kill(os.getpid(), signal.SIGINT)
        with pytest.raises(Interrupted, match="Ctrl-C"):
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1)
    with interrupts_set_event() as stop:
        os.kill(os.getpid(), signal.SIGTERM)
        assert stop.wait(5) and stop.signum == signal.SIGTERM


def _seatwin(*args: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", "from seatwin.cli.main import main; main()", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def _wait_for_messages(run_dir: Path, proc: subprocess.Popen, timeout_s: float = 120.0) -> None:
    """Until the manifest counts a flushed camera frame (bounded)."""
    for _ in range(int(timeout_s / 0.1)):
        assert proc.poll() is None, proc.communicate()
        try:
            topics = json.loads((run_dir / "manifest.json").read_text())["topics"]
        except (OSError, ValueError, KeyError):
            topics = {}
        if topics.get("/camera/front/image_raw", {}).get("count", 0) >= 2:
            return
        time.sleep(0.1)
    raise AssertionError("the run recorded no camera frame in time")


@pytest.mark.slow
@pytest.mark.parametrize("fmt", ["mcap", "sqlite3", "ros1"])
def test_simulate_process_finishes_the_bag_on_sigterm(tmp_path: Path, fmt: str, standard_readers) -> None:
    run_dir = tmp_path / "r"
    proc = _seatwin("simulate", "ferry_crossing", "--out", str(run_dir), "--sensors", "lidar,camera", "--format", fmt, "-q")
    try:
        _wait_for_messages(run_dir, proc)
    finally:
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "INCOMPLETE (interrupted)" in out and "Traceback" not in err
    manifest = json.loads((run_dir / "manifest.json").read_text())
    assert manifest["completed"] is False and manifest["error"] == "interrupted (SIGTERM)"
    cams = {t: v["count"] for t, v in manifest["topics"].items() if t.startswith("/camera/")}
    # every camera frame set whole: 3 cameras × (image, camera_info, labels, annotations)
    assert len(cams) == 12 and len(set(cams.values())) == 1, cams
    with open_bag(run_dir) as bag:
        assert not bag.recovered
        assert {t: i.count for t, i in bag.topics.items()} == {t: v["count"] for t, v in manifest["topics"].items()}
    assert standard_readers(bag_path(run_dir, fmt)) == manifest["message_count"]


def test_a_library_replacing_the_sigterm_handler_is_undone() -> None:
    """``ray.init`` installs a SIGTERM handler that exits at once; the campaign engine puts seatwin's back."""
    import sys

    from seatwin.interrupts import sigterm_kept

    with interrupts_raise():
        with sigterm_kept():
            signal.signal(signal.SIGTERM, lambda *_: sys.exit(signal.SIGTERM))  # what ray.init does
        with pytest.raises(Interrupted, match="SIGTERM"):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(1)
