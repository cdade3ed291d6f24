"""Numerical error of depth buffers (thesis 4.1.3, eqs. 4.20–4.36), as small pure functions.

All positions are view space (camera looks along −z, so ``z^v < 0`` inside the frustum).

Sign convention: 4.21 writes ``x^v − C_2``; the derivation with one-step increments
``x^d_ε = z^d_ε = +1`` gives ``x^v + C_2`` and with ``x^d_ε = −1`` gives ``x^v − C_2``: the
sign only says in which direction the pixel step goes. The thesis's form is used, whose
worst case lies at the negative corner of the far plane (4.32); by symmetry the positive
corner with ``+C_2`` gives the same ``ε_max``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.sensors.depthbuffer.projection import DepthCamera


def c1(cam: DepthCamera) -> float:
    """``C_1 = N_c,d f n / (f − n)`` (after 4.21)."""
    return cam.n_cd * cam.far * cam.near / (cam.far - cam.near)


def c2(cam: DepthCamera) -> float:
    """``C_2 = 2 C_1 tan(VFOV_c/2) / N_c,h`` (after 4.21; 4.34 for the lidar form)."""
    return 2.0 * c1(cam) / cam.n_ch * math.tan(cam.vfov_c / 2.0)


def discrete_step(p0: ArrayLike, p1: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """``[x^d_ε, y^d_ε, z^d_ε]`` between two view-space points (4.20)."""
    a = np.atleast_2d(np.asarray(p0, dtype=np.float64))
    b = np.atleast_2d(np.asarray(p1, dtype=np.float64))
    cot = 1.0 / math.tan(cam.vfov_c / 2.0)
    zz = a[:, 2] * b[:, 2]
    xe = cot * cam.n_ch / 2.0 * (b[:, 2] * a[:, 0] - a[:, 2] * b[:, 0]) / zz
    ye = cot * cam.n_ch / 2.0 * (b[:, 2] * a[:, 1] - a[:, 2] * b[:, 1]) / zz
    ze = -c1(cam) * (b[:, 2] - a[:, 2]) / zz
    return np.stack([xe, ye, ze], axis=1)


def error_components(q_v: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """``[x^v_ε, y^v_ε, z^v_ε]`` for one discrete step in each axis (4.21); rows are points."""
    q = np.atleast_2d(np.asarray(q_v, dtype=np.float64))
    x, y, z = q[:, 0], q[:, 1], q[:, 2]
    k1, k2 = c1(cam), c2(cam)
    ze = -(z**2) / (k1 + z)
    return np.stack([ze / z * (x - k2), ze / z * (y - k2), ze], axis=1)


def error(q_v: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """The Euclidean numerical error ``ε^v(x, y, z)`` (4.22)."""
    q = np.atleast_2d(np.asarray(q_v, dtype=np.float64))
    x, y, z = q[:, 0], q[:, 1], q[:, 2]
    k1, k2 = c1(cam), c2(cam)
    return np.abs(-z / (k1 + z)) * np.sqrt((x - k2) ** 2 + (y - k2) ** 2 + z**2)


def error_gradient(q_v: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """``∇ε^v`` (4.23), rows are points."""
    q = np.atleast_2d(np.asarray(q_v, dtype=np.float64))
    x, y, z = q[:, 0], q[:, 1], q[:, 2]
    k1, k2 = c1(cam), c2(cam)
    g = np.abs(z / (k1 + z))
    s2 = (x - k2) ** 2 + (y - k2) ** 2 + z**2
    s = np.sqrt(s2)
    dz = g * (z**2 * (k1 + z) + k1 * s2) / (z * (k1 + z) * s)
    return np.stack([g * (x - k2) / s, g * (y - k2) / s, dz], axis=1)


def max_error_point(cam: DepthCamera, hfov_c: float | None = None) -> NDArray[np.float64]:
    """``Q^v_max = −f [tan(HFOV_c/2), tan(VFOV_c/2), 1]`` (4.32); HFOV_c defaults to the camera's (4.3)."""
    h = cam.hfov_c if hfov_c is None else hfov_c
    return -cam.far * np.array([math.tan(h / 2.0), math.tan(cam.vfov_c / 2.0), 1.0])


