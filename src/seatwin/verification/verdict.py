"""Safety verdicts of a closed-loop run: collisions, grounding, the safety domain, perception, COLREG proxies,
path deviation and arrival — each a number and, where it fails, a reason in words.

* **collision** — the hulls (rectangles length × beam about each vessel's reference point, turned by its heading)
  overlap at some step (separating-axis test);
* **grounding** — a corner of the ownship's hull on land in the run's harbour;
* **safety domain** — the smallest centre distance to each target against ``safety_distance``;
* **perception** — when each target was first tracked (a confirmed track within 10 m), and a loss of it (untracked
  for ``track_loss_s`` or more) after that and before the closest approach;
* **COLREG proxies** — for each target the ownship gives way to (head-on, crossing from starboard, overtaking) and
  whose nominal CPA is under ``colreg_distance``: a manoeuvre (course off the nominal by ``manoeuvre_deg`` or speed
  down by ``manoeuvre_speed_frac``) begun at least ``early_s`` before the nominal closest approach and large
  (``large_deg`` course change or ``large_speed_frac`` speed loss) before it, the first turn to starboard (rules 8,
  14, 15, 16); for a target the ownship stands on for, course and speed kept (within ``manoeuvre_deg`` and
  ``manoeuvre_speed_frac``) until ``stand_on_s`` before the nominal closest approach (rule 17);
* **path** — the largest cross-track distance from the start–goal line; arrival within ``arrival_m`` of the goal.

The run *passes* without a collision, a grounding or a safety-domain breach; COLREG, perception and arrival
findings are reasons too (they do not fail the run on their own).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from seatwin.encounters.geometry import Kind, classify
from seatwin.verification.loop import RunRecord


@dataclass(frozen=True)
class VerdictRules:
    safety_distance: float = 10.0
    """m, centre to centre"""
    track_loss_s: float = 3.0
    colreg_distance: float = 20.0
    manoeuvre_deg: float = 10.0
    manoeuvre_speed_frac: float = 0.25
    early_s: float = 20.0
    large_deg: float = 30.0
    large_speed_frac: float = 0.5
    stand_on_s: float = 15.0
    arrival_m: float = 10.0


@dataclass
class TargetFindings:
    name: str
    kind: str
    nominal_cpa: float
    nominal_tcpa: float
    min_distance: float
    time_of_min: float
    collision: bool
    first_tracked: float | None
    """s after the start; None if never tracked."""
    track_lost_before_cpa: bool
    colreg_ok: bool | None
    """None when the rule proxy does not apply."""
    colreg_note: str = ""


@dataclass
class Verdict:
    passed: bool
    reasons: list[str]
    collision: bool
    grounding: bool
    min_distance: float
    colreg_ok: bool
    arrived: bool
    final_goal_distance: float
    max_cross_track: float
    targets: list[TargetFindings] = field(default_factory=list)

    def row(self) -> dict[str, object]:
        """A flat record for results tables."""
        out: dict[str, object] = {
            "passed": self.passed,
            "collision": self.collision,
            "grounding": self.grounding,
            "min_distance": round(self.min_distance, 3),
            "colreg_ok": self.colreg_ok,
            "arrived": self.arrived,
            "final_goal_distance": round(self.final_goal_distance, 3),
            "max_cross_track": round(self.max_cross_track, 3),
            "reasons": "; ".join(self.reasons),
        }
        for i, t in enumerate(self.targets, start=1):
            out[f"first_tracked_{i}"] = None if t.first_tracked is None else round(t.first_tracked, 2)
            out[f"track_lost_{i}"] = t.track_lost_before_cpa
            out[f"min_distance_{i}"] = round(t.min_distance, 3)
        return out


def _corners(
    n: NDArray[np.float64], e: NDArray[np.float64], h: NDArray[np.float64], length: float, beam: float
) -> NDArray[np.float64]:
    """(T, 4, 2) hull corners (north, east)."""
    local = np.array([[0.5, 0.5], [0.5, -0.5], [-0.5, -0.5], [-0.5, 0.5]]) * [length, beam]
    c, s = np.cos(h)[:, None], np.sin(h)[:, None]
    return np.stack([n[:, None] + c * local[:, 0] - s * local[:, 1], e[:, None] + s * local[:, 0] + c * local[:, 1]], axis=-1)


def hulls_overlap(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.bool_]:
    """(T,) whether rectangles ``a`` and ``b`` ((T, 4, 2) corners) overlap: no separating axis among their edges."""
    overlap = np.ones(a.shape[0], dtype=bool)
    for poly in (a, b):
        for k in range(2):
            edge = poly[:, k + 1] - poly[:, k]
            axis = np.stack([-edge[:, 1], edge[:, 0]], axis=-1)
            pa = np.einsum("tij,tj->ti", a, axis)
            pb = np.einsum("tij,tj->ti", b, axis)
            overlap &= (pa.max(1) >= pb.min(1)) & (pb.max(1) >= pa.min(1))
    return overlap


def _nominal(rec: RunRecord, tgt: NDArray[np.float64]) -> tuple[float, float, Kind]:
    """Nominal CPA [m], TCPA [s] and COLREG situation of a target against the ownship's straight mission at its
    start speed."""
    m = rec.mission
    course = math.atan2(m.goal_east - m.start_east, m.goal_north - m.start_north)
    t = rec.time - rec.time[0]
    on = m.start_north + m.cruise_speed * t * math.cos(course)
    oe = m.start_east + m.cruise_speed * t * math.sin(course)
    d = np.hypot(tgt[:, 0] - on, tgt[:, 1] - oe)
    i = int(np.argmin(d))
    dt = t[1] - t[0] if t.size > 1 else 1.0
    vn, ve = np.gradient(tgt[:, 0], dt)[0], np.gradient(tgt[:, 1], dt)[0]
    pn, pe = tgt[0, 0] - on[0], tgt[0, 1] - oe[0]
    bearing = float(math.remainder(math.atan2(pe, pn) - course, 2 * math.pi))
    tc = math.atan2(ve, vn)
    aspect = float(math.remainder(math.atan2(-pe, -pn) - tc, 2 * math.pi))
    kind = classify(bearing, aspect, math.remainder(tc - course, 2 * math.pi), m.cruise_speed, math.hypot(vn, ve))
    return float(d[i]), float(t[i]), kind


def judge(rec: RunRecord, harbour_map: object | None = None, rules: VerdictRules | None = None) -> Verdict:
    """The verdict of run ``rec`` (module docstring); ``harbour_map`` a :class:`~seatwin.layout.HarbourLayout` or
    :class:`~seatwin.layout.LandRaster` for grounding (None: open water)."""
    from seatwin.scenario.on_water import is_water_in

    r = rules or VerdictRules()
    t = rec.time - rec.time[0]
    own = rec.own
    length, beam = rec.sizes.get(rec.ownship, (rec.mission.length, rec.mission.beam))
    own_c = _corners(own[:, 0], own[:, 1], own[:, 2], length, beam)
    reasons: list[str] = []
    grounding = False
    if harbour_map is not None:
        wet = is_water_in(harbour_map, own_c[..., 0].ravel(), own_c[..., 1].ravel()).reshape(own_c.shape[:2])  # type: ignore[arg-type]
        dry = ~wet.all(axis=1)
        if dry.any():
            grounding = True
            k = int(np.argmax(dry))
            reasons.append(f"grounding at {t[k]:.1f} s ({own[k, 0]:.1f}, {own[k, 1]:.1f})")
    m = rec.mission
    course0 = math.atan2(m.goal_east - m.start_east, m.goal_north - m.start_north)
    heading_dev = np.degrees(np.unwrap(own[:, 2]) - course0)
    speed = np.hypot(own[:, 3], own[:, 4])
    dev_idx = (np.abs(heading_dev) > r.manoeuvre_deg) | (speed < (1 - r.manoeuvre_speed_frac) * m.cruise_speed)
    findings = []
    step = float(t[1] - t[0]) if t.size > 1 else 1.0
    for name, tgt in rec.targets.items():
        tl, tb = rec.sizes.get(name, (5.0, 2.0))
        overlap = hulls_overlap(own_c, _corners(tgt[:, 0], tgt[:, 1], tgt[:, 2], tl, tb))
        d = np.hypot(own[:, 0] - tgt[:, 0], own[:, 1] - tgt[:, 1])
        i_min = int(np.argmin(d))
        cpa_n, tcpa_n, kind = _nominal(rec, tgt)
        if overlap.any():
            reasons.append(f"collision with {name} at {t[int(np.argmax(overlap))]:.1f} s")
        elif d[i_min] < r.safety_distance:
            reasons.append(
                f"{name} passed {d[i_min]:.1f} m off, inside the {r.safety_distance:.0f} m safety domain, at {t[i_min]:.1f} s"
            )
        tracked = rec.tracked.get(name, np.zeros(t.size, bool))
        first = float(t[int(np.argmax(tracked))]) if tracked.any() else None
        lost = False
        if first is not None:
            k0, gap = int(np.argmax(tracked)), 0
            for k in range(k0, i_min + 1):
                gap = 0 if tracked[k] else gap + 1
                if gap * step >= r.track_loss_s:
                    lost = True
                    reasons.append(f"track of {name} lost at {t[k - gap + 1]:.1f} s, before the closest approach")
                    break
        else:
            reasons.append(f"{name} never tracked")
        ok: bool | None = None
        note = ""
        if kind.give_way and cpa_n < r.colreg_distance:
            before = t <= tcpa_n
            idx = np.flatnonzero(dev_idx & before)
            if not idx.size:
                ok, note = False, "no manoeuvre before the closest approach"
            else:
                k = int(idx[0])
                large = (np.abs(heading_dev[before]).max() >= r.large_deg) or (
                    speed[before].min() <= (1 - r.large_speed_frac) * m.cruise_speed
                )
                starboard = heading_dev[k] > 0 or abs(heading_dev[k]) <= r.manoeuvre_deg
                early = tcpa_n - t[k] >= r.early_s
                ok = bool(early and large and (starboard or kind is Kind.OVERTAKING))
                if not ok:
                    note = ", ".join(
                        w for w, bad in (("late", not early), ("small", not large), ("to port", not starboard)) if bad
                    )
                    note = f"give-way manoeuvre {note} (began {tcpa_n - t[k]:.0f} s before the nominal CPA)"
        elif not kind.give_way and cpa_n < r.colreg_distance:
            hold = t <= tcpa_n - r.stand_on_s
            ok = not bool((dev_idx & hold).any())
            if not ok:
                k = int(np.argmax(dev_idx & hold))
                note = f"stand-on vessel altered course or speed {tcpa_n - t[k]:.0f} s before the nominal CPA"
        if ok is False:
            reasons.append(f"COLREG ({kind.value}, {name}): {note}")
        findings.append(
            TargetFindings(
                name, kind.value, cpa_n, tcpa_n, float(d[i_min]), float(t[i_min]), bool(overlap.any()), first, lost, ok, note
            )
        )
    path = course0
    cross = -(own[:, 0] - m.start_north) * math.sin(path) + (own[:, 1] - m.start_east) * math.cos(path)
    to_goal = np.hypot(own[:, 0] - m.goal_north, own[:, 1] - m.goal_east)
    arrived = bool(to_goal.min() <= r.arrival_m)
    if not arrived:
        reasons.append(f"did not reach the goal (closest {to_goal.min():.1f} m)")
    collision = any(f.collision for f in findings)
    min_d = min((f.min_distance for f in findings), default=math.inf)
    passed = not collision and not grounding and min_d >= r.safety_distance
    return Verdict(
        passed,
        reasons,
        collision,
        grounding,
        min_d,
        all(f.colreg_ok is not False for f in findings),
        arrived,
        float(to_goal[-1]),
        float(np.abs(cross).max()),
        findings,
    )
