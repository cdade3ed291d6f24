"""Lock-step's growing samples: the state a Trajectory of the same samples gives, and its ground truth."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.api.live import LiveGroundTruth, LiveTracks
from seatwin.geo import GeodeticOrigin
from seatwin.geo.geodetic import ned_to_llh_wgs84
from seatwin.scenario import Role, Scenario, Trajectory, Vessel


def _samples(n: int, start: float = 1.6e9, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    t = start + np.cumsum(rng.uniform(0.05, 0.15, n))  # uneven steps
    poses = np.cumsum(rng.normal(0.0, 1.0, (n, 3, 3)), axis=0)
    poses[:, :, 2] = rng.uniform(-4.0, 4.0, (n, 3))  # headings jumping across ±π (unwrapped by both)
    return t, poses


def _filled(t: np.ndarray, poses: np.ndarray) -> LiveTracks:
    tracks = LiveTracks(poses.shape[1], capacity=4)  # grows three times
    for k in range(len(t)):
        tracks.append(float(t[k]), poses[k, :, 0], poses[k, :, 1], poses[k, :, 2])
    return tracks


def test_state_is_the_trajectorys_bit_for_bit() -> None:
    t, poses = _samples(40)
    tracks = _filled(t, poses)
    query = np.concatenate([t, 0.5 * (t[1:] + t[:-1]), [t[0] + 1e-7, t[-1]]])
    got = tracks.state(query)
    for i in range(3):
        ref = Trajectory(t, poses[:, i, 0], poses[:, i, 1], poses[:, i, 2]).state_at(query)
        for c, name in enumerate(("north", "east", "heading", "v_north", "v_east", "yaw_rate")):
            assert np.array_equal(got[i, c], getattr(ref, name)), name
    assert np.array_equal(tracks.trajectory(1).heading, Trajectory(t, poses[:, 1, 0], poses[:, 1, 1], poses[:, 1, 2]).heading)


def test_state_follows_each_step_and_views_stay_valid() -> None:
    t, poses = _samples(12, start=0.0, seed=3)
    tracks = LiveTracks(3, capacity=2)
    windows = []
    for k in range(len(t)):
        tracks.append(float(t[k]), poses[k, :, 0], poses[k, :, 1], poses[k, :, 2])
        if k >= 2:
            # the sample before the newest has its central difference as soon as the newest is in
            ref = Trajectory(t[: k + 1], poses[: k + 1, 0, 0], poses[: k + 1, 0, 1], poses[: k + 1, 0, 2])
            mid = 0.5 * (t[k - 2] + t[k - 1])
            np.testing.assert_allclose(tracks.state(mid)[0, :, 0], np.array(_row(ref, mid)), rtol=0, atol=1e-12)
            windows.append((k, tracks.window(0, k - 2)))
    for k, w in windows:  # views handed out before a growth still hold their samples
        assert np.array_equal(w.time, t[k - 2 : k + 1]) and np.array_equal(w.north, poses[k - 2 : k + 1, 0, 0])
    with pytest.raises(Exception, match="outside"):
        windows[0][1].state_at(t[-1])


def _row(traj: Trajectory, t: float) -> list[float]:
    s = traj.state_at(t)
    return [float(getattr(s, f)) for f in ("north", "east", "heading", "v_north", "v_east", "yaw_rate")]


def test_first_sample_velocity_is_one_sided() -> None:
    tracks = LiveTracks(1)
    tracks.append(10.0, np.array([0.0]), np.array([0.0]), np.array([0.0]))
    tracks.append(10.5, np.array([1.0]), np.array([-2.0]), np.array([0.1]))
    tracks.append(11.0, np.array([3.0]), np.array([-2.0]), np.array([0.1]))
    s = tracks.state(10.0)[0, :, 0]
    assert s[3:].tolist() == pytest.approx([2.0, -4.0, 0.2])  # (x1 − x0) / (t1 − t0), as numpy.gradient at an end
    assert tracks.state(10.5)[0, 3, 0] == pytest.approx(3.0)  # central there


def test_ground_truth_poses_and_navsatfix() -> None:
    origin = GeodeticOrigin(63.4336, 10.3926, 0.0)
    t, poses = _samples(5)
    tracks = _filled(t, poses)
    placeholder = Trajectory(np.array([0.0, 1.0]), np.zeros(2), np.zeros(2), np.zeros(2))
    roles = (Role.TARGET, Role.OWNSHIP, Role.TARGET)
    sc = Scenario("s", [Vessel(f"v{i}", r, placeholder) for i, r in enumerate(roles)], origin=origin)
    gt = LiveGroundTruth(sc, tracks, 10.0, origin)
    when = float(t[2])
    out = gt.capture(when, 0)
    assert [p.name for p in out] == ["v0", "v1", "v2"] and [p.ownship for p in out] == [False, True, False]
    assert out[0].llh is None and out[2].llh is None
    assert out[1].north == poses[2, 1, 0] and out[1].heading == pytest.approx(math.remainder(poses[2, 1, 2], 2 * math.pi))
    lat, lon, h = ned_to_llh_wgs84(np.array([out[1].north]), np.array([out[1].east]), np.zeros(1), origin)
    assert out[1].llh == (lat[0], lon[0], h[0])


EDGE_HEADINGS = [-math.pi, math.pi, 0.0, -0.0, 3.0, -3.0, 7.0, -1e3, 1e-300]
"""Headings on ±π, near it, several turns off, signed zeros."""


@settings(max_examples=40, deadline=None)
@given(
    steps=st.lists(st.floats(0.001, 2.0), min_size=2, max_size=40),
    headings=st.lists(st.sampled_from(EDGE_HEADINGS) | st.floats(-20, 20), min_size=41),
    reads=st.lists(st.booleans(), min_size=41),
    capacity=st.integers(1, 8),
)
def test_samples_are_the_trajectorys_whenever_they_are_read(
    steps: list[float], headings: list[float], reads: list[bool], capacity: int
) -> None:
    """Reads between appends (the arrays written then) or none until the end: the same bits as a Trajectory
    of the samples (headings on ±π, across it, far off; uneven steps; growths)."""
    t = 1.6e9 + np.cumsum([0.0, *steps])
    n = len(t)
    north, east, heading = np.cos(t - t[0]) * 50.0, np.sin(3.0 * (t - t[0])), np.array(headings[:n])
    tracks = LiveTracks(1, capacity=capacity)
    for k in range(n):
        tracks.append(float(t[k]), north[k : k + 1], east[k : k + 1], heading[k : k + 1])
        assert tracks.sample_time(-1) == t[k] and tracks.n == k + 1
        if reads[k] and k >= 1:
            tracks.state_rows(float(t[k]))
    query = np.concatenate([t, 0.5 * (t[1:] + t[:-1])])
    ref = Trajectory(t, north, east, heading).state_at(query)
    got = tracks.state(query)
    for c, name in enumerate(("north", "east", "heading", "v_north", "v_east", "yaw_rate")):
        assert np.array_equal(got[0, c], getattr(ref, name)), name
        assert [tracks.state_rows(float(q))[0][c] for q in query] == got[0, c].tolist(), name
    assert np.array_equal(tracks.trajectory(0).heading, Trajectory(t, north, east, heading).heading)
    assert tracks.last(0)[:2] == (north[-1], east[-1])
