"""Builders for small, hand-checkable track files and ground truths."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet, TruthTrack


def make_truth() -> TruthSet:
    """Two targets over t = 0…10 s at 1 Hz: A north at 1 m/s from (0, 0), B fixed at (0, 100)."""
    t = np.arange(0.0, 11.0)
    return TruthSet(
        {
            "A": TruthTrack("A", t, t * 1.0, np.zeros_like(t)),
            "B": TruthTrack("B", t, np.zeros_like(t), np.full_like(t, 100.0)),
        }
    )


def make_tracks(
    rows: list[tuple[float, int, float, float]], scan_times: list[float] | None = None, var: float = 1.0, confirmed: bool = True
) -> Tracks:
    """Tracks from (time, id, north, east) rows with zero velocity and covariance ``var·I``."""
    n = len(rows)
    arr = np.asarray(rows, dtype=float).reshape(n, 4)
    state = np.zeros((n, 4))
    state[:, 0], state[:, 2] = arr[:, 2], arr[:, 3]
    return Tracks(
        arr[:, 0],
        arr[:, 1].astype(int),
        np.full(n, 0.9),
        state,
        np.tile(np.eye(4) * var, (n, 1, 1)),
        np.full(n, confirmed),
        np.asarray(scan_times or [], float),
    )


@pytest.fixture
def truth() -> TruthSet:
    return make_truth()


@pytest.fixture
def tracks_factory() -> Callable[..., Tracks]:
    return make_tracks
