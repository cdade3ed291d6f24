"""The spherical projection filter ``M`` (thesis 4.1.2, eqs. 4.10–4.19) and the legacy grid.

``N_c`` cameras share the azimuth: camera ``c`` looks at sensor azimuth ``2πc/N_c`` (counter-
clockwise from the sensor's x axis, REP-103), covers ``[−π/N_c, π/N_c)`` around it, and sees
a beam of azimuth ``α`` at the thesis's longitude ``θ = α − 2πc/N_c``. The filter maps each
beam ``(θ, φ)`` to the pixel its direction projects to (4.18, truncated to the pixel that
contains it, 4.8). It depends only on constants, so it is computed once per sensor.

A beam exactly on the boundary of two sectors belongs to the sector it opens. Which camera
that is must not depend on trigonometry (an azimuth recovered from a float direction can
land a few ulps either side of the boundary, differently on different CPUs): beams on a
regular azimuth grid (:class:`AzimuthGrid`, every lidar is one) get their camera from the
integer column index.

The legacy Autoferry Gemini variant (Fig. 4.5) read the stitched depth buffers on a regular
grid instead: column linear in azimuth, and the row the beam's elevation has on the image's
centre column, for every column. Off the centre the sampled pixel ray then points at a
lower |elevation| than the beam (``tan φ' = tan φ cos θ``); on a plane the rings become
regular ``N_c``-gons and the 3-D error grows linearly with range (Fig. 4.7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo.angles import TWO_PI, wrap_to_pi
from seatwin.sensors.depthbuffer.projection import DepthCamera, camera_hfov


@dataclass(frozen=True)
class AzimuthGrid:
    """Beams on a regular azimuth grid: beam ``i`` lies at azimuth ``2π·index[i]/columns``
    (counter-clockwise from the sensor's x axis, REP-103), its elevation free."""

    index: NDArray[np.int64]
    columns: int

    def __post_init__(self) -> None:
        if self.columns < 1:
            raise ValueError(f"an azimuth grid needs columns ≥ 1, got {self.columns}")
        idx = np.asarray(self.index)
        if not np.issubdtype(idx.dtype, np.integer):
            raise ValueError(f"azimuth grid indices must be integers, got {idx.dtype}")
        object.__setattr__(self, "index", idx.astype(np.int64).reshape(-1))

    @classmethod
    def lidar(cls, columns: int, rings: int) -> AzimuthGrid:
        """The beams of :meth:`seatwin.sensors.lidar_config.LidarConfig.sensor_directions`:
        azimuth-major, column ``k`` at azimuth ``−2πk/columns`` (the head spins clockwise)."""
        return cls(-np.repeat(np.arange(columns, dtype=np.int64), rings), columns)

    def __len__(self) -> int:
        return int(self.index.shape[0])

    def azimuth(self) -> NDArray[np.float64]:
        """The grid azimuths [rad] (through floating point: for checks, not for assignment)."""
        return TWO_PI * self.index / self.columns

    def matches(self, azimuth: ArrayLike, tol: float = 1e-6) -> bool:
        """True when each ``azimuth`` [rad] lies within ``tol`` of its beam's grid azimuth."""
        a = np.asarray(azimuth, dtype=np.float64)
        return a.shape == self.index.shape and bool(np.all(np.abs(wrap_to_pi(a - self.azimuth())) <= tol))

    def cameras(self, n_c: int) -> NDArray[np.int64]:
        """The camera of each beam in integers: ``c = ⌊index·N_c/columns + ½⌋ mod N_c`` (camera
        ``c`` covers ``[2πc/N_c − π/N_c, 2πc/N_c + π/N_c)``; a beam on a boundary opens the next)."""
        return ((2 * self.index * n_c + self.columns) // (2 * self.columns)) % n_c


def reference_point(theta: ArrayLike, phi: ArrayLike, r: ArrayLike) -> NDArray[np.float64]:
    """The spherical reference model ``Q_s^v = r[−sinθ cosφ, sinφ, −cosθ cosφ]`` (4.10)."""
    t, p, rr = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in (theta, phi, r)))
    return rr[..., None] * np.stack([-np.sin(t) * np.cos(p), np.sin(p), -np.cos(t) * np.cos(p)], axis=-1)


