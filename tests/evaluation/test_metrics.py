"""RMSE (5.25), NEES (5.26), ANEES (5.27) and the bounds (5.28)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import chi2

from seatwin.evaluation.metrics import anees, anees_bounds, nees, rms, rmse


def test_rmse_is_the_state_error_norm() -> None:
    # error [3, 0, 4, 0] → sqrt(9 + 16) = 5
    assert rmse([3.0, 1.0, 4.0, 2.0], [0.0, 1.0, 0.0, 2.0]) == pytest.approx(5.0)
    assert np.allclose(rmse(np.zeros((3, 4)), np.ones((3, 4))), 2.0)


def test_nees_hand_computed() -> None:
    # P = diag(4, 1, 9, 1), e = [2, 1, 3, 0] → 4/4 + 1/1 + 9/9 + 0 = 3
    assert nees([2.0, 1.0, 3.0, 0.0], np.zeros(4), np.diag([4.0, 1.0, 9.0, 1.0])) == pytest.approx(3.0)
    # Correlated 2-D: P = [[2, 1], [1, 2]], P⁻¹ = [[2, −1], [−1, 2]]/3, e = [1, 1] → (2 − 1 − 1 + 2)/3 = 2/3
    assert nees([1.0, 1.0], [0.0, 0.0], [[2.0, 1.0], [1.0, 2.0]]) == pytest.approx(2.0 / 3.0)


def test_nees_matches_explicit_inverse_batched() -> None:
    rng = np.random.default_rng(0)
    a = rng.normal(size=(20, 4, 4))
    p = a @ a.transpose(0, 2, 1) + np.eye(4)
    e = rng.normal(size=(20, 4))
    ref = np.einsum("ni,nij,nj->n", e, np.linalg.inv(p), e)
    assert np.allclose(nees(e, np.zeros(4), p), ref, rtol=1e-10)


def test_anees_ignores_undefined_instants() -> None:
    assert anees([1.0, np.nan, 3.0, np.nan, 5.0]) == pytest.approx(3.0)
    assert math.isnan(anees([np.nan, np.nan]))
    assert rms([3.0, np.nan, 4.0]) == pytest.approx(math.sqrt(12.5))


@pytest.mark.parametrize(("n_k", "upper", "lower"), [(799, 4.1985, 3.8063), (755, 4.2042, 3.8008)])
def test_bounds_reproduce_thesis_figure_5_9(n_k: int, upper: float, lower: float) -> None:
    # Figure 5.9's bounds are (5.28) with N_g = 4 and N_k = 799 and 755 valid instants.
    b = anees_bounds(n_k)
    assert b.upper == pytest.approx(upper, abs=5e-5)
    assert b.lower == pytest.approx(lower, abs=5e-5)


def test_bounds_against_scipy_chi2() -> None:
    b = anees_bounds(50, 4, 0.95)
    assert b.upper == pytest.approx(chi2.ppf(0.975, 200) / 50, rel=1e-12)
    assert b.lower == pytest.approx(chi2.ppf(0.025, 200) / 50, rel=1e-12)
    assert b.lower < 4 < b.upper
    assert b.verdict(4.0) == "consistent"
    assert b.verdict(100.0) == "overconfident"
    assert b.verdict(0.1) == "underconfident"
    assert math.isnan(anees_bounds(0).upper)


def test_anees_of_consistent_filter_falls_inside_bounds() -> None:
    rng = np.random.default_rng(7)
    n = 2000
    a = rng.normal(size=(4, 4))
    p = a @ a.T + np.eye(4)
    e = rng.multivariate_normal(np.zeros(4), p, size=n)
    value = anees(nees(e, np.zeros(4), np.broadcast_to(p, (n, 4, 4))))
    assert anees_bounds(n).verdict(value) == "consistent"


def test_false_tracks_are_those_never_a_targets_and_land_is_counted():
    from seatwin.evaluation import evaluate

    from .conftest import make_tracks, make_truth

    class HalfPlane:  # water where east < 50
        def is_water(self, n: float, e: float) -> bool:
            return e < 50.0

    rows = [(t, 1, t * 1.0, 0.0) for t in range(11)]  # on A
    rows += [(t, 7, 500.0, 10.0 + 3 * t) for t in range(11)]  # in the water, away from everything, 3 m/s
    rows += [(t, 9, -300.0, 80.0) for t in range(5)]  # on land
    ev = evaluate(make_tracks(rows, scan_times=list(range(11))), make_truth(), mask=HalfPlane())
    ft = ev.false_tracks
    assert (ft.n_tracks, ft.n_instants, ft.n_on_land) == (2, 16, 1)
    assert ft.max_speed_mps == 0.0  # make_tracks gives zero velocity
    assert evaluate(make_tracks(rows, scan_times=list(range(11))), make_truth()).false_tracks.n_on_land is None
