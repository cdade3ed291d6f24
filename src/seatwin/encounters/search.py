"""Surrogate-guided falsification: Bayesian optimisation of a run's robustness over an encounter space.

A Gaussian process (RBF kernel, one length scale chosen by marginal likelihood from :data:`LENGTH_SCALES`, inputs the
unit cube) models the robustness of the runs so far, transformed by ``log(1 + max(score, 0))`` so the plateau of
encounters that never threaten (robustness ≥ the horizon) does not swamp the differences among the near misses.
Each next point minimises the lower confidence bound μ − κσ over ``candidates`` random points of the cube and as
many Gaussian perturbations (σ 0.05) of the best points so far. Starts from a Latin hypercube of ``initial``
points; stops at the first failure (score < 0) or after ``budget`` evaluations; deterministic for ``seed``. numpy
only (no scikit-learn); a few milliseconds a step at these sizes.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from seatwin.encounters.space import Trial, TrialLog
from seatwin.errors import ParameterError

LENGTH_SCALES = (0.1, 0.15, 0.2, 0.3, 0.45, 0.7, 1.0)
"""Candidate RBF length scales (unit-cube units); the one of largest marginal likelihood is used each step."""
NUGGET = 1e-6
"""Jitter on the kernel's diagonal (the runs are deterministic: no noise term)."""


def _kernel(a: NDArray[np.float64], b: NDArray[np.float64], scale: float) -> NDArray[np.float64]:
    d2 = ((a[:, None, :] - b[None, :, :]) ** 2).sum(-1)
    return np.exp(-0.5 * d2 / (scale * scale))


def _fit(x: NDArray[np.float64], y: NDArray[np.float64]) -> tuple[float, NDArray[np.float64], NDArray[np.float64]]:
    """(length scale, Cholesky factor, α = K⁻¹y) of the best length scale for standardised ``y``."""
    best: tuple[float, float, NDArray[np.float64], NDArray[np.float64]] | None = None
    for scale in LENGTH_SCALES:
        k = _kernel(x, x, scale) + NUGGET * np.eye(len(x))
        try:
            chol = np.linalg.cholesky(k)
        except np.linalg.LinAlgError:
            continue
        alpha = np.linalg.solve(chol.T, np.linalg.solve(chol, y))
        loglik = -0.5 * float(y @ alpha) - float(np.log(np.diag(chol)).sum())
        if best is None or loglik > best[0]:
            best = (loglik, scale, chol, alpha)
    if best is None:
        raise ParameterError("points", "the search's Gaussian process could not be fitted (repeated points?)")
    return best[1], best[2], best[3]


def surrogate_search(
    evaluate: Callable[[NDArray[np.float64]], float],
    dimension: int,
    budget: int,
    seed: int,
    initial: int = 6,
    candidates: int = 1000,
    kappa: float = 2.0,
    stop_at_failure: bool = True,
) -> list[Trial]:
    """Look for failures (score < 0) by Bayesian optimisation of the score (module docstring)."""
    if budget < 1 or initial < 1 or candidates < 1:
        raise ParameterError(
            "budget", f"expected a budget, an initial design and candidates of at least 1, got {budget}, {initial}, {candidates}"
        )
    rng = np.random.default_rng(seed)
    log = TrialLog(evaluate, stop_at_failure)
    if log.initial_design(dimension, min(initial, budget), seed):
        return log.trials
    trials = log.trials
    while len(trials) < budget:
        x = np.array([t.point for t in trials])
        raw = np.array([t.score for t in trials])
        y = np.log1p(np.maximum(raw, 0.0))
        mean, sd = float(y.mean()), float(y.std()) or 1.0
        scale, chol, alpha = _fit(x, (y - mean) / sd)
        best = x[np.argsort(raw)[: max(1, min(5, len(trials)))]]
        local = best[rng.integers(len(best), size=candidates)] + 0.05 * rng.standard_normal((candidates, dimension))
        cand = np.clip(np.vstack([rng.random((candidates, dimension)), local]), 0.0, 1.0)
        ks = _kernel(cand, x, scale)
        mu = ks @ alpha
        v = np.linalg.solve(chol, ks.T)
        sigma = np.sqrt(np.maximum(1.0 - (v * v).sum(0), 0.0))
        if log.run(cand[int(np.argmin(mu - kappa * sigma))]):
            break
    return trials