def max_error(cam: DepthCamera, hfov_c: float | None = None) -> float:
    """``ε^v_max = ε^v(Q^v_max)`` (4.32)."""
    return float(error(max_error_point(cam, hfov_c), cam)[0])


def max_error_conditions(cam: DepthCamera) -> dict[str, bool]:
    """The validity conditions of 4.32: 4.25, 4.33 (``min``, printed as "arg min"), ``N > 2``."""
    n, f = cam.near, cam.far
    return {
        "f < n(N_cd+1) (4.25)": f < n * (cam.n_cd + 1),
        "f < n(2 N_cd/N_ch + 1) (4.29, 4.33)": f < n * (2.0 * cam.n_cd / cam.n_ch + 1.0),
        "f < n(2 N_cd/N_cw + 1) (4.31, 4.33)": f < n * (2.0 * cam.n_cd / cam.n_cw + 1.0),
        "N_cw, N_ch > 2 (4.33)": cam.n_cw > 2 and cam.n_ch > 2,
    }


def max_error_numeric(cam: DepthCamera, hfov_c: float | None = None, samples: int = 41) -> float:
    """The maximum of ``ε^v`` over a grid on the whole frustum (a check of 4.32 when 4.33 fails)."""
    h = cam.hfov_c if hfov_c is None else hfov_c
    z = -np.geomspace(cam.near, cam.far, samples)
    u = np.linspace(-1.0, 1.0, samples)
    zz, ux, uy = np.meshgrid(z, u, u, indexing="ij")
    pts = np.stack([-zz * math.tan(h / 2) * ux, -zz * math.tan(cam.vfov_c / 2) * uy, zz], axis=-1).reshape(-1, 3)
    return float(error(pts, cam).max())


def video_memory(n_cw: float, n_ch: float, n_c: int, n_cd: int) -> float:
    """``B = log2(N_c,d)/8 · N_c,w N_c,h N_c`` bytes (4.35, general form)."""
    return math.log2(n_cd) / 8.0 * n_cw * n_ch * n_c


def video_memory_lidar(n_ch: float, n_c: int, n_cd: int, vfov_s: float) -> float:
    """``B_s = log2(N_c,d)/8 · sin(π/N_c)/tan(VFOV_s/2) · N_c,h² N_c`` bytes (4.35, lidar form)."""
    return math.log2(n_cd) / 8.0 * math.sin(math.pi / n_c) / math.tan(vfov_s / 2.0) * n_ch**2 * n_c


def height_from_memory(b_s: float, n_c: int, n_cd: int, vfov_s: float) -> float:
    """``N_c,h = sqrt(8/log2(N_c,d) · tan(VFOV_s/2) B_s / (sin(π/N_c) N_c))`` (4.36), not rounded."""
    return math.sqrt(8.0 / math.log2(n_cd) * math.tan(vfov_s / 2.0) * b_s / (math.sin(math.pi / n_c) * n_c))


def camera_count_gain(n_c: ArrayLike) -> NDArray[np.float64]:
    """``1 / cos(π/N_c)``, the factor of ``C_2`` in 4.34 plotted in Fig. 4.8."""
    return 1.0 / np.cos(np.pi / np.asarray(n_c, dtype=np.float64))


# --------------------------------------------------------------------------------------------
# The complete range error of a depth-buffer lidar return (storage term + grazing term).
#
# 4.20–4.36 bound the error of a point *on the sampled pixel ray*. The filter (4.18, truncated
# by 4.8) samples the ray through the centre of the pixel that contains the beam, up to half a
# pixel diagonal off the beam; on a surface seen at incidence i (from the normal) that ray meets
# the surface at another range: the grazing term, which grows as 1/cos i and is not in 4.22.
# ``--lidar-mode depthbuffer-plane`` intersects the beam itself with the pixel's surface plane,
# which removes the grazing term on planar surfaces and leaves the storage term (times
# cos(i − δ)/cos i from intersecting an oblique plane).


