"""HED (5.30) and COVDIFF (5.31): closed forms, the printed variant, numerical stability."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.evaluation.hellinger import covdiff, hellinger, log_bhattacharyya
from seatwin.evaluation.metrics import nees


def _spd(rng: np.random.Generator, n: int = 4) -> np.ndarray:
    a = rng.normal(size=(n, n))
    return a @ a.T + 0.5 * np.eye(n)


def test_identical_gaussians_have_zero_distance() -> None:
    rng = np.random.default_rng(1)
    p = _spd(rng)
    mu = rng.normal(size=4)
    assert hellinger(mu, p, mu, p) == pytest.approx(0.0, abs=1e-7)
    assert hellinger(mu, p, mu, p, "printed") == pytest.approx(0.0, abs=1e-7)
    assert covdiff(p, p) == pytest.approx(0.0, abs=1e-7)


@pytest.mark.parametrize(("mu1", "s1", "mu2", "s2"), [(0.0, 1.0, 1.0, 2.0), (3.0, 0.5, -1.0, 0.5), (0.0, 1.0, 0.0, 10.0)])
def test_one_dimensional_closed_form(mu1: float, s1: float, mu2: float, s2: float) -> None:
    # H² = 1 − sqrt(2σ₁σ₂/(σ₁²+σ₂²)) · exp(−(μ₁−μ₂)²/(4(σ₁²+σ₂²)))
    bc = math.sqrt(2 * s1 * s2 / (s1**2 + s2**2)) * math.exp(-((mu1 - mu2) ** 2) / (4 * (s1**2 + s2**2)))
    got = hellinger([mu1], [[s1**2]], [mu2], [[s2**2]])
    assert got == pytest.approx(math.sqrt(1 - bc), rel=1e-12)
    assert covdiff([[s1**2]], [[s2**2]]) == pytest.approx(math.sqrt(1 - math.sqrt(2 * s1 * s2 / (s1**2 + s2**2))), rel=1e-12)


def test_hand_computed_value() -> None:
    # μ₁=0, σ₁=1, μ₂=1, σ₂=2: BC = sqrt(4/5)·exp(−1/20) = 0.8508055…, HED = 0.3862571…
    assert hellinger([0.0], [[1.0]], [1.0], [[4.0]]) == pytest.approx(0.38625709, abs=1e-8)


def test_matches_numerical_integration_in_2d() -> None:
    mu1, p1 = np.array([0.0, 0.5]), np.array([[1.0, 0.3], [0.3, 0.5]])
    mu2, p2 = np.array([0.7, -0.2]), np.array([[0.6, -0.1], [-0.1, 1.2]])
    g = np.linspace(-8, 8, 801)
    x, y = np.meshgrid(g, g, indexing="ij")
    pts = np.stack([x, y], axis=-1)

    def pdf(mu: np.ndarray, p: np.ndarray) -> np.ndarray:
        d = pts - mu
        q = np.einsum("...i,ij,...j->...", d, np.linalg.inv(p), d)
        return np.exp(-0.5 * q) / (2 * np.pi * math.sqrt(np.linalg.det(p)))

    bc = np.sqrt(pdf(mu1, p1) * pdf(mu2, p2)).sum() * (g[1] - g[0]) ** 2
    assert hellinger(mu1, p1, mu2, p2) == pytest.approx(math.sqrt(1 - bc), rel=1e-6)


def test_printed_form_has_mean_term_exp_minus_nees_over_16() -> None:
    rng = np.random.default_rng(2)
    p = _spd(rng)
    mu1, mu2 = rng.normal(size=4), rng.normal(size=4) * 2
    q = float(nees(mu1, mu2, p))  # P̄ = P when P₁ = P₂
    assert hellinger(mu1, p, mu2, p, "printed") == pytest.approx(math.sqrt(1 - math.exp(-q / 16)), rel=1e-10)
    assert hellinger(mu1, p, mu2, p, "standard") == pytest.approx(math.sqrt(1 - math.exp(-q / 8)), rel=1e-10)
    # In general log BC_printed − log BC_standard = NEES(μ₁, μ₂, P̄)/16 ≥ 0.
    p2 = _spd(rng)
    pbar = 0.5 * (p + p2)
    diff = log_bhattacharyya(mu1, p, mu2, p2, "printed") - log_bhattacharyya(mu1, p, mu2, p2, "standard")
    assert diff == pytest.approx(float(nees(mu1, mu2, pbar)) / 16, rel=1e-10)
    assert hellinger(mu1, p, mu2, p2, "printed") <= hellinger(mu1, p, mu2, p2, "standard")


def test_equal_means_give_covdiff() -> None:
    rng = np.random.default_rng(3)
    p1, p2, mu = _spd(rng), _spd(rng), rng.normal(size=4)
    assert hellinger(mu, p1, mu, p2) == pytest.approx(float(covdiff(p1, p2)), rel=1e-12)


def test_batched_matches_loop() -> None:
    rng = np.random.default_rng(4)
    p1 = np.stack([_spd(rng) for _ in range(5)])
    p2 = np.stack([_spd(rng) for _ in range(5)])
    m1, m2 = rng.normal(size=(5, 4)), rng.normal(size=(5, 4))
    batch = hellinger(m1, p1, m2, p2)
    assert batch.shape == (5,)
    assert np.allclose(batch, [hellinger(m1[i], p1[i], m2[i], p2[i]) for i in range(5)], rtol=1e-12)


@pytest.mark.parametrize("scale", [1e-12, 1e12, 1e-300, 1e300])
def test_scale_invariance_without_overflow(scale: float) -> None:
    rng = np.random.default_rng(5)
    p1, p2 = _spd(rng), _spd(rng)
    m1, m2 = rng.normal(size=4), rng.normal(size=4)
    ref = float(hellinger(m1, p1, m2, p2))
    s = math.sqrt(scale)
    with np.errstate(all="raise"):
        got = float(hellinger(m1 * s, p1 * scale, m2 * s, p2 * scale))
        cd = float(covdiff(p1 * scale, p2 * scale))
    assert got == pytest.approx(ref, rel=1e-8)
    assert cd == pytest.approx(float(covdiff(p1, p2)), rel=1e-8)


def test_mixed_scales_stay_in_unit_interval() -> None:
    p = np.eye(4)
    for a, b in [(1e-12, 1e12), (1e-300, 1e300), (1.0, 1e12)]:
        for form in ("standard", "printed"):
            h = float(hellinger(np.zeros(4), p * a, np.ones(4), p * b, form))
            assert np.isfinite(h) and 0.0 <= h <= 1.0
            assert h == pytest.approx(1.0, abs=1e-3)


@pytest.mark.parametrize("eps", [1e-9, 1e-14, 0.0, -1e-15])
def test_near_singular_covariances(eps: float) -> None:
    v = np.array([1.0, 0.5, -0.3, 0.2])
    p1 = np.outer(v, v) + np.diag([1, 1, 1, 0]) * 1e-3 + eps * np.eye(4)  # rank 3 plus eps (even indefinite)
    p2 = np.outer(v, v) * 1.1 + np.diag([1, 1, 1, 0]) * 1e-3 + eps * np.eye(4)
    for form in ("standard", "printed"):
        h = hellinger(np.zeros(4), p1, np.full(4, 0.01), p2, form)
        assert np.isfinite(h) and 0.0 <= float(h) <= 1.0
    c = covdiff(p1, p2)
    assert np.isfinite(c) and 0.0 <= float(c) <= 1.0
    assert float(covdiff(p1, p1)) == pytest.approx(0.0, abs=1e-6)


def test_huge_nees_gives_one() -> None:
    assert float(hellinger(np.zeros(4), np.eye(4) * 1e-12, np.full(4, 1e6), np.eye(4) * 1e-12)) == 1.0
