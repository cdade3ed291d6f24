"""The 3-DOF manoeuvring model M ν̇ + C(ν)ν + D(ν)ν = τ (Fossen 2011, ch. 6–7) with milliAmpere's parameters.

State: pose η = (north, east, ψ) in the local NED frame, velocity ν = (u, v, r) in the body frame
(x forward, y starboard; r positive clockwise seen from above). τ = (X, Y, N) [N, N, N·m].

Parameters of :data:`MILLIAMPERE`: the system identification of A. A. Pedersen, "Optimization based system
identification for the milliAmpere ferry", NTNU master's thesis, 2019 (https://hdl.handle.net/11250/2625699).
The thesis itself is not readable from here; its numbers are taken from two independent public implementations that
cite it and agree on them (the IDLab AirSim vessel fork's ``MilliAmpereParams.hpp`` and the ROS 2 package
``imirfurkan/vessel_dynamics``): the identified mass matrix (rigid body + added mass) and the damping coefficients of
:class:`VesselParameters`. The two copies differ only in Y_r (24.732 vs 24.372 kg·m/s); we take 24.732.
C(ν) is Fossen's Coriolis–centripetal matrix of that mass matrix in the form both implementations use (c13 = −m22·v −
m23·r, c23 = m11·u); D(ν) the identified linear + nonlinear (|·| and cubic) damping, coupled in sway–yaw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class VesselParameters:
    """A 3-DOF model: the mass matrix (rigid body + added mass) and the damping coefficients (Fossen's notation:
    ``X_uu`` multiplies |u|·u, ``X_uuu`` u³; ``Y_rv`` multiplies |r|·v, ``Y_vr`` |v|·r, …)."""

    name: str
    m11: float
    """kg"""
    m22: float
    """kg"""
    m23: float
    """kg·m"""
    m32: float
    """kg·m"""
    m33: float
    """kg·m²"""
    X_u: float
    X_uu: float
    X_uuu: float
    Y_v: float
    Y_vv: float
    Y_vvv: float
    Y_rv: float
    Y_r: float
    Y_vr: float
    Y_rr: float
    N_v: float
    N_vv: float
    N_rv: float
    N_r: float
    N_rr: float
    N_rrr: float
    N_vr: float
    length: float
    """Length overall [m] (the hull box of the collision checks)."""
    beam: float
    """Beam [m]."""

    def mass_matrix(self) -> NDArray[np.float64]:
        """M (3 × 3)."""
        return np.array([[self.m11, 0.0, 0.0], [0.0, self.m22, self.m23], [0.0, self.m32, self.m33]])

    def coriolis(self, nu: NDArray[np.float64]) -> NDArray[np.float64]:
        """C(ν) (3 × 3), skew-symmetric."""
        u, v, r = (float(x) for x in nu)
        c13 = -self.m22 * v - self.m23 * r
        c23 = self.m11 * u
        return np.array([[0.0, 0.0, c13], [0.0, 0.0, c23], [-c13, -c23, 0.0]])

    def damping(self, nu: NDArray[np.float64]) -> NDArray[np.float64]:
        """D(ν) (3 × 3): linear plus nonlinear damping."""
        u, v, r = (float(x) for x in nu)
        au, av, ar = abs(u), abs(v), abs(r)
        d11 = -self.X_u - self.X_uu * au - self.X_uuu * u * u
        d22 = -self.Y_v - self.Y_vv * av - self.Y_rv * ar - self.Y_vvv * v * v
        d23 = -self.Y_r - self.Y_vr * av - self.Y_rr * ar
        d32 = -self.N_v - self.N_vv * av - self.N_rv * ar
        d33 = -self.N_r - self.N_vr * av - self.N_rr * ar - self.N_rrr * r * r
        return np.array([[d11, 0.0, 0.0], [0.0, d22, d23], [0.0, d32, d33]])

    def surge_damping(self, u: float) -> float:
        """The surge resistance [N] at a steady surge speed ``u`` (sway and yaw at rest): d11(u)·u."""
        return (-self.X_u - self.X_uu * abs(u) - self.X_uuu * u * u) * u


MILLIAMPERE = VesselParameters(
    name="milliampere",
    m11=2389.657,
    m22=2533.911,
    m23=62.386,
    m32=28.141,
    m33=5068.910,
    X_u=-27.632,
    X_uu=-110.064,
    X_uuu=-13.965,
    Y_v=-52.947,
    Y_vv=-116.486,
    Y_vvv=-24.313,
    Y_rv=-1540.383,
    Y_r=24.732,
    Y_vr=572.141,
    Y_rr=-115.456,
    N_v=3.5241,
    N_vv=-0.832,
    N_rv=336.827,
    N_r=-122.860,
    N_rr=-874.428,
    N_rrr=0.0,
    N_vr=-121.957,
    length=5.0,
    beam=2.8,
)
"""milliAmpere (Pedersen 2019; see the module docstring). Length and beam from the ferry's published size."""


class Model:
    """``p``'s right-hand sides in plain floats (the loop calls them a few thousand times a run): M⁻¹ once."""

    def __init__(self, p: VesselParameters):
        self.p = p
        inv = np.linalg.inv(p.mass_matrix())
        self._inv = tuple(tuple(float(x) for x in row) for row in inv)

    def accelerations(self, nu: tuple[float, float, float], tau: tuple[float, float, float]) -> tuple[float, float, float]:
        """ν̇ = M⁻¹ (τ − C(ν)ν − D(ν)ν)."""
        p = self.p
        u, v, r = nu
        au, av, ar = abs(u), abs(v), abs(r)
        c13 = -p.m22 * v - p.m23 * r
        c23 = p.m11 * u
        d11 = -p.X_u - p.X_uu * au - p.X_uuu * u * u
        d22 = -p.Y_v - p.Y_vv * av - p.Y_rv * ar - p.Y_vvv * v * v
        d23 = -p.Y_r - p.Y_vr * av - p.Y_rr * ar
        d32 = -p.N_v - p.N_vv * av - p.N_rv * ar
        d33 = -p.N_r - p.N_vr * av - p.N_rr * ar - p.N_rrr * r * r
        f0 = tau[0] - c13 * r - d11 * u
        f1 = tau[1] - c23 * r - d22 * v - d23 * r
        f2 = tau[2] + c13 * u + c23 * v - d32 * v - d33 * r
        (a00, a01, a02), (a10, a11, a12), (a20, a21, a22) = self._inv
        return (a00 * f0 + a01 * f1 + a02 * f2, a10 * f0 + a11 * f1 + a12 * f2, a20 * f0 + a21 * f1 + a22 * f2)


def pose_rates(psi: float, nu: tuple[float, float, float]) -> tuple[float, float, float]:
    """η̇ = R(ψ) ν: (ṅorth, ėast, ψ̇)."""
    c, s = math.cos(psi), math.sin(psi)
    u, v, r = nu
    return (c * u - s * v, s * u + c * v, r)
