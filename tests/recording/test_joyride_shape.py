"""The writer API carries a real radar dataset (joyride: plots per scan in world NED + GNSS truth)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seatwin.recording import RecordingWriter, VesselPose, open_bag


@pytest.mark.shared_data
def test_joyride_scans_and_truth_round_trip(shared_data: Path, tmp_path: Path) -> None:
    from scipy.io import loadmat

    m = loadmat(shared_data / "joyride" / "joyride.mat")
    times = m["time"].ravel()
    scans = [np.asarray(z, float).reshape(-1, 2) for z in m["measurements"].ravel()]
    scans = [z[np.isfinite(z).all(axis=1)] for z in scans]

    def pose(name: str, row: np.ndarray, own: bool) -> VesselPose:
        n, vn, e, ve = row
        return VesselPose(name, n, e, math.atan2(ve, vn), v_north=vn, v_east=ve, ownship=own)

    with RecordingWriter(tmp_path / "run", "mcap", metadata={"source": "joyride.mat", "heading": "course over ground"}) as w:
        for t, z, tgt, own in zip(times, scans, m["target"], m["telemetron"]):
            w.write_radar("/radar/detections", "world_ned", t, z[:, 0], z[:, 1], origin=(own[0], own[2]))
            w.write_ground_truth(t, [pose("Telemetron", own, True), pose("target", tgt, False)])

    with open_bag(tmp_path / "run") as rec:
        got = list(rec.radar_scans())
        truth = rec.ground_truth()
    assert len(got) == len(times) == 238
    assert sum(s.points.size for s in got) == sum(len(z) for z in scans) == 432
    for s, z, t in zip(got, scans, times):
        np.testing.assert_allclose(s.points["x"], z[:, 0], atol=1e-3)  # float32 at ~7 km: < 1 mm
        np.testing.assert_allclose(s.points["y"], z[:, 1], atol=1e-3)
        assert s.stamp == pytest.approx(t, abs=1e-6)
    np.testing.assert_allclose(truth["target"].north, m["target"][:, 0])
    np.testing.assert_allclose(truth["target"].v_east, m["target"][:, 3], atol=1e-9)
    assert truth["Telemetron"].ownship
