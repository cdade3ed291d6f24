"""Encounters placed in the world: the encounter frame rotated and moved onto water, and every vessel's path.

Open water (harbour ``none``): the ownship starts at the origin on a course drawn from the seed. A harbour (the
built-in layout, ``ravnkloa``, a raster): the point of the ownship's (last) closest approach and its course are drawn
— on the layout's channel, on a raster's water cells, for a harbour of :data:`ENCOUNTER_AREAS` on its water within
the area (``ravnkloa``: the canal crossing milliAmpere serves) — until every vessel's path for the whole scenario,
widened by ``clearance`` metres to each side, lies on water (:func:`seatwin.scenario.on_water.is_water_in`); the
refused draws are counted (:attr:`Placement.rejected`). None found in ``tries`` draws: a
:class:`NoPlacementError` (an :class:`~seatwin.errors.InputError`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.dynamics import WaypointPath, follow_waypoints
from seatwin.encounters.geometry import target_start
from seatwin.encounters.space import Encounter
from seatwin.errors import InputError
from seatwin.layout import HarbourLayout, LandRaster, harbour_map, harbour_name
from seatwin.scenario.on_water import is_water_in

SAMPLE_DT = 0.1
"""Paths are sampled at 10 Hz (the scenario CSV's rate)."""


class NoPlacementError(InputError):
    """The encounter has no place on the harbour's water (every draw put a path on land)."""


@dataclass(frozen=True)
class Area:
    """Where a harbour's encounters happen: the ownship's closest approach within ``radius`` [m] of a point
    (north, east [m], scenario frame)."""

    north: float
    east: float
    radius: float


ENCOUNTER_AREAS: dict[str, Area] = {"ravnkloa": Area(-45.0, 10.0, 120.0)}
"""Encounter areas of named harbours. ``ravnkloa``: the canal crossing between Ravnkloa and Fosenkaia that milliAmpere
serves — centred on milliAmpere's positions in the Gemini recordings (north −61…−16 m, east −12…70 m), 120 m round,
the width of the canal and the basin beside the crossing."""


@dataclass(frozen=True)
class Placement:
    """The encounter frame in the scenario frame: the ownship's start [m] and course [rad]; ``rejected``: the draws
    refused (a path off the water) before this one."""

    north: float
    east: float
    course: float
    rejected: int = 0

    def to_world(
        self, n: NDArray[np.float64] | float, e: NDArray[np.float64] | float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        c, s = math.cos(self.course), math.sin(self.course)
        n, e = np.asarray(n, float), np.asarray(e, float)
        return self.north + c * n - s * e, self.east + s * n + c * e


@dataclass(frozen=True)
class EncounterPaths:
    """Every vessel's path without avoidance: the ownship's first, then the targets' in order."""

    ownship: WaypointPath
    targets: tuple[WaypointPath, ...]


SLACK_S = 40.0
"""The scenario runs this long past the encounter's :attr:`~seatwin.encounters.space.Encounter.duration`: the
ownship's scripted path reaches its goal (``run_out`` seconds of sailing past the closest approach) and waits there,
so the closed loop's agent has this long to spare for its detours."""


def total_duration(encounter: Encounter) -> float:
    """The scenario's length [s]: the encounter's duration plus :data:`SLACK_S`."""
    return encounter.duration + SLACK_S


def paths(encounter: Encounter, placement: Placement, start_time: float) -> EncounterPaths:
    """The ownship and targets sailing straight through ``encounter`` from ``start_time``, sampled at 10 Hz for
    :func:`total_duration`; the ownship stops at its goal after the encounter's duration."""
    d = total_duration(encounter)
    t = SAMPLE_DT * np.arange(int(round(d / SAMPLE_DT)) + 1)
    along = encounter.own_speed * np.minimum(t, encounter.duration)
    n, e = placement.to_world(along, np.zeros_like(along))
    own = WaypointPath(start_time + t, n, e, np.full(t.shape, placement.course))
    targets = []
    for tg in encounter.targets:
        s = target_start(encounter.own_speed, tg)
        a = placement.to_world(s.north, s.east)
        b = placement.to_world(s.north + tg.speed * d * math.cos(s.course), s.east + tg.speed * d * math.sin(s.course))
        targets.append(
            follow_waypoints([(float(a[0]), float(a[1])), (float(b[0]), float(b[1]))], tg.speed, start_time, d, SAMPLE_DT)
        )
    return EncounterPaths(own, tuple(targets))


def _lines(encounter: Encounter, placement: Placement) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Every vessel's straight path once a second (what :func:`paths` samples at 10 Hz), scenario frame."""
    t = np.arange(0.0, total_duration(encounter) + 1.0, 1.0)
    n_loc, e_loc = [encounter.own_speed * np.minimum(t, encounter.duration)], [np.zeros_like(t)]
    for tg in encounter.targets:
        s = target_start(encounter.own_speed, tg)
        n_loc.append(s.north + tg.speed * t * math.cos(s.course))
        e_loc.append(s.east + tg.speed * t * math.sin(s.course))
    return placement.to_world(np.concatenate(n_loc), np.concatenate(e_loc))


def _on_water(harbour: HarbourLayout | LandRaster, encounter: Encounter, placement: Placement, clearance: float) -> bool:
    n, e = _lines(encounter, placement)
    for dn, de in ((0.0, 0.0), (clearance, 0.0), (-clearance, 0.0), (0.0, clearance), (0.0, -clearance)):
        if not is_water_in(harbour, n + dn, e + de).all():
            return False
    return True


def _water_cells(harbour: LandRaster, area: Area | None) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """The raster's water cells (row, column), within ``area`` if one is given."""
    rows, cols = np.nonzero(harbour.water)
    if area is not None:
        cn, ce = harbour.alignment.to_map(area.north, area.east)
        n_map = harbour.origin_north + (rows + 0.5) * harbour.resolution
        e_map = harbour.origin_east + (cols + 0.5) * harbour.resolution
        inside = np.hypot(n_map - cn, e_map - ce) <= area.radius
        rows, cols = rows[inside], cols[inside]
    return rows, cols


def _candidate(
    harbour: HarbourLayout | LandRaster, cells: tuple[NDArray[np.intp], NDArray[np.intp]] | None, rng: np.random.Generator
) -> tuple[float, float]:
    if isinstance(harbour, HarbourLayout) or cells is None:
        assert isinstance(harbour, HarbourLayout)
        return float(rng.uniform(harbour.north_min, harbour.north_max)), float(
            rng.uniform(-harbour.half_width, harbour.half_width)
        )
    rows, cols = cells
    i = int(rng.integers(rows.size))
    n_map = harbour.origin_north + (rows[i] + rng.random()) * harbour.resolution
    e_map = harbour.origin_east + (cols[i] + rng.random()) * harbour.resolution
    n, e = harbour.alignment.from_map(n_map, e_map)
    return float(n), float(e)


def place(
    encounter: Encounter, harbour: str, seed: int, start_time: float, clearance: float = 8.0, tries: int = 3000
) -> tuple[Placement, EncounterPaths]:
    """A placement of ``encounter`` in ``harbour`` (name or raster path) drawn from ``seed``, and its paths (module
    docstring)."""
    rng = np.random.default_rng(seed)
    m = harbour_map(harbour)
    if m is None:
        pl = Placement(0.0, 0.0, float(rng.uniform(-math.pi, math.pi)))
        return pl, paths(encounter, pl, start_time)
    area = ENCOUNTER_AREAS.get(harbour_name(harbour) or "")
    cells = _water_cells(m, area) if isinstance(m, LandRaster) else None
    if cells is not None and not cells[0].size:
        where = "" if area is None else f" within {area.radius:.0f} m of ({area.north:.0f}, {area.east:.0f})"
        raise InputError(harbour, f"the harbour's raster has no water{where} to place an encounter on")
    to_cpa = encounter.own_speed * max(t.tcpa for t in encounter.targets)
    for k in range(tries):
        n, e = _candidate(m, cells, rng)
        course = float(rng.uniform(-math.pi, math.pi))
        pl = Placement(n - to_cpa * math.cos(course), e - to_cpa * math.sin(course), course, k)
        if _on_water(m, encounter, pl, clearance):
            return pl, paths(encounter, pl, start_time)
    raise NoPlacementError(
        harbour,
        f"found no place on water for the encounter ({total_duration(encounter):.0f} s, ownship {encounter.own_speed:.1f} m/s) "
        f"in {tries} tries with {clearance} m clearance: the harbour is too small for it; use a shorter encounter or open water",
    )
