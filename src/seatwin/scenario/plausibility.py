"""Is a sampled trajectory physically possible for a harbour vessel? The one place that says.

Used when a trajectory is read (Gemini CSV) and when one is made from GNSS logs (antenna fixes
and the ground truth written from them), so a file seatwin writes is one it reads back.

* A *teleport*: two consecutive samples further apart than ``max_speed`` × their time step.
* A *heading spike*: one sample whose heading jumps more than :data:`SPIKE_JUMP_DEG` away from both
  neighbours and back, each step turning faster than ``max_turn_rate``. The vessels of the Gemini
  scenarios turn at most 13 °/s (the four real files), small harbour boats rarely over 30 °/s; a
  sample 90° off for 0.1 s (900 °/s) and back is a corrupt row, not a manoeuvre. A turn that does
  not come back is never a spike (a single-antenna course can flip when a vessel reverses).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

MAX_SPEED = 30.0
"""Default bound [m/s] on a vessel's speed between two samples (about 58 kn)."""
MAX_TURN_RATE = 180.0
"""Default bound [°/s] on the turn rate of both steps of a heading spike (6 × the fastest real turn)."""
SPIKE_JUMP_DEG = 90.0
"""A heading spike's sample is more than this off both neighbours, which agree within it."""


@dataclass(frozen=True)
class Teleport:
    """Samples ``index`` → ``index + 1`` are ``step`` metres apart in ``dt`` seconds; ``count`` steps in all are too fast."""

    index: int
    step: float
    dt: float
    count: int = 1

    @property
    def speed(self) -> float:
        return self.step / self.dt if self.dt > 0 else float("inf")


@dataclass(frozen=True)
class HeadingSpike:
    """Sample ``index`` is off its neighbours: headings [°] before, at and after it, and the time span [s]."""

    index: int
    before: float
    at: float
    after: float
    span: float

    @property
    def jump(self) -> float:
        """The smaller of the two jumps [°] into and out of the spike."""
        return float(min(abs(_wrap180(self.at - self.before)), abs(_wrap180(self.after - self.at))))


def _wrap180(x: ArrayLike) -> np.ndarray:
    return (np.asarray(x, float) + 180.0) % 360.0 - 180.0


def first_teleport(time: ArrayLike, north: ArrayLike, east: ArrayLike, max_speed: float = MAX_SPEED) -> Teleport | None:
    """The first step faster than ``max_speed`` [m/s] (``inf``: none), or ``None``; NaN counts as too fast."""
    t, n, e = (np.asarray(a, float) for a in (time, north, east))
    dt = np.diff(t)
    step = np.hypot(np.diff(n), np.diff(e))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        speed = step / dt
    bad = np.flatnonzero(~(speed <= max_speed))
    if not bad.size:
        return None
    k = int(bad[0])
    return Teleport(k, float(step[k]), float(dt[k]), int(bad.size))


def first_heading_spike(
    time: ArrayLike, heading_deg: ArrayLike, max_turn_rate: float = MAX_TURN_RATE, jump_deg: float = SPIKE_JUMP_DEG
) -> HeadingSpike | None:
    """The first heading spike (see the module docstring) of headings in degrees, or ``None``."""
    t, h = np.asarray(time, float), np.asarray(heading_deg, float)
    if len(h) < 3:
        return None
    d = _wrap180(np.diff(h))
    dt = np.diff(t)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        rate = np.abs(d) / dt
    d_in, d_out = d[:-1], d[1:]
    back = np.abs(_wrap180(h[2:] - h[:-2]))
    spike = (
        (np.abs(d_in) > jump_deg)
        & (np.abs(d_out) > jump_deg)
        & (back <= jump_deg)
        & (rate[:-1] > max_turn_rate)
        & (rate[1:] > max_turn_rate)
    )
    hits = np.flatnonzero(spike)
    if not hits.size:
        return None
    k = int(hits[0]) + 1
    return HeadingSpike(k, float(h[k - 1]), float(h[k]), float(h[k + 1]), float(t[k + 1] - t[k - 1]))
