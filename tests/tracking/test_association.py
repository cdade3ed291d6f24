"""JIPDA association: gate (5.23), exact enumeration, forward–backward, belief propagation, Stone Soup's JPDA."""

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


def test_clusters() -> None:
    gated = np.array([[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 0]], bool)
    assert sorted(sorted(c) for c in track_clusters(gated)) == [[0, 1], [2], [3]]


def _random_cluster(rng, T=None, M=None):
    T = rng.integers(1, 6) if T is None else T
    M = rng.integers(0, 8) if M is None else M
    gated = rng.random((T, M)) < 0.5
    L = rng.random((T, M)) * 10 ** rng.uniform(-1, 2)  # weak to strong likelihood ratios
    r = rng.uniform(0.05, 1.0, T)  # existence < 1
    return r, L, gated


def test_beyond_the_cap_the_forward_backward_pass_is_exact() -> None:
    # Four tracks that all gate eight measurements: 9^4 = 6561 > cap 100 → not enumerated, yet exact.
    rng = np.random.default_rng(1)
    L = rng.random((4, 8)) * 5
    g = np.ones((4, 8), bool)
    b0, b = jipda_marginals(np.full(4, 0.9), L, g, 0.9, max_hypotheses=100)
    e0, e = brute_force(np.full(4, 0.9), L, g, 0.9)
    assert np.allclose(b0, e0, atol=1e-12) and np.allclose(b, e, atol=1e-12)
    # random clusters (existence < 1, clutter, gated subsets) through the frontier path
    for _ in range(200):
        r, L, gated = _random_cluster(rng)
        b0, b = jipda_marginals(r, L, gated, 0.8, max_hypotheses=1)
        e0, e = brute_force(r, L, gated, 0.8)
        assert np.allclose(b0, e0, atol=1e-12) and np.allclose(b, e, atol=1e-12)
        assert np.allclose(existence_posterior(r, b0, 0.8)[0], existence_posterior(r, e0, 0.8)[0], atol=1e-12)


def _row(n, rng):
    """n moored boats in a row: each gates its own and its neighbours' detections (one long cluster)."""
    g = np.zeros((n, n), bool)
    for i in range(n):
        g[i, max(i - 1, 0) : i + 2] = True
    L = rng.uniform(0.5, 50.0, (n, n))
    return rng.uniform(0.3, 1.0, n), L, g


def test_row_of_boats_is_solved_exactly() -> None:
    rng = np.random.default_rng(2)
    r, L, g = _row(9, rng)  # 9 tracks: small enough to enumerate for the reference
    e0, e = jipda_marginals(r, L, g, 0.9, method="exact")
    b0, b = jipda_marginals(r, L, g, 0.9, max_hypotheses=10)
    assert np.allclose(b0, e0, atol=1e-12) and np.allclose(b, e, atol=1e-12)
    # 60 boats: 4^60 hypotheses bound, the forward-backward pass keeps a handful of states
    r, L, g = _row(60, rng)
    b0, b = jipda_marginals(r, L, g, 0.9)
    assert np.allclose(b0 + b.sum(axis=1), 1.0) and (b[~g] == 0).all()
    # its work bound exceeded → belief propagation (approximate) instead
    c0, c = jipda_marginals(r, L, g, 0.9, max_frontier_work=10)
    assert np.allclose(c0, jipda_marginals(r, L, g, 0.9, method="bp")[0], atol=0)
    assert 1e-3 < np.abs(c - b).max() < 0.3  # BP's error on a dense row (loops of length 4)


def test_belief_propagation_is_exact_on_trees() -> None:
    """Loopy BP is exact when the track–measurement gate graph has no cycle."""
    rng = np.random.default_rng(3)
    for _ in range(100):
        T = int(rng.integers(2, 7))
        # a random tree: track t > 0 shares one new measurement with an earlier track; plus private ones
        edges = []
        for t in range(1, T):
            edges.append((int(rng.integers(0, t)), t))
        M = (T - 1) + T
        g = np.zeros((T, M), bool)
        for k, (a, t) in enumerate(edges):
            g[a, k] = g[t, k] = True
        g[np.arange(T), T - 1 + np.arange(T)] = rng.random(T) < 0.7
        L = rng.random((T, M)) * 10 ** rng.uniform(-1, 2)
        r = rng.uniform(0.05, 1.0, T)
        b0, b = jipda_marginals(r, L, g, 0.8, method="bp")
        e0, e = brute_force(r, L, g, 0.8)
        assert np.allclose(b0, e0, atol=1e-9) and np.allclose(b, e, atol=1e-9)


