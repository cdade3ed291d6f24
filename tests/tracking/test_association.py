"""JIPDA association: gate (5.23), exact enumeration, the cap, agreement with Stone Soup's JPDA."""

from __future__ import annotations

import datetime as dt
import itertools

import numpy as np
import pytest
from scipy.stats import chi2

from seatwin.tracking import ekf
from seatwin.tracking.association import (
    existence_posterior,
    gate_threshold,
    jipda_marginals,
    track_clusters,
)
from seatwin.tracking.models import CartesianModel, RangeBearingModel, cv_process_noise, cv_transition


def test_gate_threshold() -> None:
    g2, pg = gate_threshold(2, g=1.0)  # thesis: g = 1
    assert g2 == 1.0 and np.isclose(pg, 1 - np.exp(-0.5))
    g2, pg = gate_threshold(2, probability=0.99)
    assert np.isclose(g2, chi2.ppf(0.99, 2)) and pg == 0.99
    with pytest.raises(ValueError):
        gate_threshold(2, g=1.0, probability=0.9)


def brute_force(r, L, gated, pd_pg):
    T, M = L.shape
    opts = [[0] + [j + 1 for j in range(M) if gated[t, j]] for t in range(T)]
    b = np.zeros((T, M + 1))
    for a in itertools.product(*opts):
        used = [x for x in a if x]
        if len(used) != len(set(used)):
            continue
        w = np.prod([(1 - r[t] * pd_pg) if a[t] == 0 else r[t] * L[t, a[t] - 1] for t in range(T)])
        for t in range(T):
            b[t, a[t]] += w
    b /= b.sum(axis=1, keepdims=True)
    return b[:, 0], b[:, 1:]


def test_marginals_equal_brute_force() -> None:
    rng = np.random.default_rng(5)
    for _ in range(20):
        T, M = rng.integers(1, 5), rng.integers(0, 7)
        gated = rng.random((T, M)) < 0.5
        L = rng.random((T, M)) * 10
        r = rng.uniform(0.1, 1.0, T)
        b0, b = jipda_marginals(r, L, gated, 0.8)
        e0, e = brute_force(r, L, gated, 0.8)
        assert np.allclose(b0, e0, atol=1e-12) and np.allclose(b, e, atol=1e-12)
        assert np.allclose(b0 + b.sum(1), 1)


def test_clusters_and_cap() -> None:
    gated = np.array([[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 0]], bool)
    assert sorted(sorted(c) for c in track_clusters(gated)) == [[0, 1], [2], [3]]
    # Four tracks that all gate eight measurements: 9^4 = 6561 > cap 100 → k-best approximation.
    rng = np.random.default_rng(1)
    L = rng.random((4, 8)) * 5
    g = np.ones((4, 8), bool)
    b0, b = jipda_marginals(np.full(4, 0.9), L, g, 0.9, max_hypotheses=100)
    assert np.allclose(b0 + b.sum(1), 1)
    assert ((b > 0).sum(axis=1) <= 2).all()  # (2+1)^4 = 81 ≤ 100 < (3+1)^4
    e0, e = brute_force(np.full(4, 0.9), L, g, 0.9)
    # An approximation: close where each track has a dominant measurement (the usual case) ...
    Lp = L.copy()
    Lp[np.arange(4), [0, 2, 4, 6]] = 200.0
    a0, a = jipda_marginals(np.full(4, 0.9), Lp, g, 0.9, max_hypotheses=100)
    p0, p = brute_force(np.full(4, 0.9), Lp, g, 0.9)
    assert np.abs(a - p).max() < 0.05
    # below the cap it is exact
    b0, b = jipda_marginals(np.full(4, 0.9), L, g, 0.9, max_hypotheses=10**4)
    assert np.allclose(b, e, atol=1e-12)


def test_existence_posterior_hand_values() -> None:
    r, w0 = existence_posterior(np.array([0.5, 0.5]), np.array([1.0, 0.0]), 0.9)
    # missed: r(1-PD PG)/(1 - r PD PG) = 0.05/0.55
    assert np.isclose(r[0], 0.05 / 0.55) and w0[0] == 1.0
    assert r[1] == 1.0 and w0[1] == 0.0


# ---- Stone Soup cross-check --------------------------------------------------------------
# Stone Soup is in the `test` extra; only these cross-checks need it (skip them, not the module).


