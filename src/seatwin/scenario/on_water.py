"""Scenarios against their harbour's water: vessels on land (a warning), and the map alignment fitted to them.

* :func:`land_samples` — each vessel's samples on land in a harbour map (scenario frame, the map's
  alignment applied);
* :func:`warn_on_land` — an :class:`OnLandWarning` per vessel on land for more than a few samples,
  naming it and when;
* :func:`fit_harbour_alignment` — :func:`seatwin.layout.alignment.fit_alignment` over every vessel
  of the given scenario files (``seatwin harbour fit-alignment``).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from seatwin.errors import InputError
from seatwin.layout import HarbourLayout, LandRaster, harbour_map
from seatwin.layout.alignment import IDENTITY, AlignmentFit, VesselPath, fit_alignment
from seatwin.scenario.model import Scenario

LAND_SAMPLES_ALLOWED = 5
"""A vessel may touch land in this many samples (0.5 s at 10 Hz: a hull at a quay) before a warning."""


class OnLandWarning(UserWarning):
    """A scenario's vessel is on its harbour's land for more than :data:`LAND_SAMPLES_ALLOWED` samples."""


@dataclass(frozen=True)
class LandSamples:
    """One vessel's samples on land: how many of how many, and when the first and last were."""

    vessel: str
    count: int
    samples: int
    first_time: float
    last_time: float
    starts_on_land: bool


def is_water_in(harbour: HarbourLayout | LandRaster, north: np.ndarray, east: np.ndarray) -> np.ndarray:
    """Scenario-frame points on ``harbour``'s water (outside a raster counts as land)."""
    if isinstance(harbour, LandRaster):
        return harbour.is_water(north, east, outside=False)
    return np.asarray(harbour.is_water(north, east), dtype=bool)


def land_samples(scenario: Scenario, harbour: HarbourLayout | LandRaster | None) -> list[LandSamples]:
    """Every vessel of ``scenario`` with at least one sample on ``harbour``'s land (outside a raster counts as land)."""
    if harbour is None:
        return []
    out = []
    for v in scenario.vessels:
        tr = v.trajectory
        land = ~is_water_in(harbour, tr.north, tr.east)
        if land.any():
            idx = np.flatnonzero(land)
            out.append(
                LandSamples(v.name, int(idx.size), len(tr.time), float(tr.time[idx[0]]), float(tr.time[idx[-1]]), bool(land[0]))
            )
    return out


def warn_on_land(scenario: Scenario, harbour: object, allowed: int = LAND_SAMPLES_ALLOWED) -> list[LandSamples]:
    """Warn (:class:`OnLandWarning`) for each vessel of ``scenario`` on ``harbour``'s land in more than
    ``allowed`` samples (or at its start); returns those vessels. A harbour whose map cannot be found is skipped
    (simulating it says what is missing)."""
    try:
        m = harbour_map(harbour)
    except InputError:
        return []
    bad = [s for s in land_samples(scenario, m) if s.count > allowed or s.starts_on_land]
    for s in bad:
        start = " (it starts there)" if s.starts_on_land else ""
        warnings.warn(
            f"{scenario.source}: vessel {s.vessel!r} is on land in harbour {harbour!r} in {s.count} of {s.samples} samples"
            f"{start}, first at t = {s.first_time - scenario.start:.1f} s (POSIX {s.first_time:.1f}), last at "
            f"t = {s.last_time - scenario.start:.1f} s (the wrong harbour, or its map not aligned to this scenario: "
            "seatwin harbour fit-alignment)",
            OnLandWarning,
            stacklevel=2,
        )
    return bad


def vessel_paths(scenarios: Sequence[Scenario]) -> list[VesselPath]:
    """Every vessel of every scenario as a :class:`VesselPath` labelled ``scenario/vessel``."""
    return [
        VesselPath(f"{sc.name}/{v.name}", v.trajectory.north, v.trajectory.east, v.trajectory.time)
        for sc in scenarios
        for v in sc.vessels
    ]


def fit_harbour_alignment(
    scenarios: Sequence[str | os.PathLike[str] | Scenario],
    harbour: str = "ravnkloa",
    **options: float,
) -> AlignmentFit:
    """Fit raster harbour ``harbour``'s alignment to the scenario frame of ``scenarios`` (files or scenarios):
    every vessel of every scenario on water (:func:`seatwin.layout.alignment.fit_alignment`, ``options`` passed on).
    The harbour's current alignment is not used: the fit starts from its raster's own frame."""
    from seatwin.scenario.load import load_scenario

    if not scenarios:
        raise InputError(None, "give at least one scenario to fit the alignment to")
    m = harbour_map(harbour)
    if not isinstance(m, LandRaster):
        raise InputError(None, f"harbour {harbour!r} is not a land raster; only a raster harbour has an alignment to fit")
    loaded = [s if isinstance(s, Scenario) else load_scenario(s) for s in scenarios]
    sources = [os.path.basename(sc.source) for sc in loaded]
    return fit_alignment(m.aligned(IDENTITY), vessel_paths(loaded), sources=sources, **options)  # type: ignore[arg-type]
