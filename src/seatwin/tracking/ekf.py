"""The extended Kalman filter of thesis Algorithm 2, batched over tracks (and measurements).

Shapes: ``x`` (T, 4), ``P`` (T, 4, 4), predicted measurements (T, d), Jacobians ``H``
(T, d, 4), innovations (T, M, d). Every function is a line or two of Algorithm 2; the
linear Kalman filter (Algorithm 1) is the special case of a constant ``H`` (the tests check
that they agree to rounding).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]


def predict(x: Array, P: Array, F: Array, Q: Array) -> tuple[Array, Array]:
    """Algorithm 2 lines 3 and 7: ``x̂ₖ|ₖ₋₁ = F x̂ₖ₋₁``, ``Pₖ|ₖ₋₁ = F Pₖ₋₁ Fᵀ + Q`` (CV: f linear)."""
    return x @ F.T, F @ P @ F.T + Q


def innovation_covariance(P: Array, H: Array, R: Array) -> Array:
    """Algorithm 2 line 10: ``S = H P Hᵀ + R`` for each track, (T, d, d)."""
    S = H @ P @ np.swapaxes(H, -1, -2) + R
    return 0.5 * (S + np.swapaxes(S, -1, -2))


def inverse_small(S: Array) -> Array:
    """Inverse of a stack of 1×1 or 2×2 (or larger) symmetric matrices; closed form for d ≤ 2."""
    d = S.shape[-1]
    if d == 1:
        return 1.0 / S
    if d == 2:
        a, b, c = S[:, 0, 0], S[:, 0, 1], S[:, 1, 1]
        det = a * c - b * b
        inv = np.empty_like(S)
        inv[:, 0, 0] = c / det
        inv[:, 1, 1] = a / det
        inv[:, 0, 1] = inv[:, 1, 0] = -b / det
        return inv
    return np.linalg.inv(S)


def log_det_small(S: Array) -> Array:
    """log |S| for a stack of small SPD matrices."""
    d = S.shape[-1]
    if d == 1:
        return np.log(S[:, 0, 0])
    if d == 2:
        return np.log(S[:, 0, 0] * S[:, 1, 1] - S[:, 0, 1] ** 2)
    return np.linalg.slogdet(S)[1]


def mahalanobis2(v: Array, S_inv: Array) -> Array:
    """``vᵀ S⁻¹ v`` for innovations (T, M, d) and inverses (T, d, d) → (T, M) (thesis eq. 5.23's left side)."""
    return ((v @ S_inv) * v).sum(axis=-1)


def gain(P: Array, H: Array, S_inv: Array) -> Array:
    """Algorithm 2 line 11: ``W = P Hᵀ S⁻¹``, (T, 4, d)."""
    return P @ np.swapaxes(H, -1, -2) @ S_inv


def update_covariance(P: Array, W: Array, H: Array) -> Array:
    """Algorithm 2 line 13: ``P = (I − W H) P`` (symmetrised)."""
    Pn = P - W @ H @ P
    return 0.5 * (Pn + np.swapaxes(Pn, -1, -2))


def update(x: Array, P: Array, v: Array, H: Array, R: Array) -> tuple[Array, Array, Array]:
    """One EKF correction per track with one innovation each (T, d): returns x̂, P, S (lines 9–13)."""
    S = innovation_covariance(P, H, R)
    W = gain(P, H, inverse_small(S))
    return x + np.einsum("tij,tj->ti", W, v), update_covariance(P, W, H), S


def kalman_step(x: Array, P: Array, z: Array, F: Array, Q: Array, H: Array, R: Array) -> tuple[Array, Array]:
    """Algorithm 1 (linear Kalman filter) for one state ``x`` (4,), ``P`` (4, 4) — the reference."""
    x = F @ x
    P = F @ P @ F.T + Q
    S = H @ P @ H.T + R
    W = P @ H.T @ np.linalg.inv(S)
    return x + W @ (z - H @ x), (np.eye(len(x)) - W @ H) @ P
