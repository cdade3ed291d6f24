"""How a served vessel moves between steps: the scenario's poses, or forces (Gemini's ``ForceControl``).

Each ``DoStep`` carries a pose for every vessel. A vessel's :class:`VesselMotion` decides the pose it
really takes at the step's time:

* :class:`ScenarioReplay` (every vessel until a force is applied to it): the pose the step sends;
* :class:`ForceDriven` (once ``ForceControl.ApplyForce`` names the vessel): the step's pose is
  ignored; the vessel's state (pose and body velocities) is integrated from the previous step to
  this one under the generalized force last applied (held constant, as Gemini's ``ForceController``
  applies it every physics step until the next request), by a :class:`VesselDynamics`.

:class:`VesselDynamics` is the seam for a vessel model: :class:`LinearManoeuvring3DOF` is the simple
one here (Fossen's 3-DOF manoeuvring model with a diagonal mass matrix, the rigid-body Coriolis
terms and linear damping, nominal values for a 5 m ferry); a full model (``seatwin.dynamics``) is
passed in its place with the same :meth:`~VesselDynamics.step`.

Frames (Fossen): pose η = (north, east, ψ) in the scenario's NED frame, ψ clockwise from north [rad];
body velocities ν = (u surge, v sway, r yaw rate); generalized force τ = (X, Y, N) [N, N, N·m] in the
body frame (surge forward, sway to starboard, yaw moment clockwise seen from above).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import ParameterError

Vector3 = NDArray[np.float64]
"""Three floats: a pose (north, east, ψ), body velocities (u, v, r) or a force (X, Y, N)."""


class VesselDynamics(Protocol):
    """A vessel's 3-DOF dynamics: advance (η, ν) by ``dt`` seconds under the constant force ``tau``."""

    def step(self, eta: Vector3, nu: Vector3, tau: Vector3, dt: float) -> tuple[Vector3, Vector3]: ...


@dataclass(frozen=True)
class LinearManoeuvring3DOF:
    """M ν̇ + C(ν) ν + D ν = τ, η̇ = R(ψ) ν (Fossen 2011, eq. 6.105 with linear damping), integrated with
    classical Runge-Kutta in sub-steps of at most ``max_dt_s``.

    M = diag(m11, m22, m33) (rigid body + added mass), D = diag(d11, d22, d33) and the rigid-body
    Coriolis force of a diagonal M: C(ν)ν = (−m22·v·r, m11·u·r, (m22 − m11)·u·v). The defaults are
    nominal values for a 5 m, ~1.8 t harbour ferry (milliAmpere's size) — surge time constant
    m11/d11 = 10 s, sway 4.3 s, yaw 2.7 s — not an identified model: a placeholder for
    ``seatwin.dynamics``.
    """

    m11: float = 2000.0
    m22: float = 2600.0
    m33: float = 4000.0
    d11: float = 200.0
    d22: float = 600.0
    d33: float = 1500.0
    max_dt_s: float = 0.01

    def __post_init__(self) -> None:
        for name in ("m11", "m22", "m33", "d11", "d22", "d33", "max_dt_s"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0) and not (name.startswith("d") and value == 0):
                raise ParameterError(name, f"expected a positive finite value, got {value!r}")

    def _derivative(self, eta: Vector3, nu: Vector3, tau: Vector3) -> tuple[Vector3, Vector3]:
        u, v, r = nu
        c, s = math.cos(eta[2]), math.sin(eta[2])
        eta_dot = np.array([c * u - s * v, s * u + c * v, r])
        coriolis = np.array([-self.m22 * v * r, self.m11 * u * r, (self.m22 - self.m11) * u * v])
        damping = np.array([self.d11 * u, self.d22 * v, self.d33 * r])
        nu_dot = (tau - coriolis - damping) / np.array([self.m11, self.m22, self.m33])
        return eta_dot, nu_dot

    def step(self, eta: Vector3, nu: Vector3, tau: Vector3, dt: float) -> tuple[Vector3, Vector3]:
        eta, nu, tau = np.array(eta, np.float64), np.array(nu, np.float64), np.asarray(tau, np.float64)
        if dt <= 0:
            return eta, nu
        n = max(1, math.ceil(dt / self.max_dt_s - 1e-9))
        h = dt / n
        for _ in range(n):
            k1e, k1n = self._derivative(eta, nu, tau)
            k2e, k2n = self._derivative(eta + h / 2 * k1e, nu + h / 2 * k1n, tau)
            k3e, k3n = self._derivative(eta + h / 2 * k2e, nu + h / 2 * k2n, tau)
            k4e, k4n = self._derivative(eta + h * k3e, nu + h * k3n, tau)
            eta = eta + h / 6 * (k1e + 2 * k2e + 2 * k3e + k4e)
            nu = nu + h / 6 * (k1n + 2 * k2n + 2 * k3n + k4n)
        return eta, nu


class VesselMotion(Protocol):
    """Where a served vessel is at a step: :meth:`pose` proposes (changes nothing), :meth:`commit` takes it."""

    def pose(self, t: float, commanded: Vector3) -> Vector3:
        """The vessel's pose (north, east [m], ψ [rad]) at POSIX time ``t``, given the pose the step sends."""
        ...

    def commit(self, t: float) -> None:
        """The step at ``t`` was taken (after :meth:`pose` for the same ``t``)."""
        ...


class ScenarioReplay:
    """The pose the step sends (a scenario replayed by the client)."""

    def pose(self, t: float, commanded: Vector3) -> Vector3:
        return np.asarray(commanded, np.float64)

    def commit(self, t: float) -> None:
        return None


def body_velocity(heading: float, v_north: float, v_east: float, yaw_rate: float) -> Vector3:
    """NED velocities and yaw rate as body velocities (u, v, r)."""
    c, s = math.cos(heading), math.sin(heading)
    return np.array([c * v_north + s * v_east, -s * v_north + c * v_east, yaw_rate])


class ForceDriven:
    """A vessel moved by the generalized force last applied to it (held between requests)."""

    def __init__(self, dynamics: VesselDynamics, t: float, eta: Vector3, nu: Vector3 | None = None):
        self.dynamics = dynamics
        self.t, self.eta = float(t), np.array(eta, np.float64)
        self.nu = np.zeros(3) if nu is None else np.array(nu, np.float64)
        self.tau = np.zeros(3)
        self._proposed: tuple[float, Vector3, Vector3] | None = None

    def set_force(self, x: float, y: float, n: float) -> None:
        """Hold τ = (X, Y, N) from the last step on."""
        tau = np.array([x, y, n], np.float64)
        if not np.isfinite(tau).all():
            raise ParameterError("generalizedForce", f"expected finite forces, got {tau.tolist()}")
        self.tau = tau

    def pose(self, t: float, commanded: Vector3) -> Vector3:
        eta, nu = self.dynamics.step(self.eta, self.nu, self.tau, float(t) - self.t)
        self._proposed = (float(t), eta, nu)
        return eta

    def commit(self, t: float) -> None:
        if self._proposed is None or self._proposed[0] != float(t):
            self.pose(t, self.eta)
        assert self._proposed is not None
        self.t, self.eta, self.nu = self._proposed
        self._proposed = None
