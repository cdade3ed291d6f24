"""Hellinger distance between Gaussians (5.29)–(5.30) and the covariance term COVDIFF (5.31).

For ``N₁ = N(μ₁, P₁)``, ``N₂ = N(μ₂, P₂)`` and ``P̄ = (P₁ + P₂)/2`` the Bhattacharyya
coefficient is (the thesis's reference [29] and every textbook)::

    BC = (|P₁|^{1/4} |P₂|^{1/4} / |P̄|^{1/2}) · exp(−NEES(μ₁, μ₂, P̄)/8),     HED = sqrt(1 − BC)

— the ``"standard"`` form. The thesis *prints* (5.30) with the exponential inside the
inner square root, ``BC = sqrt( sqrt(|P₁||P₂|)/|P̄| · exp(−NEES/8) )``, i.e. the mean term
``exp(−NEES/16)`` — the ``"printed"`` form, kept as an option. Both agree when μ₁ = μ₂ (then
HED = COVDIFF (5.31)); the printed form is never larger than the standard one.

Computed in the log domain from Cholesky log-determinants, ``HED = sqrt(−expm1(log BC))``:
no determinant is formed, so tiny, huge and near-singular covariances give a finite result
in [0, 1], and small distances keep their relative precision.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.evaluation.linalg import logdet, logdet_and_mahalanobis

HellingerForm = Literal["standard", "printed"]
FORMS: tuple[str, ...] = ("standard", "printed")


def log_bc_covariance(p1: ArrayLike, p2: ArrayLike) -> NDArray[np.float64]:
    """``log(|P₁|^{1/4}|P₂|^{1/4}/|P̄|^{1/2})`` (≤ 0): the covariance part of log BC."""
    p1 = np.asarray(p1, dtype=float)
    p2 = np.asarray(p2, dtype=float)
    value = 0.25 * logdet(p1) + 0.25 * logdet(p2) - 0.5 * logdet(0.5 * (p1 + p2))
    return np.minimum(value, 0.0)


def log_bhattacharyya(
    mu1: ArrayLike, p1: ArrayLike, mu2: ArrayLike, p2: ArrayLike, form: HellingerForm = "standard"
) -> NDArray[np.float64]:
    """``log BC`` of two Gaussians in the ``"standard"`` or the thesis's ``"printed"`` form (see module doc)."""
    if form not in FORMS:
        raise ValueError(f"form must be one of {FORMS}, got {form!r}")
    p1 = np.asarray(p1, dtype=float)
    p2 = np.asarray(p2, dtype=float)
    d = np.asarray(mu1, dtype=float) - np.asarray(mu2, dtype=float)
    ld_bar, nees_bar = logdet_and_mahalanobis(d, 0.5 * (p1 + p2))
    cov_term = np.minimum(0.25 * logdet(p1) + 0.25 * logdet(p2) - 0.5 * ld_bar, 0.0)
    mean_term = -nees_bar / (8.0 if form == "standard" else 16.0)
    return np.minimum(cov_term + mean_term, 0.0)


def _from_log_bc(log_bc: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.clip(np.sqrt(np.maximum(-np.expm1(log_bc), 0.0)), 0.0, 1.0)


def hellinger(
    mu1: ArrayLike, p1: ArrayLike, mu2: ArrayLike, p2: ArrayLike, form: HellingerForm = "standard"
) -> NDArray[np.float64]:
    """HED (5.30) between ``N(μ₁, P₁)`` and ``N(μ₂, P₂)``, batched over leading axes; in [0, 1]."""
    return _from_log_bc(log_bhattacharyya(mu1, p1, mu2, p2, form))


def covdiff(p1: ArrayLike, p2: ArrayLike) -> NDArray[np.float64]:
    """COVDIFF (5.31): the Hellinger distance of two zero-mean Gaussians, in [0, 1]."""
    return _from_log_bc(log_bc_covariance(p1, p2))