def test_belief_propagation_error_on_loopy_clusters() -> None:
    """Where the gate graph has loops BP is approximate: its measured error (docs/architecture/tracking.md).

    The usual tracking case (each track has one dominant detection, weak clutter/neighbour
    pairs, existence 0.05–1): median error ~1e-9, 99th percentile ~2e-3, worst ~1e-2. That is
    why the automatic choice uses BP only where both exact methods exceed their budgets.
    """
    rng = np.random.default_rng(4)
    errs, r_errs = [], []
    for _ in range(300):
        T = int(rng.integers(2, 6))
        C = int(rng.integers(0, 5))
        M = T + C
        g = rng.random((T, M)) < 0.3
        L = rng.uniform(0.05, 2.0, (T, M))
        own = rng.permutation(M)[:T]
        hit = rng.random(T) < 0.9
        g[np.arange(T)[hit], own[hit]] = True
        L[np.arange(T)[hit], own[hit]] = rng.uniform(50.0, 500.0, hit.sum())
        r = rng.uniform(0.05, 1.0, T)
        b0, b = jipda_marginals(r, L, g, 0.89, method="bp")
        e0, e = brute_force(r, L, g, 0.89)
        errs.append(max(np.abs(b0 - e0).max(), np.abs(b - e).max(initial=0.0)))
        r_errs.append(np.abs(existence_posterior(r, b0, 0.89)[0] - existence_posterior(r, e0, 0.89)[0]).max())
    errs, r_errs = np.array(errs), np.array(r_errs)
    assert np.median(errs) < 1e-6 and np.mean(errs < 1e-3) > 0.95
    assert errs.max() < 0.05 and r_errs.max() < 0.02


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


def _ours(x0, P0, zs, dt_s, q, model, pd, g, lam_of, **assoc):
    x, P = ekf.predict(x0, P0, cv_transition(dt_s), cv_process_noise(dt_s, q, q))
    zhat, H = model.predict(x)
    S = ekf.innovation_covariance(P, H, model.R)
    v = model.residual(zs, zhat)
    d2 = ekf.mahalanobis2(v, ekf.inverse_small(S))
    g2, pg = gate_threshold(zs.shape[1], g=g)
    lik = np.exp(-0.5 * d2) / np.sqrt(np.linalg.det(2 * np.pi * S))[:, None]
    L = pd * lik / lam_of
    return jipda_marginals(np.ones(len(x0)), L, d2 < g2, pd * pg, **assoc), d2 < g2, pg


def _problem(seed):
    rng = np.random.default_rng(seed)
    x0 = np.array([[100.0, 1.0, 50.0, -1.0], [104.0, -1.0, 52.0, 0.5], [98.0, 0.0, 47.0, 1.0]])
    P0 = np.stack([np.diag([9.0, 1.0, 9.0, 1.0])] * 3)
    zs = np.concatenate((x0[:, (0, 2)] + rng.normal(size=(3, 2)) * 2, rng.uniform((90, 40), (112, 60), (5, 2))))
    return x0, P0, zs


@pytest.mark.parametrize("assoc", [{}, {"max_hypotheses": 1}], ids=["enumeration", "forward-backward"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_marginals_equal_stonesoup_jpda_cartesian(seed, assoc) -> None:
    pytest.importorskip("stonesoup")
    from stonesoup.models.measurement.linear import LinearGaussian
    from stonesoup.updater.kalman import KalmanUpdater

    x0, P0, zs = _problem(seed)
    R = np.diag([4.0, 4.0])
    pd, lam, g = 0.9, 2e-3, 3.0
    (b0, b), gated, pg = _ours(x0, P0, zs, 1.0, 0.3, CartesianModel(R), pd, g, lam, **assoc)
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
