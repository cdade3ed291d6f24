"""Fig. 5.10 input: a recording's sweep nearest a time, in world north/east; ``compare --clouds-at``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.recording import RecordingWriter, StaticTransform, VesselPose, mount_rotation
from seatwin.report.clouds import cloud_at

T0 = 1_600_000_000.0


def _recording(run_dir: Path, shift: float = 0.0) -> Path:
    """Ownship at (0, 0) heading north; lidar (FLU) sees a target 20 m ahead moving east, plus a fixed point."""
    with RecordingWriter(run_dir, "mcap", sensors={"lidar": {"model": "VLP-16"}}) as w:
        w.write_static_transforms(
            T0, [StaticTransform("milliAmpere/base_link_frd", "lidar", (0.0, 0.0, -2.0), mount_rotation("flu"))]
        )
        for k in range(30):
            t = T0 + 0.1 * k
            east = 0.2 * k
            w.write_ground_truth(
                t, [VesselPose("milliAmpere", 0.0, 0.0, 0.0, ownship=True), VesselPose("Havfruen", 20.0, east, 0.0, v_east=2.0)]
            )
            # a 3×3 m block of points at the target (sensor frame: x ahead, y left) and one at 10 m left
            g = np.linspace(-1.0, 1.0, 4)
            gx, gy = np.meshgrid(20.0 + g + shift, -east + g)
            x = np.append(gx.ravel(), 0.0)
            y = np.append(gy.ravel(), 10.0)
            n = len(x)
            w.write_sweep("/lidar/points", "lidar", t, x, y, np.full(n, 0.5), np.ones(n), np.zeros(n, np.uint16), np.zeros(n))
    return run_dir


def test_cloud_at_world_frame(tmp_path: Path) -> None:
    snap = cloud_at(_recording(tmp_path / "run"), T0 + 1.02)
    assert snap.time == pytest.approx(T0 + 1.0)
    assert snap.ownship == pytest.approx((0.0, 0.0))
    assert snap.targets == [("Havfruen", pytest.approx(20.0), pytest.approx(2.0))]
    assert snap.points[-1] == pytest.approx([0.0, -10.0])  # 10 m to the left of a north-facing sensor is west
    assert snap.points[:-1].mean(axis=0) == pytest.approx([20.0, 2.0])


@pytest.mark.slow
def test_compare_report_with_clouds(tmp_path: Path) -> None:
    real = _recording(tmp_path / "real")
    synt = _recording(tmp_path / "synt", shift=0.5)
    out = tmp_path / "rep"
    code = run(
        [
            "compare",
            "--real",
            str(real),
            "--synthetic",
            str(synt),
            "--truth",
            str(real),
            "--tuning",
            "real",
            "--report",
            str(out),
            "--clouds-at",
            "+1.5",
            "--map",
            "none",
            "--json",
            str(tmp_path / "c.json"),
        ]
    )
    assert code == 0
    assert "Point clouds at" in (out / "index.html").read_text()
    assert json.loads((tmp_path / "c.json").read_text())["targets"][0]["tuning"] == "real"


def test_clouds_need_recordings_and_report(tmp_path: Path, capsys) -> None:
    real = _recording(tmp_path / "real")
    assert run(["compare", "--real", str(real), "--synthetic", str(real), "--truth", str(real), "--clouds-at", "+1"]) == 2
    assert "--report" in capsys.readouterr().err
