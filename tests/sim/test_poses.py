"""Vessel poses from a scenario: one instant, or a whole run at once (vectorised, the ownship's WGS-84 included)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seatwin.geo import GeodeticOrigin
from seatwin.recording import RecordingWriter, open_bag
from seatwin.recording.messages import vessel_llh
from seatwin.scenario import Role, Scenario, Trajectory, Vessel
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sim import GroundTruthSensor
from seatwin.sim.poses import PoseTable, poses_from_scenario

T0 = 1_600_000_000.25
ORIGIN = GeodeticOrigin(63.4305, 10.3951, 0.0)


def _scenario() -> Scenario:
    t = T0 + np.arange(11) * 0.1
    return Scenario(
        "s",
        [
            Vessel("own", Role.OWNSHIP, Trajectory(t, np.zeros(11), np.arange(11) * 0.2, np.full(11, math.pi / 2))),
            Vessel("tgt", Role.TARGET, Trajectory(t, 50 + np.arange(11) * 0.5, np.zeros(11), np.zeros(11))),
        ],
        origin=ORIGIN,
    )


def test_poses_from_scenario_feed_the_writer(tmp_path: Path) -> None:
    sc = _scenario()
    t = sc.vessels[0].trajectory.time
    poses = poses_from_scenario(sc, T0 + 0.5)
    assert [p.name for p in poses] == ["own", "tgt"] and poses[0].ownship and not poses[1].ownship
    assert poses[0].v_east == pytest.approx(2.0) and poses[1].north == pytest.approx(52.5)
    with RecordingWriter(tmp_path / "run", origin=sc.origin) as w:
        for k in range(11):
            w.write_ground_truth(t[k], poses_from_scenario(sc, t[k]))
    with open_bag(tmp_path / "run") as rec:
        truth = rec.ground_truth()
        odom = next(iter(rec.messages("/ground_truth/own/odom"))).msg
    assert odom.twist.twist.linear.x == pytest.approx(2.0)  # heading east, moving east: all surge
    assert odom.twist.twist.linear.y == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(truth["own"].v_east, 2.0, rtol=1e-5)
    np.testing.assert_allclose(truth["tgt"].v_north, 5.0, rtol=1e-5)


def test_pose_table_equals_step_by_step() -> None:
    """The whole run at once gives each step's poses; the ownship's LLH equals the per-step exact
    conversion the NavSatFix did before, to float rounding."""
    sc = builtin_scenario("ferry_crossing")
    times = sc.start + np.arange(600) * 0.1 + 0.03
    table = PoseTable.from_scenario(sc, times)
    for k in range(0, 600, 7):
        got, want = table.poses(k), poses_from_scenario(sc, float(times[k]))
        assert [(p.name, p.north, p.east, p.heading, p.v_north, p.v_east, p.yaw_rate, p.ownship) for p in got] == [
            (p.name, p.north, p.east, p.heading, p.v_north, p.v_east, p.yaw_rate, p.ownship) for p in want
        ]
        for p, q in zip(got, want):
            if q.ownship:
                np.testing.assert_allclose(p.llh, vessel_llh(q, sc.origin), rtol=0, atol=1e-12)
            else:
                assert p.llh is None


def test_ground_truth_sensor_uses_its_table() -> None:
    sc = _scenario()
    gt = GroundTruthSensor(sc, rate_hz=10.0)
    times = gt.frame_times(T0, T0 + 1.0)
    assert len(times) == 10
    poses = gt.capture(float(times[3]), 3)
    assert poses[0].llh is not None and poses[1].llh is None
    assert poses[0].east == pytest.approx(0.6)
    off = gt.capture(T0 + 0.55, 3)  # not the table's frame 3: computed alone
    assert off[0].llh is None and off[0].east == pytest.approx(1.1)
