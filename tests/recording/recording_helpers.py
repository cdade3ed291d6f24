"""Helpers for the recording tests: small synthetic sweeps and a populated run."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from seatwin.geo import GeodeticOrigin
from seatwin.recording import RecordingWriter, StaticTransform, VesselPose, mount_rotation
from seatwin.rng import frame_rng

T0 = 1_600_000_000.25
ORIGIN = GeodeticOrigin(63.4305, 10.3951, 0.0)


def sweep(k: int, n: int = 300) -> dict[str, np.ndarray]:
    rng = frame_rng(0, "test/sweep", k)
    return {
        "x": rng.normal(size=n).astype(np.float32),
        "y": rng.normal(size=n).astype(np.float32),
        "z": rng.normal(size=n).astype(np.float32),
        "intensity": rng.random(n).astype(np.float32),
        "ring": rng.integers(0, 16, n).astype(np.uint16),
        "time": (rng.random(n) * 0.1).astype(np.float32),
    }


def vessels(k: int) -> list[VesselPose]:
    return [
        VesselPose("milliAmpere", 1.0 + k, 2.0, 0.5, v_north=1.5, v_east=-0.5, yaw_rate=0.01, ownship=True),
        VesselPose("Havfruen", -30.0, 40.0 + 0.5 * k, -2.0, v_east=5.0),
    ]


def write_run(run_dir: Path, fmt: str, n_sweeps: int = 5, **kwargs) -> RecordingWriter:
    """A complete small run: /tf_static, lidar sweeps, ground truth, an image and radar plots per step."""
    with RecordingWriter(run_dir, fmt, origin=ORIGIN, seed=7, sensors={"lidar": {"model": "VLP-16"}}, **kwargs) as w:
        w.write_static_transforms(
            T0, [StaticTransform("milliAmpere/base_link_frd", "lidar", (0.5, 0.0, -2.0), mount_rotation("flu"))]
        )
        for k in range(n_sweeps):
            t = T0 + 0.1 * k
            w.write_sweep("/lidar/points", "lidar", t, **sweep(k))
            w.write_ground_truth(t, vessels(k))
            img = np.full((6, 8, 3), k, np.uint8)
            img[0, 0] = (1, 2, 3)
            w.write_image("/camera/image_raw", "camera", t, img, "bgr8")
            w.write_radar("/radar/detections", "radar", t, [10.0, 0.0], [0.0, -20.0], intensity=[1.0, 2.0])
    return w
