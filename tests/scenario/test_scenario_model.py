"""Trajectory interpolation: heading unwrap across ±180°, velocity, yaw rate, span errors."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.scenario.model import Role, Scenario, Trajectory, Vessel


def test_heading_interpolates_across_the_wrap():
    # 170° → −170° (i.e. 190°): the midpoint is 180°, not 0°.
    tr = Trajectory([0.0, 1.0], [0.0, 0.0], [0.0, 0.0], np.radians([170.0, -170.0]))
    mid = np.degrees(tr.state_at(0.5).heading)
    assert abs(abs(mid) - 180.0) < 1e-9
    quarter = np.degrees(tr.state_at(0.25).heading)
    assert quarter == pytest.approx(175.0)
    assert np.degrees(tr.state_at(0.75).heading) == pytest.approx(-175.0)


def test_yaw_rate_across_the_wrap_is_small_and_signed():
    t = np.arange(0.0, 5.01, 0.1)
    heading = np.radians(170.0 + 4.0 * t)  # +4 °/s clockwise, crosses 180° at t = 2.5
    tr = Trajectory(t, np.zeros_like(t), np.zeros_like(t), heading)
    s = tr.state_at([1.0, 2.5, 2.55, 4.0])
    assert np.degrees(s.yaw_rate) == pytest.approx([4.0] * 4)
    assert np.all(np.abs(s.heading) <= np.pi)


def test_velocity_of_a_straight_constant_speed_track():
    t = np.arange(0.0, 10.01, 0.1)
    tr = Trajectory(t, 2.0 * t, -1.0 * t, np.full_like(t, np.arctan2(-1.0, 2.0)))
    s = tr.state_at([0.0, 3.33, 10.0])
    assert s.v_north == pytest.approx([2.0] * 3)
    assert s.v_east == pytest.approx([-1.0] * 3)
    assert s.speed == pytest.approx([np.hypot(2, 1)] * 3)
    assert s.north[1] == pytest.approx(6.66)
    assert s.yaw_rate == pytest.approx([0.0] * 3)


def test_state_outside_the_span_is_a_clear_error():
    tr = Trajectory([10.0, 11.0], [0.0, 1.0], [0.0, 0.0], [0.0, 0.0], source="x.csv (vessel 1)")
    with pytest.raises(InputError, match=r"x\.csv \(vessel 1\).*outside the trajectory's span \[10\.0, 11\.0\]"):
        tr.state_at(11.5)
    with pytest.raises(InputError, match="outside"):
        tr.state_at([10.5, 9.0])
    assert tr.state_at(11.0).north == pytest.approx(1.0)


def test_bad_trajectories_are_rejected():
    with pytest.raises(InputError, match="increase strictly"):
        Trajectory([0.0, 0.0], [0, 0], [0, 0], [0, 0])
    with pytest.raises(InputError, match="not finite"):
        Trajectory([0.0, 1.0], [0, np.nan], [0, 0], [0, 0])
    with pytest.raises(InputError, match="at least 2"):
        Trajectory([0.0], [0], [0], [0])


def test_scenario_span_and_roles():
    a = Trajectory([0.0, 10.0], [0, 10], [0, 0], [0, 0])
    b = Trajectory([2.0, 12.0], [0, 10], [5, 5], [0, 0])
    sc = Scenario("s", [Vessel("own", Role.OWNSHIP, a), Vessel("t", Role.TARGET, b)])
    assert (sc.start, sc.end, sc.duration) == (2.0, 10.0, 8.0)
    assert sc.ownship.name == "own" and [v.name for v in sc.targets] == ["t"]
    with pytest.raises(InputError, match="at most one ownship"):
        Scenario("s", [Vessel("a", Role.OWNSHIP, a), Vessel("b", Role.OWNSHIP, b)])
    with pytest.raises(InputError, match="no vessel named 'x'"):
        sc.vessel("x")
