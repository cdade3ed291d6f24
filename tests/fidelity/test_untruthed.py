"""The don't-care rule recognises a vessel without truth by sustained motion, not extent (issue 21): a
clutter track that jumps between quay features or jitters in place is not a vessel; a boat is, even
with a jump."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.evaluation.tracks_io import Tracks
from seatwin.fidelity.joyride import AWAY_M, VESSEL_MIN_DISPLACEMENT_M, JoyrideData, sustained_motion, untruthed_vessels


def _jumpy_clutter(n: int = 120, seed: int = 0) -> np.ndarray:
    """(n, 2) a clutter track on a quay: jitter of 3 m about one spot, two single-scan jumps of 150 m and
    160 m to other features (raw extent ~220 m) where it stays."""
    rng = np.random.default_rng(seed)
    spot = np.zeros((n, 2))
    spot[n // 3 :] += [150.0, 0.0]
    spot[2 * n // 3 :] += [0.0, 160.0]
    return spot + rng.normal(0.0, 3.0, (n, 2))


def _sawtooth(n: int = 120) -> np.ndarray:
    """Clutter that drifts 40 m along a quay at 2 m/s, jumps back to its start, and again (a track handed
    along a row of moored boats): 240 m of bounded steps, yet it never gets more than 40 m away."""
    return np.column_stack([2.0 * (np.arange(n) % 20), np.zeros(n)])


def _quay(n: int = 120, seed: int = 1) -> np.ndarray:
    """A stationary quay track with 4 m of jitter (its path length grows ~5 m a scan; it goes nowhere)."""
    return np.random.default_rng(seed).normal(0.0, 4.0, (n, 2))


def _boat(n: int = 120, speed: float = 3.0, jump_at: int | None = None, seed: int = 2) -> np.ndarray:
    rng = np.random.default_rng(seed)
    p = np.column_stack([speed * np.arange(n), 20.0 * np.sin(np.arange(n) / 30.0)]) + rng.normal(0.0, 1.5, (n, 2))
    if jump_at is not None:
        p[jump_at:] += [0.0, 120.0]
    return p


def test_sustained_motion_ignores_jumps_and_jitter() -> None:
    t = np.arange(120, dtype=float)
    clutter = _jumpy_clutter()
    extent = np.hypot(*(clutter - clutter[0]).T).max()
    assert extent > 200.0  # the old 200 m extent test would call it a vessel
    assert sustained_motion(t, *clutter.T) < 30.0
    assert sustained_motion(t, *_quay().T) < 30.0
    assert sustained_motion(t, *_sawtooth().T) == pytest.approx(38.0)
    boat = _boat()
    assert sustained_motion(t, *boat.T) == pytest.approx(np.hypot(*(boat - boat[0]).T).max(), abs=1e-9)
    assert sustained_motion(t, *_boat(jump_at=60).T) > 300.0  # a boat whose track jumps once still moved
    # the bound on a step scales with Δt: 20 m in 1 s is motion, 60 m in 1 s a jump, 60 m in 4 s motion
    assert sustained_motion(np.array([0.0, 1.0]), np.array([0.0, 20.0]), np.zeros(2)) == 20.0
    assert sustained_motion(np.array([0.0, 1.0]), np.array([0.0, 60.0]), np.zeros(2)) == 0.0
    assert sustained_motion(np.array([0.0, 4.0]), np.array([0.0, 60.0]), np.zeros(2)) == 60.0
    assert sustained_motion(np.array([5.0]), np.array([1.0]), np.array([2.0])) == 0.0


def _tracks(paths: list[np.ndarray], t: np.ndarray) -> Tracks:
    rows = [(ti, k + 1, *p) for k, path in enumerate(paths) for ti, p in zip(t, path, strict=True)]
    rows.sort()
    time, ids, north, east = (np.array(c) for c in zip(*rows, strict=True))
    state = np.column_stack([north, np.zeros(len(rows)), east, np.zeros(len(rows))])
    return Tracks(time, ids, np.full(len(rows), 0.9), state, np.tile(np.eye(4), (len(rows), 1, 1)), np.ones(len(rows), bool))


def test_the_rule_accepts_boats_and_not_jumpy_or_stationary_clutter() -> None:
    t = 100.0 + np.arange(120, dtype=float)
    data = JoyrideData(t, [np.empty((0, 2))] * len(t), np.full((len(t), 4), AWAY_M), np.zeros((len(t), 4)))
    tracks = _tracks([_jumpy_clutter(), _quay(), _sawtooth(), _boat(), _boat(jump_at=60, seed=3)], t)
    vessels = untruthed_vessels(tracks, data, gate_m=60.0)
    assert len(vessels) == 2
    starts = sorted(round(float(v[0, 3])) for v in vessels.values())  # east of each accepted track's first row
    assert starts == sorted([round(_boat()[0, 1]), round(_boat(jump_at=60, seed=3)[0, 1])])
    slow = _tracks([_boat(speed=VESSEL_MIN_DISPLACEMENT_M / 130.0)], t)  # gets ~180 m: not far enough
    assert untruthed_vessels(slow, data, gate_m=60.0) == {}


@pytest.mark.slow
def test_on_a_ravnkloa_recording_no_track_is_on_land_and_no_clutter_is_a_vessel(shared_data, tmp_path) -> None:
    import dataclasses

    from seatwin.perception.datasets import import_ravnkloa_radar
    from seatwin.pipeline import track_recording
    from seatwin.pipeline.track import recording_mask

    folder = shared_data / "ravnkloa"
    csv = folder / "radar-2023" / "2023-08-26-11-59-55.csv"  # main's tracker: 2 tracks partly on land, a jumpy "vessel"
    run = tmp_path / "rv"
    import_ravnkloa_radar(csv, run, "mcap", map_path=str(folder / "ravnkloa_radar_base_map.yaml"))
    mask = recording_mask(run)
    for tuning in ("ravnkloa", "joyride"):
        tracks = track_recording(run, tuning=tuning).tracks
        conf = tracks.confirmed
        assert conf.any()
        for k in np.unique(tracks.track_id[conf]):
            s = tracks.state[conf & (tracks.track_id == k)]
            assert (~mask.is_water(s[:, 0], s[:, 2])).mean() <= 0.2, (tuning, k)
            assert np.hypot(s[:, 1], s[:, 3]).max() < 2 * 10.0
        t = np.unique(tracks.time)
        data = JoyrideData(t, [np.empty((0, 2))] * len(t), np.full((len(t), 4), AWAY_M), np.zeros((len(t), 4)))
        assert untruthed_vessels(tracks, data, gate_m=60.0) == {}
        state = tracks.state.copy()  # every track jumps 150 m once, half-way through: still no vessel
        for k in np.unique(tracks.track_id[conf]):
            rows = np.flatnonzero(conf & (tracks.track_id == k))
            state[rows[len(rows) // 2 :], 2] += 150.0
        assert untruthed_vessels(dataclasses.replace(tracks, state=state), data, gate_m=60.0) == {}
