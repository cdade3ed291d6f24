"""Two azimuth thrusters: thrust allocation τ → (angle, thrust) per thruster, and the actuators' rate limits.

Thruster i sits at ``(x_i, y_i)`` in the body frame and pushes with ``f_i ≥ 0`` [N] along its azimuth ``α_i`` (0 =
ahead, clockwise positive): its force (f cos α, f sin α) and moment x_i·f sin α − y_i·f cos α.

Allocation (Fossen 2011, §11.2.2, the extended thrust configuration): the four force components
(F_x1, F_y1, F_x2, F_y2) that give τ with the least norm (``T⁺ τ`` for the 3 × 4 configuration matrix ``T``),
then each thruster's azimuth and thrust from its component pair. A thrust above ``max_thrust`` scales the whole
τ down (its direction kept); a thruster asked for almost nothing keeps its azimuth.

Actuators: each step the azimuth turns towards the command by at most ``max_angle_rate``·dt (the shorter way; the
thrusters turn all round) and the thrust moves by at most ``max_thrust_rate``·dt — the thrust acts along the
*actual* azimuth, so a slow azimuth costs force until it gets there.

milliAmpere (:data:`MILLIAMPERE_THRUSTERS`): two thrusters on the centre line 1.8 m fore and aft of the origin,
500 N each, azimuth rates 34.46°/s and 37.53°/s — as in the public implementations of Pedersen's (2019) model (the
rates cite its Table 3.9). The thrust rate (250 N/s: zero to full in 2 s) is our assumption; no reverse thrust
(the azimuths turn instead).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np
from numpy.typing import NDArray

from seatwin.geo import wrap_to_pi


@dataclass(frozen=True)
class ThrusterConfig:
    """Where the thrusters are and how fast they act (one entry per thruster)."""

    x: tuple[float, ...]
    """Body-frame x of each thruster [m]."""
    y: tuple[float, ...]
    """Body-frame y of each thruster [m]."""
    max_thrust: tuple[float, ...]
    """N"""
    max_angle_rate: tuple[float, ...]
    """rad/s"""
    max_thrust_rate: tuple[float, ...]
    """N/s"""
    min_force: float = 1.0
    """Below this force [N] a thruster keeps its azimuth (no spinning on rounding noise)."""

    def configuration(self) -> NDArray[np.float64]:
        """T (3 × 2n): τ = T · (F_x1, F_y1, F_x2, F_y2, …)."""
        cols = []
        for x, y in zip(self.x, self.y):
            cols += [[1.0, 0.0, -y], [0.0, 1.0, x]]
        return np.array(cols).T


MILLIAMPERE_THRUSTERS = ThrusterConfig(
    x=(1.8, -1.8),
    y=(0.0, 0.0),
    max_thrust=(500.0, 500.0),
    max_angle_rate=(math.radians(34.46), math.radians(37.53)),
    max_thrust_rate=(250.0, 250.0),
)


@dataclass(frozen=True)
class ThrusterState:
    """Actual azimuths [rad] and thrusts [N] of the thrusters."""

    angle: tuple[float, ...]
    thrust: tuple[float, ...]

    @classmethod
    def idle(cls, n: int = 2) -> ThrusterState:
        return cls((0.0,) * n, (0.0,) * n)


@cache
def _pseudo_inverse(config: ThrusterConfig) -> NDArray[np.float64]:
    """T⁺ of a configuration (computed once per configuration: the loop allocates every step)."""
    return np.linalg.pinv(config.configuration())


def allocate(
    config: ThrusterConfig, tau: tuple[float, float, float], current: ThrusterState, cone: float | None = None
) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Commanded (azimuths, thrusts) for the generalised force ``tau``; see the module docstring.

    ``cone`` [rad]: under way, keep every azimuth within ``cone`` of ahead — each thruster's forward component kept
    (at least ``min_force``), its sideways one cut to ``forward · tan(cone)`` — so that the thrusters steer like
    rudders instead of swinging broadside (and back, at their rate limit) whenever the surge demand drops; the yaw
    moment is what is given up."""
    F = _pseudo_inverse(config) @ np.asarray(tau, dtype=float)
    fx, fy = F[0::2], F[1::2]
    if cone is not None:
        fx = np.maximum(fx, config.min_force)
        lim = fx * math.tan(cone)
        fy = np.clip(fy, -lim, lim)
    thrust = np.hypot(fx, fy)
    limit = np.asarray(config.max_thrust, dtype=float)
    over = float(np.max(thrust / limit))
    if over > 1.0:
        thrust = thrust / over
    angle = tuple(
        float(np.arctan2(fy[i], fx[i])) if thrust[i] >= config.min_force else current.angle[i] for i in range(len(thrust))
    )
    return angle, tuple(float(f) if f >= config.min_force else 0.0 for f in thrust)


def actuate(
    config: ThrusterConfig, state: ThrusterState, angle: tuple[float, ...], thrust: tuple[float, ...], dt: float
) -> ThrusterState:
    """The thrusters after ``dt`` seconds of moving towards the command at their rate limits."""
    new_a, new_f = [], []
    for i in range(len(state.angle)):
        da = float(wrap_to_pi(angle[i] - state.angle[i]))
        step = config.max_angle_rate[i] * dt
        new_a.append(float(wrap_to_pi(state.angle[i] + max(-step, min(step, da)))))
        target = max(0.0, min(config.max_thrust[i], thrust[i]))
        df = target - state.thrust[i]
        fstep = config.max_thrust_rate[i] * dt
        new_f.append(state.thrust[i] + max(-fstep, min(fstep, df)))
    return ThrusterState(tuple(new_a), tuple(new_f))


def generalised_force(config: ThrusterConfig, state: ThrusterState) -> tuple[float, float, float]:
    """τ = (X, Y, N) the thrusters exert in ``state``."""
    X = Y = N = 0.0
    for x, y, a, f in zip(config.x, config.y, state.angle, state.thrust):
        fx, fy = f * math.cos(a), f * math.sin(a)
        X += fx
        Y += fy
        N += x * fy - y * fx
    return X, Y, N
