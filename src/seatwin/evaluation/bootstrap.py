"""Circular block bootstrap over time series (instants are autocorrelated: resample blocks, not points)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray


def circular_block_indices(n: int, block: int, rng: np.random.Generator) -> NDArray[np.int64]:
    """``n`` indices into a series of length ``n``: blocks of ``block`` consecutive instants from random
    starts, wrapping around the end (circular: no edge bias). Blocks are kept shorter than a third
    of the series, or every resample would be a rotation of it."""
    if n <= 0:
        return np.empty(0, dtype=np.int64)
    length = max(1, min(block, n // 3))
    k = int(np.ceil(n / length))
    starts = rng.integers(0, n, k)
    return ((starts[:, None] + np.arange(length)[None, :]) % n).ravel()[:n].astype(np.int64)


def percentile_interval(replicates: NDArray[np.float64], level: float = 0.95) -> tuple[float, float] | None:
    """The percentile interval of the finite bootstrap ``replicates`` (None when there are none)."""
    r = np.asarray(replicates, float)
    r = r[np.isfinite(r)]
    if not len(r):
        return None
    a = (1.0 - level) / 2.0
    return (float(np.quantile(r, a)), float(np.quantile(r, 1.0 - a)))


BLOCK_RULES = ("politis-white", "acf")
"""Rules of :func:`block_length`: ``politis-white`` (the default) and ``acf``."""


def _acf(x: NDArray[np.float64], lags: int) -> NDArray[np.float64]:
    """Sample autocorrelation of the centred series ``x`` at lags 0 … ``lags`` (denominator n, the usual estimate)."""
    var = float(x @ x)
    return np.array([1.0] + [float(x[:-k] @ x[k:]) / var for k in range(1, lags + 1)])


def politis_white_block_length(x: NDArray[np.float64]) -> float:
    """The optimal block length of the circular block bootstrap of a mean (Politis & White 2004, with the correction of
    Patton, Politis & White 2009), unrounded: ``b = (2 G² / D)^(1/3) n^(1/3)``, ``G = Σ λ(k/M) |k| R(k)``,
    ``D = 4/3 (Σ λ(k/M) R(k))²`` over ``|k| ≤ M`` (``R`` the autocovariance, ``λ`` the flat-top kernel); ``M = 2 m̂``,
    ``m̂`` the first lag after which ``K = max(5, √log10 n)`` autocorrelations in a row are below ``2 √(log10 n / n)``.
    ``x``: finite, centred, not constant, at least 4 values. 1 where the dependence is not positive on the whole
    (long-run variance ``Σ λ R(k)`` at most ``R(0)``: e.g. an alternating series, whose ``D → 0`` would ask for
    huge blocks, while resampling single values already overstates its mean's variance)."""
    n = len(x)
    k_n = max(5, int(np.ceil(np.sqrt(np.log10(n)))))
    top = min(n - 1, int(np.ceil(np.sqrt(n))) + k_n)
    rho = _acf(x, top)
    c = 2.0 * np.sqrt(np.log10(n) / n)
    small = np.abs(rho[1:]) < c
    m_hat = top
    for m in range(0, top - k_n + 1):
        if small[m : m + k_n].all():
            m_hat = m
            break
    big_m = min(2 * max(m_hat, 1), n - 1)
    acov = rho[: big_m + 1] * float(x @ x) / n if big_m <= top else _acf(x, big_m) * float(x @ x) / n
    k = np.arange(1, big_m + 1)
    t = k / big_m
    lam = np.where(t <= 0.5, 1.0, 2.0 * (1.0 - t))
    g = 2.0 * float(np.sum(lam * k * acov[1:]))
    s0 = float(acov[0] + 2.0 * np.sum(lam * acov[1:]))
    if s0 <= acov[0] or g <= 0.0:
        return 1.0  # no net positive dependence: independent resampling (block 1) is already conservative
    d = 4.0 / 3.0 * s0 * s0
    return float((2.0 * g * g / d) ** (1.0 / 3.0) * n ** (1.0 / 3.0))


def block_length(series: ArrayLike, cap: int | None = None, rule: str = "politis-white") -> int:
    """A block length chosen from the data, from ``series`` (its finite values, in order), at most ``cap`` (default
    ``n // 3``, :func:`circular_block_indices`'s own bound; for ``politis-white`` also ``⌈min(3√n, n/3)⌉``); 1 for a
    constant or too short series. Rules:

    * ``politis-white`` (default): :func:`politis_white_block_length`, rounded up — the standard automatic choice,
      minimising the mean squared error of the bootstrap variance of a mean;
    * ``acf``: the first lag ``k ≥ 1`` at which the sample autocorrelation falls below ``2/√n`` (the lag beyond which
      the series is as good as uncorrelated at the 95 % level)."""
    if rule not in BLOCK_RULES:
        raise ValueError(f"unknown block-length rule {rule!r}; expected one of {', '.join(BLOCK_RULES)}")
    x = np.asarray(series, float).reshape(-1)
    x = x[np.isfinite(x)]
    n = len(x)
    top = max(1, n // 3 if cap is None else min(cap, n // 3))
    if n < 4:
        return 1
    x = x - x.mean()
    var = float(x @ x)
    if var <= 0.0:
        return 1
    if rule == "politis-white":
        b_max = int(np.ceil(min(3.0 * np.sqrt(n), n / 3.0)))  # Patton, Politis & White's bound
        return int(min(top, b_max, max(1, np.ceil(politis_white_block_length(x)))))
    bound = 2.0 / np.sqrt(n)
    for k in range(1, top + 1):
        if float(x[:-k] @ x[k:]) / var < bound:
            return k
    return top


def runs_block_length(runs: Sequence[ArrayLike], rule: str = "politis-white") -> int:
    """:func:`block_length` for a statistic pooled over several runs: the longest that any run asks for."""
    return max([block_length(r, rule=rule) for r in runs] or [1])


SOKAL_WINDOW = 5.0
"""Sokal's automatic window: the autocorrelations are summed up to the first lag ``M ≥ c τ(M)``, c = 5."""


def integrated_autocorrelation_time(series: ArrayLike, c: float = SOKAL_WINDOW) -> float:
    """``τ = 1 + 2 Σ_{k=1}^{M} ρ(k)`` of ``series`` (its finite values, in order), ``M`` the smallest lag with
    ``M ≥ c τ(M)`` (Sokal's automatic window; at most n − 1): the variance of the series' mean is ``τ σ² / n``, so
    ``n / τ`` values are worth independent ones; divided by ``1 − (2M + 1)/n`` (at least ½), the bias of the sum when
    the mean is estimated from the series. At least 1 (the floor: negative correlation is not credited); 1 for a
    constant series or one shorter than 4."""
    x = np.asarray(series, float).reshape(-1)
    x = x[np.isfinite(x)]
    n = len(x)
    if n < 4:
        return 1.0
    x = x - x.mean()
    var = float(x @ x)
    if var <= 0.0:
        return 1.0
    tau, m = 1.0, n - 1
    for k in range(1, n):
        tau += 2.0 * float(x[:-k] @ x[k:]) / var
        if k >= c * tau:
            m = k
            break
    # The mean is estimated from the series itself: every autocovariance is low by about Var(x̄) = τσ²/n, so the
    # window's sum by (2M + 1)τ/n; undone, at most doubling τ.
    return max(1.0, tau / max(0.5, 1.0 - (2 * m + 1) / n))


def runs_autocorrelation_time(runs: Sequence[ArrayLike]) -> float:
    """:func:`integrated_autocorrelation_time` for a mean pooled over runs: the runs' τ weighted by their number of
    finite values (the pooled mean's variance is ``σ² Σ nᵢ τᵢ / N²``)."""
    n = [int(np.isfinite(np.asarray(r, float)).sum()) for r in runs]
    if not sum(n):
        return 1.0
    return float(sum(k * integrated_autocorrelation_time(r) for k, r in zip(n, runs)) / sum(n))


def _values_and_boot_variance(
    runs: Sequence[ArrayLike], boot_means: ArrayLike
) -> tuple[list[NDArray[np.float64]], NDArray[np.float64], float]:
    """The runs as flat arrays, their finite values one run after another, and the variance (ddof 1) of the finite
    ``boot_means`` (0 with fewer than 2): what both inflation factors compare."""
    parts = [np.asarray(r, float).reshape(-1) for r in runs]
    x = np.concatenate(parts) if parts else np.empty(0)
    bm = np.asarray(boot_means, float)
    bm = bm[np.isfinite(bm)]
    return parts, x[np.isfinite(x)], float(np.var(bm, ddof=1)) if len(bm) >= 2 else 0.0


def long_memory_inflation(runs: Sequence[ArrayLike], boot_means: ArrayLike, level: float = 0.95) -> float:
    """The factor by which to widen a block-bootstrap spread of a statistic pooled over ``runs`` when the series
    remember longer than the blocks see: ``√max(1, V_τ / V_boot) · t_ν / z``, ``V_τ = τ s² / N`` the long-run
    variance of the pooled mean (:func:`runs_autocorrelation_time`; ``s²`` the values' variance), ``V_boot`` the
    variance of ``boot_means`` (the plain mean of the same block resamples), ``t_ν / z`` the ratio of the Student-t
    (``ν = N / τ − 1`` effective values, at least 1) and normal quantiles at ``level`` — the variance is estimated
    from ``N / τ`` independent spells only. 1 with fewer than 2 values or no bootstrap spread."""
    from scipy.stats import norm, t

    parts, x, v_boot = _values_and_boot_variance(runs, boot_means)
    if len(x) < 2 or v_boot <= 0.0:
        return 1.0
    tau = runs_autocorrelation_time(parts)
    ratio = tau * float(np.var(x, ddof=1)) / len(x) / v_boot
    q = (1.0 + level) / 2.0
    nu = max(1.0, len(x) / tau - 1.0)
    return float(np.sqrt(max(1.0, ratio)) * t.ppf(q, nu) / norm.ppf(q))


BATCHES = 4
"""Batches of :func:`batch_means_inflation` (docs/fidelity-score.md, *Batch-means floor*)."""


def batch_means_inflation(runs: Sequence[ArrayLike], boot_means: ArrayLike, level: float = 0.95, batches: int = BATCHES) -> float:
    """The factor by which to widen a bootstrap spread of a pooled mean when batch means vary more than it allows:
    ``√r · t_{b−1} / z`` if ``r = V_bm / V_boot > 1``, else 1; ``V_bm`` the variance of the ``batches`` contiguous
    equal-count batches' means (the runs' finite values one after another) over ``batches``, ``V_boot`` that of
    ``boot_means``. Catches slow drifts too weak per lag for an autocorrelation time to see. 1 with fewer than
    ``2·batches`` values or no bootstrap spread."""
    from scipy.stats import norm, t

    _, x, v_boot = _values_and_boot_variance(runs, boot_means)
    if len(x) < 2 * batches or v_boot <= 0.0:
        return 1.0
    means = np.array([c.mean() for c in np.array_split(x, batches)])
    ratio = float(np.var(means, ddof=1)) / batches / v_boot
    if ratio <= 1.0:
        return 1.0
    q = (1.0 + level) / 2.0
    return float(np.sqrt(ratio) * t.ppf(q, batches - 1) / norm.ppf(q))
