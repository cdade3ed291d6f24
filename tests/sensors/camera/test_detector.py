"""The ``label`` detector (P_D by box size, box noise, seeded) and detections → world bearings → the fused tracker."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seatwin.geo import mount_matrix, yaw_matrix
from seatwin.sensors.camera import intrinsic_matrix
from seatwin.sensors.camera.detector import LabelDetectorConfig, detect, detection_bearings, detection_probability


def test_detection_probability_hand_values() -> None:
    cfg = LabelDetectorConfig(p_max=0.9, h50_px=10.0, slope_px=2.0)
    assert float(detection_probability(10.0, 1.0, cfg)) == pytest.approx(0.45)
    assert float(detection_probability(10.0, 0.5, cfg)) == pytest.approx(0.225)
    assert float(detection_probability(14.0, 1.0, cfg)) == pytest.approx(0.9 / (1 + math.exp(-2.0)))
    assert float(detection_probability(100.0, 0.0, cfg)) == 0.0
    p = detection_probability(np.arange(1, 60), 1.0, cfg)
    assert (np.diff(p) > 0).all()  # grows as boxes grow


def test_detector_rates_noise_and_seed() -> None:
    cfg = LabelDetectorConfig(min_confidence=0.0)
    big = [("A", 300.0, 200.0, 80.0, 40.0, 1.0)]
    small = [("B", 300.0, 200.0, 6.0, 3.0, 1.0)]
    hits_big = [detect(big, cfg, "/camera/front/labels", i, 612, 512) for i in range(400)]
    hits_small = [detect(small, cfg, "/camera/front/labels", i, 612, 512) for i in range(400)]
    rate_big = np.mean([len(h) for h in hits_big])
    rate_small = np.mean([len(h) for h in hits_small])
    p_big, p_small = float(detection_probability(40, 1, cfg)), float(detection_probability(3, 1, cfg))
    assert abs(rate_big - p_big) < 3 * math.sqrt(p_big * (1 - p_big) / 400) + 1e-9
    assert abs(rate_small - p_small) < 3 * math.sqrt(p_small * (1 - p_small) / 400)
    cx = np.array([d[0].center_x for d in hits_big if d])
    assert 0.5 < np.std(cx) < 8.0 and abs(np.mean(cx) - 300.0) < 1.0  # σ = 1 + 0.04 · 80 = 4.2 px
    again = [detect(big, cfg, "/camera/front/labels", i, 612, 512) for i in range(400)]
    assert again == hits_big  # same seed, camera and stamp → same draws
    other = [detect(big, cfg.with_(seed=1), "/camera/front/labels", i, 612, 512) for i in range(400)]
    assert other != hits_big


def test_detection_bearings_through_the_full_camera_model() -> None:
    k = intrinsic_matrix(612, 512, 82.0)
    for heading, az in ((0.0, 0.0), (0.7, 72.0), (-2.0, -72.0)):
        rot = yaw_matrix(heading) @ mount_matrix("optical", pitch=-math.radians(15), yaw=math.radians(az))
        b = detection_bearings([305.5], [255.5], k, None, rot)
        assert float(b[0]) == pytest.approx(math.remainder(heading + math.radians(az), 2 * math.pi))
    # a world point seen by a pitched camera: its pixel's bearing is the point's bearing, whatever its row
    rot = mount_matrix("optical", pitch=-math.radians(15))
    pts = np.array([[40.0, 12.0, 2.0], [40.0, 12.0, -6.0], [15.0, -9.0, 2.5]])
    opt = pts @ rot
    u = k[0, 0] * opt[:, 0] / opt[:, 2] + k[0, 2]
    v = k[1, 1] * opt[:, 1] / opt[:, 2] + k[1, 2]
    np.testing.assert_allclose(detection_bearings(u, v, k, None, rot), np.arctan2(pts[:, 1], pts[:, 0]), atol=1e-12)


@pytest.mark.slow
def test_fused_lidar_camera_tracking(tmp_path: Path) -> None:
    from seatwin.perception.from_recording import scans_from_recording
    from seatwin.pipeline.track import track_recording
    from seatwin.recording import open_bag
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sim.run import simulate_scenario

    sc = builtin_scenario("ferry_crossing")
    run = tmp_path / "run"
    simulate_scenario(sc, run, start=sc.start + 35.0, duration=6.0, progress=False, sensors=("lidar", "camera"))
    with open_bag(run) as rec:
        truth = rec.ground_truth()
        scans = [s for s in scans_from_recording(rec, ("camera",)).scans]
    assert len(scans) == 30 and all(s.sensor == "camera" and s.kind.name == "BEARING" for s in scans)
    # every camera bearing lies near a target's true bearing from the rig, or a moored boat's (they are labelled too)
    from seatwin.layout import moored_boat_positions

    moored = moored_boat_positions("default")
    errs, on_moored = [], 0
    for s in scans:
        for (b,) in s.z:
            targets = [
                math.atan2(np.interp(s.time, v.time, v.east) - s.sensor_east, np.interp(s.time, v.time, v.north) - s.sensor_north)
                for v in truth.values()
                if not v.ownship
            ]
            boats = [math.atan2(e - s.sensor_east, n - s.sensor_north) for n, e in moored]
            err = [abs(math.remainder(b - x, 2 * math.pi)) for x in targets + boats]
            errs.append(min(err))
            on_moored += int(np.argmin(err) >= len(targets))
    assert errs and np.degrees(np.median(errs)) < 2.0 and 0 < on_moored < len(errs)
    res = track_recording(run, sensors=("lidar", "camera"), tuning="synthetic")
    assert res.sensors == ("lidar", "camera") and res.n_confirmed >= 1
