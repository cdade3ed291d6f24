"""Process and measurement models of the tracker's extended Kalman filter (thesis ch. 5.1.2–5.1.3).

State (thesis eq. 5.32): ``x = [north, v_north, east, v_east]`` in the world NED frame.

* Process: constant velocity (Helgesen ch. 6.4.1; Brekke, *Fundamentals of Sensor Fusion*,
  the discretised continuous white-noise acceleration model) with the thesis's
  ``Q = diag(Q11, Q22)`` (eq. 5.24) read as the acceleration noise intensities [m²/s³] of
  the north and east axes.
* Measurements (all batched over tracks: ``predict`` takes (T, 4) states and returns the
  (T, d) predicted measurements and (T, d, 4) Jacobians ``H`` of Algorithm 2 line 6):
  :class:`RangeBearingModel` (lidar, radar; ``R_li = diag(R11 [m²], R22 [rad²])``),
  :class:`BearingModel` (camera; ``R_c = R_c11 [rad²]``), :class:`CartesianModel`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.geo.angles import wrap_to_pi
from seatwin.perception.measurements import MeasurementKind, Scan

Array = NDArray[np.float64]


def cv_transition(dt: float) -> Array:
    """Constant-velocity transition matrix F for state [n, vn, e, ve] over ``dt`` seconds."""
    return np.array([[1.0, dt, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, dt], [0, 0, 0, 1.0]])


def cv_process_noise(dt: float, q_north: float, q_east: float) -> Array:
    """Discretised CV process noise (thesis eq. 5.24's Q11, Q22 as intensities [m²/s³]).

    Per axis ``q · [[dt³/3, dt²/2], [dt²/2, dt]]``.
    """
    blk = np.array([[dt**3 / 3.0, dt**2 / 2.0], [dt**2 / 2.0, dt]])
    Q = np.zeros((4, 4))
    Q[:2, :2] = q_north * blk
    Q[2:, 2:] = q_east * blk
    return Q


@dataclass(frozen=True)
class CartesianModel:
    """``h(x) = [north, east]`` — linear (H constant)."""

    R: Array
    kind = MeasurementKind.CARTESIAN
    angle_index = None
    _H = np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0]])

    def predict(self, x: Array) -> tuple[Array, Array]:
        return x[:, (0, 2)], np.repeat(self._H[None], x.shape[0], axis=0)

    def residual(self, z: Array, zhat: Array) -> Array:
        """(T, M, d) innovations ``z_j − ẑ_t`` (Algorithm 2 line 9)."""
        return z[None, :, :] - zhat[:, None, :]

    def clutter_density(self, z: Array, density_per_m2: float) -> Array:
        """Clutter density at each measurement, in measurement space (here per m²)."""
        return np.full(z.shape[0], density_per_m2)


@dataclass(frozen=True)
class RangeBearingModel:
    """``h(x) = [|p − s|, atan2(e − s_e, n − s_n)]`` about the sensor position ``s``."""

    R: Array
    sensor_north: float = 0.0
    sensor_east: float = 0.0
    kind = MeasurementKind.RANGE_BEARING
    angle_index = 1

    def predict(self, x: Array) -> tuple[Array, Array]:
        dn = x[:, 0] - self.sensor_north
        de = x[:, 2] - self.sensor_east
        r2 = np.maximum(dn * dn + de * de, 1e-12)
        r = np.sqrt(r2)
        zhat = np.column_stack((r, np.arctan2(de, dn)))
        H = np.zeros((x.shape[0], 2, 4))
        H[:, 0, 0] = dn / r
        H[:, 0, 2] = de / r
        H[:, 1, 0] = -de / r2
        H[:, 1, 2] = dn / r2
        return zhat, H

    def residual(self, z: Array, zhat: Array) -> Array:
        v = z[None, :, :] - zhat[:, None, :]
        v[..., 1] = wrap_to_pi(v[..., 1])
        return v

    def clutter_density(self, z: Array, density_per_m2: float) -> Array:
        """Uniform Cartesian clutter seen in (range, bearing): ``λ · range`` per m·rad (Jacobian)."""
        return density_per_m2 * np.maximum(z[:, 0], 1e-3)


@dataclass(frozen=True)
class BearingModel:
    """``h(x) = atan2(e − s_e, n − s_n)`` — the camera's bearing-only model (Helgesen ch. 2.1.8)."""

    R: Array
    sensor_north: float = 0.0
    sensor_east: float = 0.0
    kind = MeasurementKind.BEARING
    angle_index = 0

    def predict(self, x: Array) -> tuple[Array, Array]:
        dn = x[:, 0] - self.sensor_north
        de = x[:, 2] - self.sensor_east
        r2 = np.maximum(dn * dn + de * de, 1e-12)
        H = np.zeros((x.shape[0], 1, 4))
        H[:, 0, 0] = -de / r2
        H[:, 0, 2] = dn / r2
        return np.arctan2(de, dn)[:, None], H

    def residual(self, z: Array, zhat: Array) -> Array:
        return wrap_to_pi(z[None, :, :] - zhat[:, None, :])

    def clutter_density(self, z: Array, density_per_rad: float) -> Array:
        """Clutter density per radian of bearing (given directly in the tuning)."""
        return np.full(z.shape[0], density_per_rad)


MeasurementModel = CartesianModel | RangeBearingModel | BearingModel


def model_for_scan(scan: Scan, R: Array) -> MeasurementModel:
    """The measurement model of ``scan``'s kind at its sensor position, with noise ``R``."""
    kind = scan.kind
    if kind is MeasurementKind.CARTESIAN:
        return CartesianModel(R)
    if kind is MeasurementKind.RANGE_BEARING:
        return RangeBearingModel(R, scan.sensor_north, scan.sensor_east)
    return BearingModel(R, scan.sensor_north, scan.sensor_east)
