"""The path/speed-profile builder of the built-ins."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.scenario.motion import Path, SpeedProfile, follow


def test_path_lines_and_arcs_end_where_geometry_says():
    p = Path(0.0, 0.0, 0.0).line(10.0).arc(10.0, 90.0).line(5.0)
    n, e, h = p.end_pose()
    assert (n, e, np.degrees(h)) == pytest.approx((20.0, 15.0, 90.0))
    assert p.length == pytest.approx(15.0 + 10.0 * np.pi / 2)
    # Port turn (negative angle) from north ends heading west.
    n, e, h = Path(0.0, 0.0, 0.0).arc(5.0, -90.0).end_pose()
    assert (n, e, np.degrees(h)) == pytest.approx((5.0, -5.0, -90.0))


def test_jog_shifts_sideways_and_keeps_heading():
    n, e, h = Path(0.0, 0.0, 0.0).jog(12.0, 10.0, 30.0).end_pose()
    assert e == pytest.approx(12.0)
    assert h == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(ValueError):
        Path(0.0, 0.0, 0.0).jog(1.0, 10.0, 30.0)


def test_heading_along_the_path_matches_the_direction_of_motion():
    p = Path(0.0, 0.0, 1.0).line(5.0).arc(8.0, 120.0).line(5.0).turn_to(-45.0, 6.0).line(3.0)
    s = np.linspace(0.0, p.length, 4001)
    n, e, h = p.at(s)
    direction = np.arctan2(np.gradient(e, s), np.gradient(n, s))
    err = np.angle(np.exp(1j * (direction - h)))
    assert np.abs(err).max() < 1e-2
    assert np.degrees(p.end_pose()[2]) == pytest.approx(-45.0)


def test_speed_profile_ramps_and_distance():
    sp = SpeedProfile(((0.0, 0.0), (8.0, 1.8), (60.0, 1.8), (68.0, 0.0)))
    assert sp.speed([0.0, 4.0, 8.0, 30.0, 68.0, 100.0]) == pytest.approx([0.0, 0.9, 1.8, 1.8, 0.0, 0.0])
    t = np.linspace(0.0, 80.0, 160001)
    assert sp.distance(80.0) == pytest.approx(np.trapezoid(sp.speed(t), t), rel=1e-9)
    assert sp.distance(80.0) == pytest.approx(0.9 * 8 + 1.8 * 52 + 0.9 * 8)
    assert SpeedProfile(((5.0, 1.0),)).distance([0.0, 5.0, 10.0]) == pytest.approx([0.0, 5.0, 10.0])


def test_follow_samples_at_the_rate_and_refuses_a_short_path():
    tr = follow(Path(0.0, 0.0, 0.0).line(100.0), SpeedProfile.constant(2.0), 1000.0, 10.0)
    assert len(tr.time) == 101 and tr.rate_hz == pytest.approx(10.0)
    assert tr.north[-1] == pytest.approx(20.0)
    with pytest.raises(ValueError, match="path is"):
        follow(Path(0.0, 0.0, 0.0).line(10.0), SpeedProfile.constant(2.0), 0.0, 10.0)