def grid_angles(n_sw: int, n_sh: int, n_c: int, vfov_s: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Longitudes ``θ(n_θ)`` of one camera and latitudes ``φ(n_φ)`` (4.12 with 4.13, HFOV_s = 2π/N_c)."""
    if n_sw % n_c:
        raise ValueError(f"N_s,w = {n_sw} must be a multiple of N_c = {n_c} (4.13)")
    hfov_s = camera_hfov(n_c)
    n_theta = np.arange(n_sw // n_c)
    n_phi = np.arange(n_sh)
    return hfov_s * (n_c / n_sw * n_theta - 0.5), vfov_s * (n_phi / n_sh - 0.5)


def grid_radius(n_r: ArrayLike, near: float, far: float, n_cd: int) -> NDArray[np.float64]:
    """``r = (f − n) n_r / N_c,d + n`` (4.12)."""
    return (far - near) * np.asarray(n_r, dtype=np.float64) / n_cd + near


def project_reference(theta: ArrayLike, phi: ArrayLike, r: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """Continuous ``[x_s^d, y_s^d, z_s^d]`` of the reference point (4.18, ``N_c,d`` typo removed)."""
    t, p, rr = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in (theta, phi, r)))
    cot = 1.0 / math.tan(cam.vfov_c / 2.0)
    n, f = cam.near, cam.far
    xd = cam.n_cw / 2.0 * (1.0 - cam.n_ch / cam.n_cw * cot * np.tan(t))
    yd = cam.n_ch / 2.0 * (1.0 + cot * np.tan(p) / np.cos(t))
    zd = cam.n_cd / 2.0 * (1.0 + (f + n) / (f - n) - 2.0 * f * n / ((f - n) * rr * np.cos(t) * np.cos(p)))
    return np.stack([xd, yd, zd], axis=-1)


def point_cloud_depth(z_sd: ArrayLike, cam: DepthCamera) -> NDArray[np.float64]:
    """``Z_s^d = z_s^d / N_c,d`` (4.19)."""
    return np.asarray(z_sd, dtype=np.float64) / cam.n_cd


def sensor_angles(directions: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Azimuth (counter-clockwise from x) and elevation of sensor-frame directions (x fwd, y left, z up)."""
    d = np.atleast_2d(np.asarray(directions, dtype=np.float64))
    return np.arctan2(d[:, 1], d[:, 0]), np.arctan2(d[:, 2], np.hypot(d[:, 0], d[:, 1]))


def split_cameras(azimuth: ArrayLike, n_c: int, grid: AzimuthGrid | None = None) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """The camera ``c`` whose sector holds each azimuth, and the local longitude ``θ ∈ [−π/N_c, π/N_c)``.

    With ``grid`` (the beams' integer azimuth indices) the camera comes from
    :meth:`AzimuthGrid.cameras`, and ``θ`` is the azimuth less that camera's nearest centre.
    """
    step = camera_hfov(n_c)
    a = np.asarray(azimuth, dtype=np.float64)
    u = a / step
    if grid is None:
        k = np.floor(u + 0.5)
        return (k.astype(np.int64) % n_c), a - k * step
    if len(grid) != a.size:
        raise ValueError(f"the azimuth grid has {len(grid)} beams, the azimuths {a.size}")
    c = grid.cameras(n_c).reshape(a.shape)
    k = c + n_c * np.floor((u - c) / n_c + 0.5)  # the centre 2πk/N_c of camera c nearest to a
    return c, a - k * step


@dataclass(frozen=True)
class PixelMap:
    """Which camera and pixel each beam samples: the filter ``M`` (or the legacy grid)."""

    camera: NDArray[np.int64]
    x_d: NDArray[np.int64]
    y_d: NDArray[np.int64]
    cam: DepthCamera
    n_c: int
    filtered: bool

    def __len__(self) -> int:
        return int(self.camera.shape[0])

    def mask(self, camera: int | None = 0) -> NDArray[np.bool_]:
        """``M`` as an ``N_c,h × N_c,w`` image (row 0 = bottom, ``y^d = 0``) for one camera or all (None)."""
        m = np.zeros((self.cam.n_ch, self.cam.n_cw), dtype=bool)
        sel = np.ones(len(self), bool) if camera is None else self.camera == camera
        m[self.y_d[sel], self.x_d[sel]] = True
        return m


def _pixels(xd: NDArray[np.float64], yd: NDArray[np.float64], cam: DepthCamera) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    # Truncation to the containing pixel (4.8); the sector's closing edge (x^d = N_c,w or a
    # top beam at y^d = N_c,h) belongs to the last pixel.
    x = np.clip(np.floor(xd), 0, cam.n_cw - 1).astype(np.int64)
    y = np.clip(np.floor(yd), 0, cam.n_ch - 1).astype(np.int64)
    return x, y


def check_coverage(elevation: ArrayLike, theta: ArrayLike, cam: DepthCamera, tol_px: float = 1.0) -> None:
    """Raise when a beam falls more than ``tol_px`` outside its camera's image (VFOV_c too small)."""
    yd = project_reference(theta, elevation, 1.0, cam)[..., 1]
    out = (yd < -tol_px) | (yd > cam.n_ch + tol_px)
    if np.any(out):
        worst = float(np.degrees(np.max(np.abs(np.asarray(elevation)[out]))))
        raise ValueError(
            f"beams up to ±{worst:.2f}° elevation fall outside VFOV_c = {math.degrees(cam.vfov_c):.2f}°; "
            "raise VFOV_s (4.17) to cover the sensor"
        )


def spherical_filter(directions: ArrayLike, cam: DepthCamera, n_c: int, grid: AzimuthGrid | None = None) -> PixelMap:
    """The spherical projection filter for beams with sensor-frame ``directions`` (4.18–4.19);
    ``grid``: their integer azimuth indices, which then decide the cameras."""
    az, el = sensor_angles(directions)
    c, theta = split_cameras(az, n_c, grid)
    check_coverage(el, theta, cam)
    q = project_reference(theta, el, 1.0, cam)
    x, y = _pixels(q[:, 0], q[:, 1], cam)
    return PixelMap(c, x, y, cam, n_c, True)


def legacy_grid(directions: ArrayLike, cam: DepthCamera, n_c: int, grid: AzimuthGrid | None = None) -> PixelMap:
    """Autoferry Gemini's sampling without the filter: a regular grid over each camera's image.

    Column linear in the local azimuth, ``x^d = (1/2 − θ/HFOV_c) N_c,w``; row the beam's
    elevation has at the image centre, ``y^d = N_c,h/2 (1 + cot(VFOV_c/2) tan φ)`` — 4.18
    without its ``1/cos θ`` (and with ``θ`` for ``tan θ``): the beam shape error. ``grid`` as
    for :func:`spherical_filter`.
    """
    az, el = sensor_angles(directions)
    c, theta = split_cameras(az, n_c, grid)
    xd = (0.5 - theta / camera_hfov(n_c)) * cam.n_cw
    yd = cam.n_ch / 2.0 * (1.0 + np.tan(el) / math.tan(cam.vfov_c / 2.0))
    x, y = _pixels(xd, yd, cam)
    return PixelMap(c, x, y, cam, n_c, False)


def grid_columns(n_sw: int, n_sh: int, n_c: int) -> AzimuthGrid:
    """The :class:`AzimuthGrid` of :func:`grid_directions`: column ``J = c·N_s,w/N_c + n_θ`` lies
    at azimuth ``2πJ/N_s,w − π/N_c`` = ``2π(2J − N_s,w/N_c)/(2N_s,w)``."""
    if n_sw % n_c:
        raise ValueError(f"N_s,w = {n_sw} must be a multiple of N_c = {n_c} (4.13)")
    half_turns = 2 * np.arange(n_sw, dtype=np.int64) - n_sw // n_c
    return AzimuthGrid(np.tile(half_turns, n_sh), 2 * n_sw)


def grid_directions(n_sw: int, n_sh: int, n_c: int, vfov_s: float) -> NDArray[np.float64]:
    """Sensor-frame unit directions of the thesis's regular beam grid (4.12–4.13), all cameras
    (elevation-major: ``N_s,h`` rows of ``N_s,w`` azimuths; :func:`grid_columns` gives their grid)."""
    theta, phi = grid_angles(n_sw, n_sh, n_c, vfov_s)
    az = (np.arange(n_c)[:, None] * camera_hfov(n_c) + theta[None, :]).ravel()
    a, p = np.meshgrid(az, phi, indexing="xy")
    return np.stack([np.cos(p) * np.cos(a), np.cos(p) * np.sin(a), np.sin(p)], axis=-1).reshape(-1, 3)