def depth_step(depth: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """One depth level at view depth ``D = −z^v > 0``: ``|z^v_ε| = D² / (C_1 − D)`` (the z row of 4.21)."""
    d = np.asarray(depth, dtype=np.float64)
    return d**2 / (c1(cam) - d)


def pixel_deviation_max(cam: DepthCamera) -> float:
    """The largest angle δ between a beam and the centre ray of the pixel containing it (4.18 with 4.8).

    Half a pixel diagonal seen from the image centre, where pixels subtend the largest angle:
    ``δ_max = atan(√2 tan(VFOV_c/2) / N_c,h)`` (square pixels, 4.3).
    """
    return math.atan(math.sqrt(2.0) * math.tan(cam.vfov_c / 2.0) / cam.n_ch)


def storage_term(range_m: ArrayLike, cam: DepthCamera, levels: float = 1.0) -> NDArray[np.float64]:
    """Range error of ``levels`` depth levels (4.21's ``z^v_ε``) at range ``r`` along a pixel ray.

    Along a ray with range ``k`` per unit depth the error is ``levels · k · D²/(C_1 − D)`` with
    ``D = r/k``, largest on the optical axis (``k = 1``): ``levels · r²/(C_1 − r)``. ``levels = 1``
    for the thesis's back-projection of the truncated ``z^d`` (4.8, 4.37); ½ for a point rebuilt
    from a rounded depth (a GPU rounds to the nearest level).
    """
    return levels * depth_step(range_m, cam)


def grazing_term(range_m: ArrayLike, deviation: ArrayLike, incidence: ArrayLike) -> NDArray[np.float64]:
    """Range error of sampling a plane along a ray ``δ`` off the beam, the beam at incidence ``i``.

    A beam meets a plane at distance ``h`` at range ``r = h/cos i``; a ray turned by ``δ`` towards
    grazing meets it at ``h/cos(i + δ)``: ``Δr = r (cos i / cos(i + δ) − 1)`` ≈ ``r δ tan i`` —
    the issue's ``R·δθ/tan β`` with ``β = π/2 − i`` the angle to the surface. ``inf`` where
    ``i + δ ≥ π/2`` (the ray misses the plane). Extends 4.22, which assumes the point lies on the beam.
    """
    r, d, i = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in (range_m, deviation, incidence)))
    with np.errstate(divide="ignore", invalid="ignore"):
        out = r * (np.cos(i) / np.cos(i + d) - 1.0)
    return np.where(i + d < math.pi / 2.0, out, np.inf)


def range_error_bound(
    range_m: ArrayLike, incidence: ArrayLike, cam: DepthCamera, plane: bool = False, levels: float | None = None
) -> NDArray[np.float64]:
    """The complete bound on ``|Δr|`` of a depth-buffer lidar return on a planar surface.

    Thesis filter (``plane=False``): ``storage_term(r, levels=1) + grazing_term(r, δ_max, i)``
    (4.21 + the grazing term, ``δ_max`` by :func:`pixel_deviation_max`). Plane intersection
    (``plane=True``): the storage error ``e`` of the pixel's point moves the plane by ``e·|n·s|``
    along its normal, and the beam's intersection by ``e·|n·s|/|n·u| ≤ e·cos(max(i − δ_max, 0))/cos i``
    (``levels = ½``: the rasteriser rounds). Curved surfaces and edges are not covered.
    """
    r = np.asarray(range_m, dtype=np.float64)
    i = np.asarray(incidence, dtype=np.float64)
    dev = pixel_deviation_max(cam)
    if not plane:
        return storage_term(r, cam, 1.0 if levels is None else levels) + grazing_term(r, dev, i)
    with np.errstate(divide="ignore"):
        gain = np.where(i < math.pi / 2.0, np.cos(np.maximum(i - dev, 0.0)) / np.cos(i), np.inf)
    return storage_term(r, cam, 0.5 if levels is None else levels) * gain
