"""Tracker performance metrics of thesis ch. 5.1.4: RMSE (5.25), NEES (5.26), ANEES (5.27), bounds (5.28).

All functions take batches: states ``(…, n)`` and covariances ``(…, n, n)``. NaN marks an
undefined instant (a track loss); :func:`anees` averages over the defined ones only, as the
thesis does ("letting N_k only contain the number of valid instances").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.evaluation.linalg import mahalanobis_squared


def rmse(x_hat: ArrayLike, x_ref: ArrayLike) -> NDArray[np.float64]:
    """RMSE (5.25): ``sqrt((x̂ − x_r)ᵀ(x̂ − x_r))`` per instant — the Euclidean norm of the state error."""
    e = np.asarray(x_hat, dtype=float) - np.asarray(x_ref, dtype=float)
    return np.sqrt(np.einsum("...i,...i->...", e, e))


def nees(x_hat: ArrayLike, x_ref: ArrayLike, covariance: ArrayLike) -> NDArray[np.float64]:
    """NEES (5.26): ``(x̂ − x_r)ᵀ P⁻¹ (x̂ − x_r)`` per instant, by a Cholesky solve (no explicit inverse)."""
    e = np.asarray(x_hat, dtype=float) - np.asarray(x_ref, dtype=float)
    return mahalanobis_squared(e, np.asarray(covariance, dtype=float))


def anees(nees_values: ArrayLike) -> float:
    """ANEES (5.27): the mean NEES over the valid (finite) instants; NaN when there is none."""
    v = np.asarray(nees_values, dtype=float).reshape(-1)
    v = v[np.isfinite(v)]
    return float(v.mean()) if v.size else float("nan")


@dataclass(frozen=True)
class AneesBounds:
    """The two-sided χ² acceptance interval of ANEES (5.28)."""

    lower: float
    upper: float
    n_k: int
    n_g: int
    confidence: float

    def verdict(self, value: float) -> str:
        """``"consistent"`` inside the bounds, ``"overconfident"`` above, ``"underconfident"`` below (thesis 5.1.4)."""
        if not np.isfinite(value):
            return "undefined"
        if value > self.upper:
            return "overconfident"
        if value < self.lower:
            return "underconfident"
        return "consistent"


def anees_bounds(n_k: int, n_g: int = 4, confidence: float = 0.95) -> AneesBounds:
    """Bounds (5.28): ``χ²⁻¹(1 − α/2, N_k·N_g)/N_k`` and ``χ²⁻¹(α/2, N_k·N_g)/N_k`` with α = 1 − confidence.

    The thesis uses ``confidence = 0.95`` (quantiles 0.975 and 0.025) and ``N_g = 4``.
    """
    from scipy.stats import chi2

    if n_k < 1:
        return AneesBounds(float("nan"), float("nan"), int(n_k), int(n_g), confidence)
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence}")
    alpha = 1.0 - confidence
    dof = n_k * n_g
    return AneesBounds(
        lower=float(chi2.ppf(alpha / 2, dof) / n_k),
        upper=float(chi2.ppf(1 - alpha / 2, dof) / n_k),
        n_k=int(n_k),
        n_g=int(n_g),
        confidence=confidence,
    )


def rms(values: ArrayLike) -> float:
    """Root mean square of the finite per-instant values (e.g. RMSE (5.25) summarised over a scenario)."""
    v = np.asarray(values, dtype=float).reshape(-1)
    v = v[np.isfinite(v)]
    return float(np.sqrt(np.mean(v * v))) if v.size else float("nan")
