"""A synthetic camera's depth buffer as equations: projection (4.3–4.9) and its inverse (4.37–4.42).

View space follows the thesis (OpenGL): the camera looks along −z, x to the right, y up;
``near``/``far`` are the positive plane distances ``n``/``f``. Discrete image space has
``x^d ∈ [0, N_c,w)``, ``y^d ∈ [0, N_c,h)`` (row 0 at the bottom) and ``z^d ∈ [0, N_c,d)``.

Two misprints of the thesis are corrected here (tests check the corrected forms against the
matrix form 4.5–4.8, of which they are the expansion):

* 4.9/4.18 write ``2 f n N_c,d / (f − n)`` in ``z^d``; the ``N_c,d`` inside the bracket is a
  typo (with it ``z^d`` would leave ``[0, N_c,d]``). Here ``z^d = N_c,d/2 (1 + (f+n)/(f−n) + 2fn/((f−n) z^v))``.
* 4.41 has 0 in the homogeneous corner of ``R_y``; a rotation needs 1 (3×3 used here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

DEPTH_24BIT = 2**24
"""``N_c,d`` of a 24-bit depth buffer, the thesis's choice (section "Deciding parameters")."""


@dataclass(frozen=True)
class DepthCamera:
    """One virtual camera: resolution ``N_c,w × N_c,h``, depth precision ``N_c,d``, VFOV, planes."""

    n_cw: int
    n_ch: int
    vfov_c: float
    """Vertical field of view [rad]."""
    near: float
    far: float
    n_cd: int = DEPTH_24BIT

    def __post_init__(self) -> None:
        if not (0.0 < self.near < self.far):
            raise ValueError(f"need 0 < near < far, got near={self.near}, far={self.far}")
        if self.n_cw < 1 or self.n_ch < 1 or self.n_cd < 2:
            raise ValueError(f"resolution must be positive, got {self.n_cw}×{self.n_ch}, N_c,d={self.n_cd}")
        if not (0.0 < self.vfov_c < math.pi):
            raise ValueError(f"VFOV_c must be in (0, π), got {self.vfov_c}")

    @property
    def aspect(self) -> float:
        """``a = N_c,w / N_c,h`` (4.3)."""
        return self.n_cw / self.n_ch

    @property
    def hfov_c(self) -> float:
        """The horizontal field of view that the resolution implies, from 4.3."""
        return 2.0 * math.atan(self.aspect * math.tan(self.vfov_c / 2.0))

    @property
    def resolution(self) -> NDArray[np.float64]:
        """The diagonal of the camera resolution matrix ``N_c`` (4.8)."""
        return np.array([self.n_cw, self.n_ch, self.n_cd], dtype=np.float64)


def aspect_ratio(hfov_c: float, vfov_c: float) -> float:
    """``a = tan(HFOV_c/2) / tan(VFOV_c/2)`` (4.3)."""
    return math.tan(hfov_c / 2.0) / math.tan(vfov_c / 2.0)


def camera_hfov(n_c: int) -> float:
    """``HFOV_c = HFOV_s = 2π / N_c`` (4.14): the azimuth sector of one of ``N_c`` cameras [rad]."""
    if n_c < 1:
        raise ValueError(f"N_c must be ≥ 1, got {n_c}")
    return 2.0 * math.pi / n_c


def camera_vfov(vfov_s: float, hfov_s: float) -> float:
    """``VFOV_c = 2 atan(tan(VFOV_s/2) / cos(HFOV_s/2))`` (4.17) [rad]."""
    return 2.0 * math.atan(math.tan(vfov_s / 2.0) / math.cos(hfov_s / 2.0))


def camera_width(n_ch: float, vfov_s: float, hfov_s: float) -> float:
    """``N_c,w = N_c,h sin(HFOV_s/2) / tan(VFOV_s/2)`` from 4.16 (not rounded)."""
    return n_ch * math.sin(hfov_s / 2.0) / math.tan(vfov_s / 2.0)


def projection_matrix(cam: DepthCamera) -> NDArray[np.float64]:
    """The projection ``T_v^i`` (4.5)."""
    n, f = cam.near, cam.far
    cot = 1.0 / math.tan(cam.vfov_c / 2.0)
    return np.array(
        [
            [cam.n_ch / cam.n_cw * cot, 0.0, 0.0, 0.0],
            [0.0, cot, 0.0, 0.0],
            [0.0, 0.0, -(f + n) / (f - n), -2.0 * f * n / (f - n)],
            [0.0, 0.0, -1.0, 0.0],
        ]
    )


