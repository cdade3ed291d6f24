"""Batched, overflow-free linear algebra for covariance matrices: log-determinants and Mahalanobis terms.

Every matrix is symmetrised and factored by Cholesky. A matrix that is not numerically
positive definite (singular, or indefinite by rounding) falls back to an eigen-decomposition
whose eigenvalues are floored at ``n·eps`` times the largest one, so results stay finite:
no determinant is ever formed (only its logarithm), so scales from 1e-300 to 1e300 are fine.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

_EPS = np.finfo(float).eps
_TINY = np.finfo(float).tiny


def _whiten(cov: NDArray[np.float64], d: NDArray[np.float64] | None) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """``(log|P|, L⁻¹d)`` for a batch ``cov`` (…, n, n) and vectors ``d`` (…, n)."""
    p = 0.5 * (cov + np.swapaxes(cov, -1, -2))
    n = p.shape[-1]
    batch = p.shape[:-2]
    flat = p.reshape(-1, n, n)
    dflat = None if d is None else np.broadcast_to(d, batch + (n,)).reshape(-1, n)
    logdet = np.empty(len(flat))
    white = None if d is None else np.empty((len(flat), n))
    try:
        chol = np.linalg.cholesky(flat)
        ok = np.all(np.einsum("kii->ki", chol) > 0, axis=1)
    except np.linalg.LinAlgError:
        chol = None
        ok = np.zeros(len(flat), dtype=bool)
    if chol is None:
        # Factor one by one so that only the bad matrices take the slow path.
        chol = np.zeros_like(flat)
        for k in range(len(flat)):
            try:
                chol[k] = np.linalg.cholesky(flat[k])
                ok[k] = bool(np.all(np.diag(chol[k]) > 0))
            except np.linalg.LinAlgError:
                ok[k] = False
    if ok.any():
        lk = chol[ok]
        logdet[ok] = 2.0 * np.log(np.einsum("kii->ki", lk)).sum(axis=1)
        if white is not None:
            white[ok] = np.linalg.solve(lk, dflat[ok][..., None])[..., 0]
    bad = ~ok
    if bad.any():
        w, v = np.linalg.eigh(flat[bad])
        top = np.abs(w).max(axis=1, keepdims=True)
        w = np.maximum(w, np.maximum(top * n * _EPS, _TINY))
        logdet[bad] = np.log(w).sum(axis=1)
        if white is not None:
            white[bad] = np.einsum("kji,kj->ki", v, dflat[bad]) / np.sqrt(w)
    return logdet.reshape(batch), None if white is None else white.reshape(batch + (n,))


def logdet(cov: NDArray[np.float64]) -> NDArray[np.float64]:
    """``log|P|`` for a batch of covariance matrices (…, n, n)."""
    return _whiten(np.asarray(cov, dtype=float), None)[0]


def mahalanobis_squared(d: NDArray[np.float64], cov: NDArray[np.float64]) -> NDArray[np.float64]:
    """``dᵀ P⁻¹ d`` for batches ``d`` (…, n) and ``cov`` (…, n, n), without forming ``P⁻¹``."""
    d = np.asarray(d, dtype=float)
    cov = np.asarray(cov, dtype=float)
    batch = np.broadcast_shapes(d.shape[:-1], cov.shape[:-2])
    cov = np.broadcast_to(cov, batch + cov.shape[-2:])
    _, y = _whiten(cov, d)
    return np.einsum("...i,...i->...", y, y)


def logdet_and_mahalanobis(d: NDArray[np.float64], cov: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Both ``log|P|`` and ``dᵀ P⁻¹ d`` from one factorisation."""
    d = np.asarray(d, dtype=float)
    cov = np.asarray(cov, dtype=float)
    batch = np.broadcast_shapes(d.shape[:-1], cov.shape[:-2])
    cov = np.broadcast_to(cov, batch + cov.shape[-2:])
    ld, y = _whiten(cov, d)
    return ld, np.einsum("...i,...i->...", y, y)