def _stonesoup_marginals(x0, P0, zs, dt_s, q, meas_model, updater_cls, pd, pg, lam, g):
    from stonesoup.dataassociator.probability import JPDA
    from stonesoup.gater.distance import DistanceGater
    from stonesoup.hypothesiser.probability import PDAHypothesiser
    from stonesoup.measures import Mahalanobis
    from stonesoup.models.transition.linear import CombinedLinearGaussianTransitionModel, ConstantVelocity
    from stonesoup.predictor.kalman import KalmanPredictor
    from stonesoup.types.detection import Detection
    from stonesoup.types.state import GaussianState
    from stonesoup.types.track import Track

    t0 = dt.datetime(2020, 9, 15, 12)
    t1 = t0 + dt.timedelta(seconds=dt_s)
    trans = CombinedLinearGaussianTransitionModel([ConstantVelocity(q), ConstantVelocity(q)])
    predictor = KalmanPredictor(trans)
    updater = updater_cls(meas_model)
    hyp = PDAHypothesiser(predictor, updater, clutter_spatial_density=lam, prob_detect=pd, prob_gate=pg)
    jpda = JPDA(DistanceGater(hyp, measure=Mahalanobis(), gate_threshold=g))
    tracks = [Track([GaussianState(x.reshape(4, 1), P, timestamp=t0)]) for x, P in zip(x0, P0)]
    dets = [Detection(z.reshape(-1, 1), timestamp=t1, measurement_model=meas_model) for z in zs]
    res = jpda.associate(tracks, set(dets), t1)
    b0 = np.zeros(len(tracks))
    b = np.zeros((len(tracks), len(dets)))
    for i, trk in enumerate(tracks):
        for h in res[trk]:
            if h.measurement in dets:
                b[i, dets.index(h.measurement)] = float(h.probability)
            else:
                b0[i] = float(h.probability)
    return b0, b


def _ours(x0, P0, zs, dt_s, q, model, pd, g, lam_of):
    x, P = ekf.predict(x0, P0, cv_transition(dt_s), cv_process_noise(dt_s, q, q))
    zhat, H = model.predict(x)
    S = ekf.innovation_covariance(P, H, model.R)
    v = model.residual(zs, zhat)
    d2 = ekf.mahalanobis2(v, ekf.inverse_small(S))
    g2, pg = gate_threshold(zs.shape[1], g=g)
    lik = np.exp(-0.5 * d2) / np.sqrt(np.linalg.det(2 * np.pi * S))[:, None]
    L = pd * lik / lam_of
    return jipda_marginals(np.ones(len(x0)), L, d2 < g2, pd * pg), d2 < g2, pg


def _problem(seed):
    rng = np.random.default_rng(seed)
    x0 = np.array([[100.0, 1.0, 50.0, -1.0], [104.0, -1.0, 52.0, 0.5], [98.0, 0.0, 47.0, 1.0]])
    P0 = np.stack([np.diag([9.0, 1.0, 9.0, 1.0])] * 3)
    zs = np.concatenate((x0[:, (0, 2)] + rng.normal(size=(3, 2)) * 2, rng.uniform((90, 40), (112, 60), (5, 2))))
    return x0, P0, zs


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_marginals_equal_stonesoup_jpda_cartesian(seed) -> None:
    pytest.importorskip("stonesoup")
    from stonesoup.models.measurement.linear import LinearGaussian
    from stonesoup.updater.kalman import KalmanUpdater

    x0, P0, zs = _problem(seed)
    R = np.diag([4.0, 4.0])
    pd, lam, g = 0.9, 2e-3, 3.0
    (b0, b), gated, pg = _ours(x0, P0, zs, 1.0, 0.3, CartesianModel(R), pd, g, lam)
    assert gated.sum(axis=0).max() >= 2  # a real joint problem: shared measurements
    s0, s = _stonesoup_marginals(x0, P0, zs, 1.0, 0.3, LinearGaussian(4, (0, 2), R), KalmanUpdater, pd, pg, lam, g)
    assert np.allclose(b0, s0, atol=1e-9, rtol=0) and np.allclose(b, s, atol=1e-9, rtol=0)


@pytest.mark.parametrize("seed", [0, 3])
def test_marginals_equal_stonesoup_jpda_range_bearing(seed) -> None:
    pytest.importorskip("stonesoup")
    from stonesoup.models.measurement.nonlinear import CartesianToBearingRange
    from stonesoup.updater.kalman import ExtendedKalmanUpdater

    x0, P0, zs_cart = _problem(seed)
    R = np.diag([4.0, 1e-4])  # range m², bearing rad²
    zs = np.column_stack((np.hypot(zs_cart[:, 0], zs_cart[:, 1]), np.arctan2(zs_cart[:, 1], zs_cart[:, 0])))
    pd, lam, g = 0.9, 0.5, 3.0  # a constant density per m·rad, as Stone Soup takes it
    (b0, b), gated, pg = _ours(x0, P0, zs, 1.0, 0.3, RangeBearingModel(R), pd, g, lam)
    assert gated.sum(axis=0).max() >= 2

    class AnalyticBearingRange(CartesianToBearingRange):
        """Stone Soup's model with the analytic Jacobian (its default is numerical differences, ~1e-8 off)."""

        def jacobian(self, state, **kwargs):
            _, H = RangeBearingModel(R).predict(np.asarray(state.state_vector, float).reshape(1, 4))
            return H[0, ::-1]

    ss_model = AnalyticBearingRange(4, (0, 2), np.diag([R[1, 1], R[0, 0]]))
    s0, s = _stonesoup_marginals(x0, P0, zs[:, ::-1], 1.0, 0.3, ss_model, ExtendedKalmanUpdater, pd, pg, lam, g)
    assert np.allclose(b0, s0, atol=1e-9, rtol=0) and np.allclose(b, s, atol=1e-9, rtol=0)
