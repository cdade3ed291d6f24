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


def block_length(series: ArrayLike, cap: int | None = None) -> int:
    """A block length chosen from the data: the first lag ``k ≥ 1`` at which the sample autocorrelation of
    ``series`` (its finite values, in order) falls below ``2/√n`` — the lag beyond which the series is as good
    as uncorrelated at the 95 % level — at most ``cap`` (default ``n // 3``, :func:`circular_block_indices`'s
    own bound). 1 for a constant or too short series."""
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
    bound = 2.0 / np.sqrt(n)
    for k in range(1, top + 1):
        if float(x[:-k] @ x[k:]) / var < bound:
            return k
    return top


def runs_block_length(runs: Sequence[ArrayLike]) -> int:
    """:func:`block_length` for a statistic pooled over several runs: the longest that any run asks for."""
    return max([block_length(r) for r in runs] or [1])
