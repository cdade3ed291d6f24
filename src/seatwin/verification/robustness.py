"""A continuous safety robustness of a closed-loop run: how close the ownship came to breaching the safety domain.

The minimum distance is flat (the agent keeps its planning radius) outside small failure pockets, so a search that
follows it has nothing to climb. The **time to breach** sees more: at each step, with both vessels' velocities held,
the seconds until their centres come within the safety distance (0 inside it). A step's margin is its time to breach
when the held velocities lead into the safety domain, else ``horizon`` plus how far [m] outside it their closest
approach stays (so courses that never threaten still rank by how near they pass). A run's robustness is the smallest
margin over its steps and targets — an agent that turns away at the last moment had a small one, one that turned
early a large one — and, when the run failed (collision, grounding or a breach), the breach's depth in metres taken
negative. So the sign says pass (≥ 0) or fail (< 0), and a falsifier (:func:`seatwin.encounters.adaptive_search`)
can descend it. Black box: only the sailed states are used, so it applies to any agent (in process or over gRPC).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from seatwin.verification.loop import RunRecord
from seatwin.verification.verdict import Verdict


def time_to_breach(
    rel_north: NDArray[np.float64],
    rel_east: NDArray[np.float64],
    rel_v_north: NDArray[np.float64],
    rel_v_east: NDArray[np.float64],
    distance: float,
) -> NDArray[np.float64]:
    """Per sample, the time [s] until the relative position p + w·τ first lies within ``distance`` of 0 (the smallest
    τ ≥ 0 with |p + w τ| ≤ distance): 0 when already within, ∞ when never."""
    p2 = rel_north**2 + rel_east**2
    pw = rel_north * rel_v_north + rel_east * rel_v_east
    w2 = rel_v_north**2 + rel_v_east**2
    disc = pw**2 - w2 * (p2 - distance**2)
    out = np.full(p2.shape, np.inf)
    approaching = (pw < 0) & (disc >= 0) & (w2 > 1e-12)
    out[approaching] = (-pw[approaching] - np.sqrt(disc[approaching])) / w2[approaching]
    out[p2 <= distance**2] = 0.0
    return out


def closest_approach_distance(
    rel_north: NDArray[np.float64],
    rel_east: NDArray[np.float64],
    rel_v_north: NDArray[np.float64],
    rel_v_east: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Per sample, the smallest |p + w τ| over τ ≥ 0 (the predicted closest approach with velocities held)."""
    w2 = rel_v_north**2 + rel_v_east**2
    tau = np.where(w2 > 1e-12, -(rel_north * rel_v_north + rel_east * rel_v_east) / np.maximum(w2, 1e-12), 0.0)
    tau = np.maximum(tau, 0.0)
    return np.hypot(rel_north + rel_v_north * tau, rel_east + rel_v_east * tau)


def _velocity(north: NDArray[np.float64], east: NDArray[np.float64], t: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
    if t.size < 2:
        return np.zeros_like(north), np.zeros_like(east)
    return np.gradient(north, t), np.gradient(east, t)


def robustness(record: RunRecord, verdict: Verdict, safety_distance: float, horizon: float = 60.0) -> float:
    """The run's robustness (module docstring): if it passed, the smallest margin over its steps and targets (a
    finite time to breach [s], else ``horizon`` + the predicted closest approach's distance outside the safety
    distance [m]); if it failed, −(how far inside the safety distance it came) [m], at most −0.001."""
    if not verdict.passed:
        return -max(safety_distance - verdict.min_distance, 1e-3)
    t = record.time
    own = record.own
    c, s = np.cos(own[:, 2]), np.sin(own[:, 2])
    own_vn, own_ve = own[:, 3] * c - own[:, 4] * s, own[:, 3] * s + own[:, 4] * c
    worst = math.inf
    for tgt in record.targets.values():
        vn, ve = _velocity(tgt[:, 0], tgt[:, 1], t)
        rel = (tgt[:, 0] - own[:, 0], tgt[:, 1] - own[:, 1], vn - own_vn, ve - own_ve)
        ttb = time_to_breach(*rel, safety_distance)
        margin = np.where(np.isfinite(ttb), ttb, horizon + closest_approach_distance(*rel) - safety_distance)
        worst = min(worst, float(margin.min()) if margin.size else math.inf)
    return worst
