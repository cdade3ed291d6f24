"""The surrogate (Gaussian-process) falsifier on synthetic scores: it finds a small failure region sooner than random
sampling, is deterministic, and names bad input."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.encounters import random_points
from seatwin.encounters.search import surrogate_search
from seatwin.errors import ParameterError

CENTRE = np.array([0.8, 0.2, 0.7, 0.35, 0.6])


def _score(u):
    """Fails within 0.15 of CENTRE (≈ 0.03 % of the 5-D cube); flat (1.45) beyond 0.6, like encounters that never
    threaten."""
    d = float(np.linalg.norm(np.asarray(u) - CENTRE))
    return d - 0.15 if d < 0.6 else 1.45


def test_surrogate_search_finds_a_small_failure_region_sooner_than_random():
    found, rand = [], []
    for seed in range(4):
        trials = surrogate_search(_score, 5, budget=80, seed=seed)
        assert trials[-1].score < 0 and all(t.score >= 0 for t in trials[:-1])
        found.append(len(trials))
        scores = (_score(u) for u in random_points(5, 20000, seed))
        rand.append(next(i + 1 for i, s in enumerate(scores) if s < 0))
    assert max(found) < min(rand)


def test_surrogate_search_is_deterministic_and_keeps_to_the_cube():
    a = surrogate_search(_score, 5, budget=15, seed=3, stop_at_failure=False)
    assert a == surrogate_search(_score, 5, budget=15, seed=3, stop_at_failure=False)
    assert len(a) == 15 and all(0.0 <= x <= 1.0 for t in a for x in t.point)


def test_bad_search_input_is_named():
    with pytest.raises(ParameterError, match="budget"):
        surrogate_search(_score, 5, budget=0, seed=0)
