"""Circular block bootstrap over time series (instants are autocorrelated: resample blocks, not points)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray


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
