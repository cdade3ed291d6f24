"""Tracks of a harbour's moored boats (real, no ground truth) are don't-care, not false tracks (issue 21)."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.evaluation import evaluate, stationary_truth
from seatwin.layout import moored_boat_positions
from seatwin.pipeline.evaluate import evaluate_run

from .conftest import make_tracks, make_truth

T = np.arange(0.0, 11.0)


def _rows(track_id: int, north: np.ndarray, east: np.ndarray) -> list[tuple[float, int, float, float]]:
    return [(float(t), track_id, float(n), float(e)) for t, n, e in zip(T, north, east)]


def _three_tracks(moored: np.ndarray) -> list[tuple[float, int, float, float]]:
    """Track 1 on target A; track 2 within 3 m of the moored boat all along; track 3 of nothing (far away); track 4
    sails past the moored boat (within 10 m of it in 3 of its 11 rows)."""
    jitter = np.random.default_rng(1).normal(0.0, 1.0, (len(T), 2))
    past = moored[1] + np.linspace(-50.0, 50.0, len(T))
    return (
        _rows(1, T * 1.0, np.zeros_like(T))
        + _rows(2, moored[0] + jitter[:, 0], moored[1] + jitter[:, 1])
        + _rows(3, np.full_like(T, 400.0), np.full_like(T, -400.0))
        + _rows(4, np.full_like(T, moored[0] + 3.0), past)
    )


def test_a_track_on_a_moored_boat_is_dont_care_not_false() -> None:
    moored = np.array([60.0, 60.0])
    tracks, truth = make_tracks(_three_tracks(moored)), make_truth()
    plain = evaluate(tracks, truth, 10.0).false_tracks
    assert plain is not None and (plain.n_tracks, plain.n_dont_care) == (3, 0)
    spared = evaluate(tracks, truth, 10.0, dont_care=stationary_truth([moored], T[0], T[-1])).false_tracks
    assert spared is not None and (spared.n_tracks, spared.n_dont_care) == (2, 1)  # track 4 only passes by: still false
    assert spared.n_instants == plain.n_instants - len(T)


def test_evaluate_run_takes_the_moored_boats_of_the_harbour() -> None:
    """``evaluate_run`` with a harbour: its moored boats (the built-in harbour has five) are don't-care."""
    boats = moored_boat_positions("harbour")
    assert len(boats) == 5
    rows = [r for k, b in enumerate(boats) for r in _rows(10 + k, np.full_like(T, b[0]), np.full_like(T, b[1]))]
    tracks = make_tracks(rows + _rows(1, T * 1.0, np.zeros_like(T)))
    harbour = evaluate_run(tracks, make_truth(), map_spec="harbour").false_tracks
    assert harbour is not None and (harbour.n_tracks, harbour.n_dont_care) == (0, 5)
    none = evaluate_run(tracks, make_truth(), map_spec="none").false_tracks
    assert none is not None and (none.n_tracks, none.n_dont_care) == (5, 0)


def test_stationary_truth_holds_still() -> None:
    s = stationary_truth([[1.0, 2.0], [3.0, 4.0]], 5.0, 5.0)
    assert s.names == ["moored1", "moored2"]
    np.testing.assert_allclose(s.states_at([5.0, 5.5])[1], [[3.0, 0.0, 4.0, 0.0]] * 2)
    with pytest.raises(ValueError, match="names"):
        stationary_truth([[1.0, 2.0]], 0.0, 1.0, names=["a", "b"])
