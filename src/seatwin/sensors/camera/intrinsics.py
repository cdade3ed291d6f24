"""Pinhole intrinsics and the plumb-bob lens distortion (ROS ``camera_info``, OpenCV's model).

Pixel convention as OpenCV and ROS: pixel (0, 0)'s centre is at (0, 0), the principal point of
an ideal camera is the image centre ((W − 1)/2, (H − 1)/2). Square pixels: ``fy = fx``.

The distortion is applied *to the synthetic image*: every pixel of the distorted image takes
the colour of the pinhole render at the undistorted position of its ray (iterative inversion
of the plumb-bob model, computed once per camera), so an image rectified with the recorded
``D`` and ``K`` is the pinhole image again.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray


def focal_from_hfov(width: int, hfov_deg: float) -> float:
    """Focal length [pixels] of a pinhole ``width`` pixels wide spanning ``hfov_deg``:
    f = (W / 2) / tan(HFOV / 2) (thesis 4.1.1, the frustum's field of view)."""
    return 0.5 * width / math.tan(math.radians(hfov_deg) / 2.0)


def vfov_deg(width: int, height: int, hfov_deg: float) -> float:
    """Vertical field of view from the aspect ratio (thesis Eq. 4.3): tan(VFOV/2) = (H/W) tan(HFOV/2)."""
    return math.degrees(2.0 * math.atan(height / width * math.tan(math.radians(hfov_deg) / 2.0)))


def intrinsic_matrix(width: int, height: int, hfov_deg: float) -> NDArray[np.float64]:
    """``K`` of a square-pixel pinhole with the principal point at the image centre."""
    f = focal_from_hfov(width, hfov_deg)
    return np.array([[f, 0.0, (width - 1) / 2.0], [0.0, f, (height - 1) / 2.0], [0.0, 0.0, 1.0]])


def distort(x: ArrayLike, y: ArrayLike, d: Sequence[float]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Plumb-bob distortion of normalised image coordinates (x = X/Z, y = Y/Z), ``d`` = (k1, k2, t1, t2, k3):

    r² = x² + y², x_d = x (1 + k1 r² + k2 r⁴ + k3 r⁶) + 2 t1 x y + t2 (r² + 2 x²),
    y_d = y (1 + k1 r² + k2 r⁴ + k3 r⁶) + t1 (r² + 2 y²) + 2 t2 x y.
    """
    k1, k2, t1, t2, k3 = (float(v) for v in d)
    x, y = np.asarray(x, float), np.asarray(y, float)
    r2 = x * x + y * y
    radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))
    return x * radial + 2 * t1 * x * y + t2 * (r2 + 2 * x * x), y * radial + t1 * (r2 + 2 * y * y) + 2 * t2 * x * y


def undistort(xd: ArrayLike, yd: ArrayLike, d: Sequence[float], iterations: int = 20) -> tuple[NDArray, NDArray]:
    """Normalised coordinates whose :func:`distort` is (xd, yd): OpenCV's fixed-point iteration."""
    k1, k2, t1, t2, k3 = (float(v) for v in d)
    xd, yd = np.asarray(xd, float), np.asarray(yd, float)
    x, y = xd.copy(), yd.copy()
    for _ in range(iterations):
        r2 = x * x + y * y
        radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))
        dx = 2 * t1 * x * y + t2 * (r2 + 2 * x * x)
        dy = t1 * (r2 + 2 * y * y) + 2 * t2 * x * y
        x, y = (xd - dx) / radial, (yd - dy) / radial
    return x, y


def project(points: ArrayLike, k: ArrayLike, d: Sequence[float] | None = None) -> NDArray[np.float64]:
    """(N, 2) pixel coordinates (u, v) of (N, 3) points in the optical frame (z > 0), distorted by ``d``."""
    p = np.asarray(points, float).reshape(-1, 3)
    k = np.asarray(k, float)
    x, y = p[:, 0] / p[:, 2], p[:, 1] / p[:, 2]
    if d is not None and any(v != 0.0 for v in d):
        x, y = distort(x, y, d)
    return np.stack([k[0, 0] * x + k[0, 1] * y + k[0, 2], k[1, 1] * y + k[1, 2]], axis=1)


def source_pixels(k: ArrayLike, d: Sequence[float], width: int, height: int) -> tuple[NDArray, NDArray]:
    """(u, v) H×W: where each pixel of the distorted image lies in the pinhole image (its ray undistorted)."""
    k = np.asarray(k, float)
    v, u = np.mgrid[0:height, 0:width].astype(float)
    yd = (v - k[1, 2]) / k[1, 1]
    xd = (u - k[0, 2] - k[0, 1] * yd) / k[0, 0]
    x, y = undistort(xd, yd, d)
    return k[0, 0] * x + k[0, 1] * y + k[0, 2], k[1, 1] * y + k[1, 2]


@dataclass(frozen=True)
class DistortionMap:
    """Where each pixel of the distorted image samples the pinhole render (bilinear; nearest for ids)."""

    width: int
    height: int
    index: NDArray[np.int64]
    """(4, H·W) flat pixel indices of the four neighbours in the pinhole image."""
    weight: NDArray[np.float32]
    """(4, H·W) bilinear weights (all zero where the ray leaves the render: black)."""
    nearest: NDArray[np.int64]
    """(H·W,) flat index of the nearest pinhole pixel (−1 outside)."""

    @classmethod
    def build(cls, k: ArrayLike, d: Sequence[float], width: int, height: int) -> DistortionMap:
        su, sv = (a.ravel() for a in source_pixels(k, d, width, height))
        inside = (su >= 0) & (su <= width - 1) & (sv >= 0) & (sv <= height - 1) & np.isfinite(su) & np.isfinite(sv)
        su, sv = np.where(inside, su, 0.0), np.where(inside, sv, 0.0)
        x0 = np.minimum(np.floor(su).astype(np.int64), width - 2)
        y0 = np.minimum(np.floor(sv).astype(np.int64), height - 2)
        fx, fy = su - x0, sv - y0
        idx = np.stack([y0 * width + x0, y0 * width + x0 + 1, (y0 + 1) * width + x0, (y0 + 1) * width + x0 + 1])
        w = np.stack([(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy]) * inside
        near = np.where(inside, np.rint(sv).astype(np.int64) * width + np.rint(su).astype(np.int64), -1)
        return cls(width, height, idx, w.astype(np.float32), near)

    def apply(self, image: NDArray[np.uint8]) -> NDArray[np.uint8]:
        """The distorted H×W×C image of a pinhole H×W×C image (bilinear)."""
        c = image.shape[2] if image.ndim == 3 else 1
        flat = image.reshape(-1, c).astype(np.float32)
        acc = flat[self.index[0]] * self.weight[0][:, None]
        for j in range(1, 4):
            acc += flat[self.index[j]] * self.weight[j][:, None]
        out = np.clip(acc + 0.5, 0, 255).astype(np.uint8)
        return out.reshape(self.height, self.width, c) if image.ndim == 3 else out.reshape(self.height, self.width)

    def apply_nearest(self, values: NDArray, fill: int = -1) -> NDArray:
        """The distorted image of per-pixel labels (object ids), nearest neighbour; ``fill`` outside."""
        flat = values.reshape(-1)
        out = np.where(self.nearest >= 0, flat[np.maximum(self.nearest, 0)], fill)
        return out.reshape(self.height, self.width).astype(values.dtype)
