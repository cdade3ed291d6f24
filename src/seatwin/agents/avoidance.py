"""COLREG-aware collision avoidance by velocity obstacles, and line-of-sight guidance to a goal.

Velocity obstacles with COLREG constraints after Y. Kuwata, M. T. Wolf, D. Zarzhitsky and T. L. Huntsberger, "Safe
maritime autonomous navigation with COLREGS, using velocity obstacles", IEEE Journal of Oceanic Engineering 39(1),
2014, pp. 110–119:

* candidate velocities: ``speed_fractions`` of the desired speed × courses every ``course_step`` all round;
* a candidate is in an obstacle's velocity obstacle when, with both velocities held, the two come closer than
  ``safety_radius`` within ``horizon`` seconds;
* obstacles count only when, at the ownship's present velocity, their closest approach is nearer than
  ``safety_radius`` and less than ``reaction_time`` seconds away (a late agent has a short one);
* COLREG: for a target the ownship must give way to head-on or crossing from starboard (rules 14, 15), candidates
  that would pass it leaving it to starboard (relative velocity left of the line of sight) are forbidden too — the
  ownship turns to starboard and passes behind; a target the ownship stands on for (crossing from port, overtaking
  the ownship) is ignored until its closest approach is under ``stand_on_time`` away (rule 17(b): act when the
  give-way vessel alone cannot avoid collision);
* the chosen velocity minimises a weighted departure from the desired course and speed, a turn to port (weighted
  extra) and a change from the previous choice (hysteresis); when every candidate is blocked, the one keeping
  farthest from all obstacles;
* the give-way constraint holds only while the target is forward of the ownship's beam, and not for a target
  already passing clear to starboard (≥ half the safety radius): that pass is widened, not crossed (our departure).

Guidance: lookahead-based line of sight to the straight path from start to goal (Fossen 2011, §10.3.2), the speed
reduced within ``slow_down`` metres of the goal, the last ``lookahead`` metres (or a goal passed abeam after a
detour) steered straight for; stop within ``arrival`` metres, holding the heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from seatwin.agents.interface import Mission, Navigation, TrackEstimate
from seatwin.encounters.geometry import Kind, classify
from seatwin.geo import wrap_to_pi


@dataclass(frozen=True)
class AvoidanceParameters:
    safety_radius: float = 20.0
    """m: the closest the agent plans to pass a target (centre to centre)."""
    horizon: float = 60.0
    """s: how far ahead a velocity obstacle looks."""
    reaction_time: float = 60.0
    """s: obstacles whose closest approach is further away in time are not yet acted on."""
    stand_on_time: float = 15.0
    """s: a stand-on agent acts when the closest approach is this near (rule 17(b))."""
    course_step_deg: float = 5.0
    speed_fractions: tuple[float, ...] = (1.0, 0.75, 0.5, 0.25, 0.0)
    w_course: float = 1.0
    w_speed: float = 0.5
    w_change: float = 0.5
    w_port: float = 0.5
    """Extra cost of a turn to port (rules 14, 15, 17(c): seamen alter to starboard)."""
    lookahead: float = 20.0
    """m: LOS lookahead distance."""
    slow_down: float = 20.0
    """m: within this of the goal the speed falls as the square root of the distance left (a constant deceleration;
    the autopilot coasts down, no astern), to at least :func:`min_speed` until arrival."""
    arrival: float = 3.0
    """m"""


def los_guidance(nav: Navigation, mission: Mission, p: AvoidanceParameters) -> tuple[float, float]:
    """Desired (speed, course) to follow the straight path from the mission's start to its goal."""
    path = math.atan2(mission.goal_east - mission.start_east, mission.goal_north - mission.start_north)
    dn, de = nav.north - mission.start_north, nav.east - mission.start_east
    cross = -dn * math.sin(path) + de * math.cos(path)
    course = float(wrap_to_pi(path - math.atan2(cross, p.lookahead)))
    to_goal = math.hypot(mission.goal_north - nav.north, mission.goal_east - nav.east)
    along_left = (mission.goal_north - nav.north) * math.cos(path) + (mission.goal_east - nav.east) * math.sin(path)
    if to_goal <= p.arrival:
        return 0.0, nav.heading  # arrived: stop and hold the heading
    if along_left < p.lookahead:  # the last stretch (or past the goal after a detour): straight for the goal
        course = math.atan2(mission.goal_east - nav.east, mission.goal_north - nav.north)
    return max(min_speed(mission, p), mission.cruise_speed * min(1.0, math.sqrt(to_goal / p.slow_down))), course


def min_speed(mission: Mission, p: AvoidanceParameters) -> float:
    """The slowest approach to the goal (a quarter of the cruise speed, at most 0.3 m/s)."""
    return min(0.3, 0.25 * mission.cruise_speed)


