"""COLREG encounters as geometry: where a target starts so that, without avoidance, it meets the ownship with a given
closest point of approach (CPA) after a given time (TCPA).

The encounter frame: the ownship starts at the origin on course 0 (north) at ``own_speed``; each target sails a
straight line at ``speed`` on course ``relative_course`` (target course − ownship course). A target's CPA is signed:
positive when, at the closest approach, the target is to starboard of the ownship (east in this frame; exactly ahead
or astern counts as starboard when it is ahead). Its start follows: the relative position at TCPA is ``cpa`` times the
unit normal of the relative velocity on that side, and the target sails back from there for TCPA seconds.

The COLREG situation is classified from the start (:func:`situation`), by the usual sectors (COLREG rules 13–15; the
22.5° abaft the beam of rule 13 gives the 112.5° limits): the ownship overtakes when it is more than 112.5° off the
target's bow and faster; head-on when the courses are reciprocal within ``HEAD_ON_COURSE_DEG`` and the target is
within ``HEAD_ON_BEARING_DEG`` of the ownship's bow; otherwise a crossing, the ownship giving way to a target on its
starboard side (rule 15) and standing on for one to port (rule 17).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

from seatwin.errors import ParameterError
from seatwin.geo import wrap_to_pi


class Kind(str, Enum):
    HEAD_ON = "head_on"
    CROSSING_GIVE_WAY = "crossing_give_way"
    CROSSING_STAND_ON = "crossing_stand_on"
    OVERTAKING = "overtaking"
    OVERTAKEN = "overtaken"

    @property
    def give_way(self) -> bool:
        """Whether the ownship must keep out of the way (rules 13–15; both give way head-on)."""
        return self in (Kind.HEAD_ON, Kind.CROSSING_GIVE_WAY, Kind.OVERTAKING)


HEAD_ON_COURSE_DEG = 15.0
"""Courses within this of reciprocal (and the target near the bow) make a head-on situation."""
HEAD_ON_BEARING_DEG = 22.5
ABAFT_BEAM_DEG = 112.5


@dataclass(frozen=True)
class TargetGeometry:
    """One target's encounter without avoidance."""

    cpa: float
    """Signed distance at the closest approach [m] (positive: the target passes to starboard of the ownship)."""
    tcpa: float
    """Time to the closest approach from the encounter's start [s]."""
    relative_course: float
    """Target course − ownship course [rad]."""
    speed: float
    """Target speed [m/s]."""

    def __post_init__(self) -> None:
        for name in ("cpa", "tcpa", "relative_course", "speed"):
            if not math.isfinite(getattr(self, name)):
                raise ParameterError(name, f"expected a finite number, got {getattr(self, name)!r}")
        if self.tcpa <= 0:
            raise ParameterError("tcpa", f"expected a time to the closest approach > 0 s, got {self.tcpa}")
        if self.speed < 0:
            raise ParameterError("speed", f"expected a target speed ≥ 0 m/s, got {self.speed}")


@dataclass(frozen=True)
class Start:
    """A target's start in the encounter frame and what the ownship sees of it there."""

    north: float
    east: float
    course: float
    """rad, in the encounter frame (the ownship's course is 0)."""
    bearing: float
    """Relative bearing of the target from the ownship's bow at the start [rad], (−π, π]."""
    range: float
    """m"""
    aspect: float
    """Relative bearing of the ownship from the target's bow at the start [rad]."""


def target_start(own_speed: float, target: TargetGeometry) -> Start:
    """Where ``target`` starts so that it passes the ownship (``own_speed`` north from the origin) as specified."""
    if not (own_speed >= 0 and math.isfinite(own_speed)):
        raise ParameterError("own_speed", f"expected an ownship speed ≥ 0 m/s, got {own_speed!r}")
    c = target.relative_course
    vt = (target.speed * math.cos(c), target.speed * math.sin(c))
    vr = (vt[0] - own_speed, vt[1])
    nr = math.hypot(*vr)
    if nr < 1e-6:
        raise ParameterError("speed", "the target moves with the ownship (no relative motion): no closest approach")
    normal = (-vr[1] / nr, vr[0] / nr)
    if normal[1] < 0 or (normal[1] == 0 and normal[0] < 0):
        normal = (-normal[0], -normal[1])
    at_cpa = (own_speed * target.tcpa + target.cpa * normal[0], target.cpa * normal[1])
    n0, e0 = at_cpa[0] - vt[0] * target.tcpa, at_cpa[1] - vt[1] * target.tcpa
    bearing = math.atan2(e0, n0)
    aspect = float(wrap_to_pi(math.atan2(-e0, -n0) - c))
    return Start(n0, e0, float(wrap_to_pi(c)), bearing, math.hypot(n0, e0), aspect)


def classify(bearing: float, aspect: float, relative_course: float, own_speed: float, target_speed: float) -> Kind:
    """The COLREG situation from what the ownship sees (module docstring): the target's relative ``bearing`` from the
    ownship's bow, the ownship's ``aspect`` from the target's bow, ``relative_course`` (target − ownship) [rad]."""
    if abs(aspect) > math.radians(ABAFT_BEAM_DEG) and own_speed > target_speed:
        return Kind.OVERTAKING
    if abs(bearing) > math.radians(ABAFT_BEAM_DEG):
        return Kind.OVERTAKEN
    reciprocal = abs(float(wrap_to_pi(relative_course - math.pi))) <= math.radians(HEAD_ON_COURSE_DEG)
    if reciprocal and abs(bearing) <= math.radians(HEAD_ON_BEARING_DEG):
        return Kind.HEAD_ON
    return Kind.CROSSING_GIVE_WAY if bearing > 0 else Kind.CROSSING_STAND_ON


def situation(own_speed: float, target: TargetGeometry) -> Kind:
    """The COLREG situation of ``target`` with the ownship at the encounter's start (module docstring)."""
    s = target_start(own_speed, target)
    return classify(s.bearing, s.aspect, target.relative_course, own_speed, target.speed)


def closest_approach(own: tuple[float, float, float, float], target: tuple[float, float, float, float]) -> tuple[float, float]:
    """(distance at CPA [m], time to CPA [s], ≥ 0) of two constant-velocity vessels given as (north, east, v_north,
    v_east)."""
    dn, de = target[0] - own[0], target[1] - own[1]
    vn, ve = target[2] - own[2], target[3] - own[3]
    v2 = vn * vn + ve * ve
    t = 0.0 if v2 < 1e-12 else max(0.0, -(dn * vn + de * ve) / v2)
    return math.hypot(dn + vn * t, de + ve * t), t
