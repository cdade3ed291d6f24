"""Run-to-run spread of a statistic: the variance a within-run block bootstrap cannot see (issue 22, item 2).

A tracker behaves differently from run to run (a track lost for seconds, a late initiation, a track on another
part of the hull); inside one run such an event happens once, so resampling blocks of that run cannot reproduce
it. The model's replicate runs (one per seed) can: the spread of their per-run statistics estimates the sampling
variance of *one* run's statistic. This module estimates the part of it the within-run bootstrap misses
(:func:`run_spread`) and draws run effects with that covariance for the bootstrap replicates (:func:`run_effects`);
:func:`seatwin.evaluation.score.target_score` uses them (docs/fidelity-score.md, *Run-to-run spread*).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

GAUSSIAN_PARAMS = ("mean_north", "mean_east", "log_sd_north", "log_sd_east", "atanh_correlation")
"""The parameters of a 2-D error Gaussian on which run effects are added (unbounded scales: log σ, atanh ρ)."""
_RHO_MAX = 0.999


def gaussian_params(mean: ArrayLike, cov: ArrayLike) -> NDArray[np.float64]:
    """``(μ_n, μ_e, log σ_n, log σ_e, atanh ρ)`` of a 2-D Gaussian (``cov`` positive definite)."""
    m, p = np.asarray(mean, float).reshape(2), np.asarray(cov, float).reshape(2, 2)
    sd = np.sqrt(np.diag(p))
    rho = float(np.clip(p[0, 1] / (sd[0] * sd[1]), -_RHO_MAX, _RHO_MAX))
    return np.array([m[0], m[1], np.log(sd[0]), np.log(sd[1]), np.arctanh(rho)])


def gaussian_from_params(params: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Mean and covariance back from :func:`gaussian_params`' vector."""
    q = np.asarray(params, float).reshape(5)
    sd, rho = np.exp(q[2:4]), float(np.tanh(q[4]))
    cov = np.array([[sd[0] ** 2, rho * sd[0] * sd[1]], [rho * sd[0] * sd[1], sd[1] ** 2]])
    return q[:2].copy(), cov


@dataclass(frozen=True)
class RunSpread:
    """The between-run covariance of one run's statistic and the degrees of freedom of its estimate."""

    cov: NDArray[np.float64]
    """Covariance (d × d, positive semi-definite) of the run effect of a single run."""
    dof: int
    """Degrees of freedom of the estimate: the number of runs − 1."""
    runs: int

    @property
    def sd(self) -> NDArray[np.float64]:
        return np.sqrt(np.diag(self.cov))


def run_spread(per_run: ArrayLike, within: ArrayLike | None = None) -> RunSpread | None:
    """The between-run covariance of a statistic from its values in ``K ≥ 2`` replicate runs of one model,
    ``per_run`` (K × d, finite): their sample covariance (ddof 1) — the sampling covariance of one run's value,
    within-run noise included — minus ``within`` (K × d × d: each run's within-run bootstrap covariance of its
    value; their mean is the part a within-run bootstrap already reproduces), projected onto the positive
    semi-definite matrices (negative eigenvalues set to 0). None with fewer than 2 runs."""
    x = np.asarray(per_run, float)
    x = x.reshape(len(x), -1)
    if len(x) < 2:
        return None
    if not np.isfinite(x).all():
        raise ValueError("run_spread: per-run values must be finite")
    s = np.atleast_2d(np.cov(x, rowvar=False, ddof=1))
    if within is not None:
        w = np.asarray(within, float).reshape(len(x), x.shape[1], x.shape[1])
        s = s - w.mean(axis=0)
    vals, vecs = np.linalg.eigh(0.5 * (s + s.T))
    cov = (vecs * np.clip(vals, 0.0, None)) @ vecs.T
    return RunSpread(cov, len(x) - 1, len(x))


def t_scales(dof: int, n: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """``n`` factors ``√(ν / χ²_ν)``: a Gaussian draw times one of them is Student-t with ``ν = dof`` degrees of
    freedom — the predictive law of a new run's effect when its variance is itself estimated from ``ν + 1`` runs."""
    return np.sqrt(dof / rng.chisquare(dof, n))


def run_effects(spread: RunSpread, scale: float, scales: NDArray[np.float64], rng: np.random.Generator) -> NDArray[np.float64]:
    """One run effect per entry of ``scales`` (:func:`t_scales`): ``N(0, spread.cov × scale²)`` draws, each
    multiplied by its t-factor (share one ``scales`` between the real and the synthetic side of a replicate: both
    sides' effects use one variance estimate). ``scale``: 1 for one run, ``1/√K`` for the pool of K runs."""
    vals, vecs = np.linalg.eigh(spread.cov)
    root = vecs * np.sqrt(np.clip(vals, 0.0, None))
    z = rng.standard_normal((len(scales), len(vals)))
    return (z @ root.T) * (scale * np.asarray(scales, float))[:, None]
