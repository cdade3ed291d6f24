"""Two boats closer together than a track's exclusion gate both get confirmed tracks (issue 21, Scenario6:
Finn and Havfruen sail 17–24 m apart). The thesis's rule (``real-thesis``, ``init_association_max`` null) lets
no measurement inside a track's exclusion gate start a track, so the boat that appears second never gets one."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.perception import MeasurementKind
from seatwin.perception.measurements import Scan
from seatwin.tracking import JIPDATracker, load_tuning
from seatwin.tracking.gnn import GNNTracker


def _boat_a(t: float) -> np.ndarray:
    """Boat A: 50 m north of the radar, sailing east at 1.5 m/s (from 30 m west)."""
    return np.array([50.0, -30.0 + 1.5 * t])


def _two_boats(separation: float, seed: int, n: int = 40, second_from: int = 10) -> list[Scan]:
    """Radar range/bearing plots (σ 1 m) of boat A from the first scan and of boat B, ``separation`` metres north of
    A (farther from the radar) on the same course, from scan ``second_from`` on; 1 s scans."""
    rng = np.random.default_rng(seed)
    scans = []
    for k in range(n):
        a = _boat_a(k)
        boats = [a] if k < second_from else [a, a + [separation, 0.0]]
        pos = np.array(boats) + rng.normal(0.0, 1.0, (len(boats), 2))
        z = np.column_stack([np.hypot(pos[:, 0], pos[:, 1]), np.arctan2(pos[:, 1], pos[:, 0])])
        scans.append(Scan(float(k), "radar", MeasurementKind.RANGE_BEARING, z))
    return scans


def _confirmed_on(tab, boat: np.ndarray, t: float) -> set[int]:  # noqa: ANN001
    """Confirmed tracks within 5 m of ``boat`` at time ``t``."""
    m = tab.confirmed & (tab.time == t)
    d = np.hypot(tab.x[m, 0] - boat[0], tab.x[m, 2] - boat[1])
    return {int(k) for k in tab.track_id[m][d < 5.0]}


@pytest.mark.parametrize("tracker", [JIPDATracker, GNNTracker])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_two_boats_20_m_apart_both_get_confirmed_tracks(tracker, seed: int) -> None:  # noqa: ANN001
    scans = _two_boats(20.0, seed)
    tab = tracker(load_tuning("real")).run(scans)
    t = scans[-1].time
    a = _boat_a(t)
    on_a, on_b = _confirmed_on(tab, a, t), _confirmed_on(tab, a + [20.0, 0.0], t)
    assert on_a and on_b and not on_a & on_b
    # The second boat's plots lie inside the first track's exclusion gate: the thesis's rule gives it no track.
    thesis = tracker(load_tuning("real-thesis")).run(scans)
    assert not _confirmed_on(thesis, a + [20.0, 0.0], t)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_one_boat_starts_no_duplicate_track(seed: int) -> None:
    """A track's own detections, alone in its gate, are explained: one boat, one track."""
    scans = _two_boats(20.0, seed, second_from=10**6)
    tab = JIPDATracker(load_tuning("real")).run(scans)
    assert len(np.unique(tab.track_id)) == 1 and tab.confirmed[-1]


def test_thesis_rule_is_the_exclusion_gate_alone() -> None:
    assert load_tuning("real-thesis").init_association_max is None
    assert load_tuning("real").init_association_max == 0.5


def test_a_track_born_inside_another_tracks_gate_starts_with_less_existence() -> None:
    """Births are weighted by the probability that neither plot is an existing track's: 1 far from every track (the
    thesis's initial existence), below it for the second boat's first track."""
    cfg = load_tuning("real")
    tab = JIPDATracker(cfg).run(_two_boats(20.0, 1))
    first = {int(k): float(r) for k, r in zip(tab.track_id[::-1], tab.existence[::-1])}  # each track's first row
    assert first[1] == cfg.initial_existence
    assert len(first) >= 2 and all(0.0 < r < cfg.initial_existence for k, r in first.items() if k != 1)