def to_image_space(q_v: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """View space → normalised image space ``Q^i`` (4.6–4.7); rows of ``q_v`` are points."""
    q = np.atleast_2d(np.asarray(q_v, dtype=np.float64))
    h = np.concatenate([q, np.ones((len(q), 1))], axis=1) @ projection_matrix(cam).T
    return h[:, :3] / h[:, 3:4]


def image_to_discrete(q_i: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """``Q^d = ½ N_c (1 + Q^i)`` (4.8), before truncation to integers."""
    return 0.5 * cam.resolution * (1.0 + np.atleast_2d(np.asarray(q_i, dtype=np.float64)))


def discrete_coordinates(q_v: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """Component form 4.9 of ``Q^d`` (continuous; :func:`quantise` truncates it)."""
    q = np.atleast_2d(np.asarray(q_v, dtype=np.float64))
    x, y, z = q[:, 0], q[:, 1], q[:, 2]
    n, f = cam.near, cam.far
    cot = 1.0 / math.tan(cam.vfov_c / 2.0)
    xd = cam.n_cw / 2.0 * (1.0 - cam.n_ch / cam.n_cw * cot * x / z)
    yd = cam.n_ch / 2.0 * (1.0 - cot * y / z)
    zd = cam.n_cd / 2.0 * (1.0 + (f + n) / (f - n) + 2.0 * f * n / ((f - n) * z))
    return np.stack([xd, yd, zd], axis=1)


def depth_to_discrete(z_v: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """The ``z^d`` row of 4.9 for view-space depths ``z^v`` (negative), continuous."""
    z = np.asarray(z_v, dtype=np.float64)
    n, f = cam.near, cam.far
    return cam.n_cd / 2.0 * (1.0 + (f + n) / (f - n) + 2.0 * f * n / ((f - n) * z))


def discrete_to_depth(z_d: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """Inverse of :func:`depth_to_discrete`: ``z^v`` for a (possibly fractional) ``z^d``."""
    zi = 2.0 * np.asarray(z_d, dtype=np.float64) / cam.n_cd - 1.0
    n, f = cam.near, cam.far
    return 2.0 * f * n / ((f - n) * zi - (f + n))


def quantise(q_d: ArrayLike, cam: DepthCamera) -> NDArray[np.int64]:
    """``Q^d ∈ ℕ`` (4.8): truncation to the cell, clipped to ``[0, N_c − 1]`` per axis."""
    q = np.floor(np.atleast_2d(np.asarray(q_d, dtype=np.float64)))
    return np.clip(q, 0, cam.resolution - 1).astype(np.int64)


def back_project(q_d: ArrayLike, cam: DepthCamera, xy_offset: float = 0.5) -> NDArray[np.float64]:
    """Discrete ``Q^d = [x^d, y^d, Z^d]`` → view space (4.37–4.40).

    ``xy_offset`` is added to the pixel indices: 0.5 (default) back-projects through the
    pixel centre, where a rasteriser samples depth; 0 is the literal 4.37 (pixel corner),
    one more half pixel of error, still inside the one-step error of 4.21.
    """
    q = np.atleast_2d(np.asarray(q_d, dtype=np.float64)).copy()
    q[:, :2] += xy_offset
    q_i = 2.0 * q / cam.resolution - 1.0  # 4.38
    h = np.concatenate([q_i, np.ones((len(q_i), 1))], axis=1) @ np.linalg.inv(projection_matrix(cam)).T  # 4.39
    return h[:, :3] / h[:, 3:4]  # 4.40


def pixel_ray(x_d: ArrayLike, y_d: ArrayLike, cam: DepthCamera, xy_offset: float = 0.5) -> NDArray[np.float64]:
    """View-space direction (not unit; ``z = −1``) through pixel ``(x^d, y^d)`` + ``xy_offset``.

    A point at depth ``D`` (``z^v = −D``) on this ray is ``D ·`` the returned vector.
    """
    t = math.tan(cam.vfov_c / 2.0)
    xi = 2.0 * (np.asarray(x_d, dtype=np.float64) + xy_offset) / cam.n_cw - 1.0
    yi = 2.0 * (np.asarray(y_d, dtype=np.float64) + xy_offset) / cam.n_ch - 1.0
    x = xi * cam.n_cw / cam.n_ch * t
    y = yi * t
    return np.stack([x, y, -np.ones_like(x)], axis=-1)


def rotation_y(c: ArrayLike, n_c: int) -> NDArray[np.float64]:
    """``R_y(c)`` (4.41) as 3×3 (or (N, 3, 3) for an array ``c``): camera ``c`` → camera 0's view space."""
    a = 2.0 * np.pi * np.asarray(c, dtype=np.float64) / n_c
    ca, sa = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([ca, z, sa], -1), np.stack([z, o, z], -1), np.stack([-sa, z, ca], -1)], -2)


def unite_clouds(q_v: ArrayLike, camera: ArrayLike, n_c: int) -> NDArray[np.float64]:
    """``Q_li^v = R_y(c) Q_c^v`` (4.42): points of camera ``c`` in camera 0's view space."""
    q = np.atleast_2d(np.asarray(q_v, dtype=np.float64))
    r = rotation_y(np.broadcast_to(np.asarray(camera), (len(q),)), n_c)
    return np.einsum("nij,nj->ni", r, q)


# View space of camera 0 (x right, y up, looking −z) ↔ the sensor frame (REP-103: x forward,
# y left, z up). Camera 0 looks along the sensor's x axis.
VIEW_TO_SENSOR = np.array([[0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
"""Rotation taking camera-0 view-space vectors to the sensor frame (x fwd, y left, z up)."""
