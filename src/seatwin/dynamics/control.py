"""A speed and heading autopilot: set-points (surge speed, heading) → τ, for agents that command set-points.

Surge: the steady resistance at the set speed as feed-forward plus a proportional term, X = d₁₁(u_d)·u_d +
m₁₁·k_u·(u_d − u), not below zero unless ``brake``.
Heading: a cascade — a yaw-rate reference r_d = k_ψ·(ψ_d − ψ) (the shorter way) limited to
``max_yaw_rate``, and N = m₃₃·k_r·(r_d − r). Sway is left free (Y = 0). Under way the allocation keeps the azimuths in a cone
about ahead (:meth:`Autopilot.cone`): the thrusters steer like rudders. Stateless, so the loop stays a pure function
of its state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from seatwin.dynamics.integrate import VesselState
from seatwin.dynamics.vessel import VesselParameters
from seatwin.geo import wrap_to_pi


@dataclass(frozen=True)
class Autopilot:
    """Gains and limits of the speed/heading controller."""

    k_u: float = 0.5
    """1/s: the surge error's time constant is about 1/k_u."""
    k_psi: float = 0.6
    """1/s"""
    k_r: float = 2.0
    """1/s"""
    max_yaw_rate: float = 0.2
    """rad/s (11.5°/s)."""
    cone_deg: float = 35.0
    """Under way (a set speed over ``cone_speed``) the thrusters stay within this of ahead (``allocate``'s cone)."""
    cone_speed: float = 0.3
    """m/s"""
    brake: bool = False
    """Ask for astern force to slow down. Off by default: thrusters without reverse thrust must turn round for it,
    sweeping their force sideways on the way (the ferry spins); without it the ferry coasts down to a lower speed."""

    def cone(self, speed: float) -> float | None:
        """The allocation's azimuth cone [rad] for a set speed (None: full azimuth, manoeuvring at rest)."""
        return math.radians(self.cone_deg) if speed > self.cone_speed else None

    def force(self, p: VesselParameters, state: VesselState, speed: float, heading: float) -> tuple[float, float, float]:
        """τ for surge speed ``speed`` [m/s] and ``heading`` [rad]."""
        X = p.surge_damping(speed) + p.m11 * self.k_u * (speed - state.u)
        if not self.brake:
            X = max(X, 0.0)
        r_d = self.k_psi * float(wrap_to_pi(heading - state.heading))
        r_d = max(-self.max_yaw_rate, min(self.max_yaw_rate, r_d))
        N = p.m33 * self.k_r * (r_d - state.r)
        return X, 0.0, N
