"""Angles: wrapping to [−π, π) or [0, 2π), degrees to [−180, 180), unwrapping, circular means.

Every angle in seatwin is wrapped here. Floating-point inputs keep their dtype (a float32
array stays float32, as the inline ``(a + π) % 2π − π`` it replaces did); scalars come back
as ``float``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

TWO_PI = 2.0 * np.pi
"""2π, the full turn [rad]."""


def _floating(angle: ArrayLike) -> NDArray[np.floating]:
    a = np.asarray(angle)
    return a if np.issubdtype(a.dtype, np.floating) else a.astype(np.float64)


def _out(a: NDArray[np.floating]) -> NDArray[np.floating] | float:
    return float(a) if a.ndim == 0 else a


def wrap_to_pi(angle: ArrayLike) -> NDArray[np.floating] | float:
    """Wrap angles [rad] to [−π, π)."""
    a = _floating(angle)
    return _out((a + np.pi) % TWO_PI - np.pi)


def wrap_to_2pi(angle: ArrayLike) -> NDArray[np.floating] | float:
    """Wrap angles [rad] to [0, 2π) (bearings and azimuths of a full turn)."""
    return _out(_floating(angle) % TWO_PI)


def wrap_to_180(deg: ArrayLike) -> NDArray[np.floating] | float:
    """Wrap angles in degrees to [−180, 180) (longitude differences, file headings)."""
    return _out((_floating(deg) + 180.0) % 360.0 - 180.0)


def unwrap(angle: ArrayLike) -> NDArray[np.float64]:
    """Remove 2π jumps so an angle sequence can be interpolated linearly."""
    return np.unwrap(np.asarray(angle, dtype=float))


def circular_mean(angle: ArrayLike, weights: ArrayLike | None = None, axis: int | None = None) -> NDArray[np.float64] | float:
    """The (weighted) mean direction of ``angle`` [rad] along ``axis``, in (−π, π]:
    ``atan2(Σ w sin a, Σ w cos a)``."""
    a = np.asarray(angle, dtype=float)
    s, c = np.sin(a), np.cos(a)
    if weights is not None:
        w = np.asarray(weights, dtype=float)
        s, c = w * s, w * c
    return _out(np.arctan2(s.sum(axis), c.sum(axis)))