def _cpa(pn: float, pe: float, wn: float, we: float) -> tuple[float, float]:
    """(distance, time ≥ 0) of the closest approach of relative position p moving at relative velocity −w."""
    w2 = wn * wn + we * we
    t = 0.0 if w2 < 1e-12 else max(0.0, (pn * wn + pe * we) / w2)
    return math.hypot(pn - wn * t, pe - we * t), t


def choose_velocity(
    nav: Navigation,
    desired_speed: float,
    desired_course: float,
    obstacles: list[TrackEstimate],
    p: AvoidanceParameters,
    previous_course: float | None = None,
    engaged: dict[int, Kind] | None = None,
    speed_scale: float | None = None,
) -> tuple[float, float, dict[int, Kind]]:
    """(speed, course) to sail now, and the obstacles acted on with their COLREG situation. An obstacle in
    ``engaged`` (acted on in the previous step) stays acted on, in the situation it was first classified as, until
    its closest approach is past — so neither a noisy track nor the ownship's own turn (which moves a head-on target
    to its port side) makes the agent swing back. Candidate speeds are fractions of ``speed_scale`` (default the
    desired speed): an agent stopped at its goal (desired speed 0) can still get out of a target's way."""
    engaged = engaged or {}
    active, colreg, acting = [], [], {}
    for o in obstacles:
        pn, pe = o.north - nav.north, o.east - nav.east
        d, t = _cpa(pn, pe, nav.v_north - o.v_north, nav.v_east - o.v_east)
        rng = math.hypot(pn, pe)
        if o.id in engaged and t > 0:
            kind = engaged[o.id]
        else:
            if d >= p.safety_radius or (rng > p.safety_radius and t <= 0):
                continue
            bearing = float(wrap_to_pi(math.atan2(pe, pn) - nav.heading))
            o_course = math.atan2(o.v_east, o.v_north)
            aspect = float(wrap_to_pi(math.atan2(-pe, -pn) - o_course))
            rel = float(wrap_to_pi(o_course - nav.course))
            kind = classify(bearing, aspect, rel, nav.speed, math.hypot(o.v_north, o.v_east))
            limit = p.reaction_time if kind.give_way else min(p.reaction_time, p.stand_on_time)
            if t > limit and rng > p.safety_radius:
                continue
        active.append(o)
        acting[o.id] = kind
        # the give-way constraint holds while the target is forward of the ownship's beam (Kuwata et al. apply it
        # before the crossing); abaft the beam it would force the ownship round after a target already passing
        forward = abs(float(wrap_to_pi(math.atan2(pe, pn) - nav.heading))) < math.pi / 2
        # a target already passing clear to starboard (at least half the safety radius off) is passed wider on the
        # same side rather than crossed ahead of (our departure from Kuwata et al., whose constraint would turn the
        # ownship across its bow)
        wn, we = nav.v_north - o.v_north, nav.v_east - o.v_east
        clear_to_starboard = (pn * we - pe * wn) < 0 and d >= 0.5 * p.safety_radius
        colreg.append(kind in (Kind.HEAD_ON, Kind.CROSSING_GIVE_WAY) and forward and not clear_to_starboard)
    if not active:
        return desired_speed, desired_course, {}
    courses = desired_course + np.radians(np.arange(-180.0, 180.0, p.course_step_deg))
    fractions = np.asarray(p.speed_fractions, dtype=float)
    scale = desired_speed if speed_scale is None else max(speed_scale, desired_speed)
    speeds = np.repeat(scale * fractions, courses.size)
    crs = np.tile(courses, fractions.size)
    vn, ve = speeds * np.cos(crs), speeds * np.sin(crs)
    blocked = np.zeros(speeds.size, dtype=bool)
    clearance = np.full(speeds.size, np.inf)
    for o, rule in zip(active, colreg):
        pn, pe = o.north - nav.north, o.east - nav.east
        wn, we = vn - o.v_north, ve - o.v_east
        w2 = np.maximum(wn * wn + we * we, 1e-12)
        t = np.clip((pn * wn + pe * we) / w2, 0.0, p.horizon)
        d = np.hypot(pn - wn * t, pe - we * t)
        clearance = np.minimum(clearance, d)
        blocked |= d < p.safety_radius
        if rule:
            blocked |= (pn * we - pe * wn) < 0  # relative velocity left of the line of sight: leaves it to starboard
    signed = np.asarray(wrap_to_pi(crs - desired_course))
    dev = np.abs(signed)
    cost = (
        p.w_course * dev / math.pi
        + p.w_port * np.maximum(-signed, 0.0) / math.pi
        + p.w_speed * np.abs(speeds - desired_speed) / max(scale, 0.1)
    )
    if previous_course is not None:
        cost += p.w_change * np.abs(np.asarray(wrap_to_pi(crs - previous_course))) / math.pi
    free = np.flatnonzero(~blocked)
    i = int(free[np.argmin(cost[free])]) if free.size else int(np.argmax(clearance - 1e-3 * cost))
    return float(speeds[i]), float(wrap_to_pi(crs[i])), acting
