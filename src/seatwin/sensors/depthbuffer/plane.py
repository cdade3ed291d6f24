"""Intersecting a beam with the local surface plane of its pixel (``--lidar-mode depthbuffer-plane``).

The thesis's filter reads a beam's point at the centre of the pixel that contains it; at
incidence ``i`` that is off in range by about ``r δ tan i`` (the grazing term,
:func:`~seatwin.sensors.depthbuffer.errors.grazing_term`). Here each pixel's point is rebuilt
from its depth (4.37–4.40, through the pixel centre) and, with the pixel's surface normal,
gives a plane; the exact beam is intersected with it, which leaves only the storage term.

A plane is only right when the beam meets the same surface as the pixel. Each beam is checked
against the 2 × 2 pixels whose centres surround its projection: when all four hold a surface
of the same object and their four planes put the beam at the same range (within a tolerance of
a few depth levels), the nearest pixel's plane is used; otherwise (silhouette, occlusion edge,
crease, the water line) the beam falls back to the thesis point of its nearest pixel.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.sensors.depthbuffer.errors import depth_step
from seatwin.sensors.depthbuffer.projection import DepthCamera, discrete_to_depth, pixel_ray

TOLERANCE_M = 0.01
"""Fixed part of the spread of the four planes' ranges still taken as one surface [m]."""
TOLERANCE_LEVELS = 4.0
"""Depth levels (4.21) added to the tolerance: the storage and the rasteriser's float32 depth."""


@dataclass(frozen=True)
class PixelBlock:
    """The 2 × 2 pixels around each of N projected beams: columns ``x`` and rows ``y`` (N, 4), and
    which of the four contains the beam (``nearest``, the pixel the thesis's filter reads)."""

    x: NDArray[np.int64]
    y: NDArray[np.int64]
    nearest: NDArray[np.int64]


def pixel_block(x_d: ArrayLike, y_d: ArrayLike, cam: DepthCamera) -> PixelBlock:
    """The pixels whose centres (``+½``) surround the continuous pixel positions ``(x^d, y^d)`` (4.9),
    clipped to the image (at the border some of the four repeat)."""
    xd = np.asarray(x_d, dtype=np.float64).reshape(-1)
    yd = np.asarray(y_d, dtype=np.float64).reshape(-1)
    x0, y0 = np.floor(xd - 0.5), np.floor(yd - 0.5)
    xs = np.clip(np.stack([x0, x0 + 1, x0, x0 + 1], axis=1), 0, cam.n_cw - 1).astype(np.int64)
    ys = np.clip(np.stack([y0, y0, y0 + 1, y0 + 1], axis=1), 0, cam.n_ch - 1).astype(np.int64)
    # the containing pixel ⌊x^d⌋ is x0 + 1 when the beam lies left of its centre, x0 otherwise (4.8)
    near = (np.floor(xd) > x0).astype(np.int64) + 2 * (np.floor(yd) > y0).astype(np.int64)
    return PixelBlock(xs, ys, near)


def window_depth_to_depth(window: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """View depth ``D = −z^v`` of a window depth ``z^d / N_c,d`` ∈ [0, 1) (inverse of 4.8–4.9)."""
    return -discrete_to_depth(np.asarray(window, dtype=np.float64) * cam.n_cd, cam)


def pixel_points(x: ArrayLike, y: ArrayLike, window: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """View-space points of pixels ``(x, y)`` at their window depths, through the pixel centres (4.37–4.40)."""
    depth = window_depth_to_depth(window, cam)
    return pixel_ray(x, y, cam) * depth[..., None]


def plane_range(origins: ArrayLike, directions: ArrayLike, points: ArrayLike, normals: ArrayLike) -> NDArray[np.float64]:
    """Distance along unit ``directions`` from ``origins`` to the plane through ``points`` with
    ``normals`` (any length): ``t = n·(p − o) / n·u``; NaN where the beam runs parallel to it."""
    o, u, p, n = (np.asarray(a, dtype=np.float64) for a in (origins, directions, points, normals))
    num = np.einsum("...j,...j->...", n, p - o)
    den = np.einsum("...j,...j->...", n, u)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(np.abs(den) > 1e-9 * np.linalg.norm(n, axis=-1), num / den, np.nan)


def plane_tolerance(depth: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """Largest spread of the four planes' ranges taken as one surface at view depth ``D`` [m]."""
    return TOLERANCE_M + TOLERANCE_LEVELS * depth_step(depth, cam)


def one_surface(ranges: ArrayLike, ids: ArrayLike, tolerance: ArrayLike) -> NDArray[np.bool_]:
    """True where the four pixels of a block (rows of ``ranges`` and ``ids``, (N, 4)) hold one
    object (id ≥ 0) and put the beam at ranges within ``tolerance`` (N,) of each other."""
    t = np.asarray(ranges, dtype=np.float64)
    i = np.asarray(ids)
    same = np.all(i == i[:, :1], axis=1) & (i[:, 0] >= 0)
    ok = np.all(np.isfinite(t) & (t > 0), axis=1)
    spread = np.ptp(np.where(ok[:, None], t, 0.0), axis=1)
    return same & ok & (spread <= np.asarray(tolerance, dtype=np.float64))
