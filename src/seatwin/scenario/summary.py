"""What a scenario holds: vessels, span, rate, speeds and closest approaches, as plain data."""

from __future__ import annotations

import datetime as dt
from itertools import combinations
from pathlib import Path
from typing import Any

import numpy as np

from seatwin.errors import InputError
from seatwin.layout import DEFAULT_LAYOUT, HarbourLayout, LandRaster, harbour_map
from seatwin.mesh_placement import is_mesh_path
from seatwin.scenario.model import Scenario, Trajectory


def water_fraction(north: np.ndarray, east: np.ndarray, harbour: HarbourLayout | LandRaster = DEFAULT_LAYOUT) -> float:
    """Fraction of the points on ``harbour``'s open water (a layout, or a land raster: outside it counts as land)."""
    if isinstance(harbour, LandRaster):
        on = harbour.is_water(north, east, outside=False)
    else:
        on = np.asarray(harbour.is_water(north, east), dtype=bool)
    return float(on.mean()) if on.size else 0.0


def scenario_harbour_map(scenario: Scenario) -> HarbourLayout | LandRaster | None:
    """The 2-D map of the scenario's own harbour; None for ``none`` or when its raster cannot be found
    (a summary or a plot still works; simulating it says what is missing)."""
    try:
        return harbour_map(scenario.environment.get("harbour", "default"))
    except InputError:
        return None


def closest_approach(a: Trajectory, b: Trajectory, start: float | None = None, end: float | None = None) -> tuple[float, float]:
    """(distance [m], POSIX time) of the closest approach of two trajectories within their common span.

    Exact for the model's linear interpolation: between consecutive sample times of either
    trajectory the relative position moves on a straight line, whose nearest point is solved
    in closed form.
    """
    lo = max(a.start, b.start) if start is None else start
    hi = min(a.end, b.end) if end is None else end
    if hi < lo:
        raise ValueError(f"the trajectories do not overlap in time ({a.source}, {b.source})")
    t = np.union1d(a.time, b.time)
    t = np.unique(np.concatenate([[lo, hi], t[(t > lo) & (t < hi)]]))
    sa, sb = a.state_at(t), b.state_at(t)
    rel = np.stack([sb.north - sa.north, sb.east - sa.east], axis=1)
    if len(t) == 1:
        return float(np.hypot(*rel[0])), float(t[0])
    p0, d = rel[:-1], np.diff(rel, axis=0)
    dd = (d * d).sum(axis=1)
    u = np.clip(np.divide(-(p0 * d).sum(axis=1), dd, out=np.zeros_like(dd), where=dd > 0), 0.0, 1.0)
    dist = np.hypot(*(p0 + u[:, None] * d).T)
    k = int(np.argmin(dist))
    return float(dist[k]), float(t[k] + u[k] * (t[k + 1] - t[k]))


def _iso(t: float) -> str:
    return dt.datetime.fromtimestamp(t, tz=dt.UTC).isoformat(timespec="milliseconds")


def scenario_summary(scenario: Scenario) -> dict[str, Any]:
    """A JSON-ready summary: span, rate, per-vessel speeds (min/mean/max over the samples in the
    common span), path lengths, and each pair's closest approach (distance, time). ``on_water`` is the
    fraction of each vessel's samples on its harbour's open water (the default layout or a land raster:
    a trajectory recorded elsewhere shows up here), ``None`` without a harbour map."""
    start, end = scenario.start, scenario.end
    harbour = scenario_harbour_map(scenario)
    vessels = []
    for v in scenario.vessels:
        tr = v.trajectory
        times = tr.time[(tr.time >= start - 1e-9) & (tr.time <= end + 1e-9)]
        if len(times) == 0:
            times = np.array([start, end])
        s = tr.state_at(times)
        vessels.append(
            {
                "name": v.name,
                "role": v.role.value,
                "model": Path(v.model).name if is_mesh_path(v.model) else v.model,
                "dimensions": None if v.dimensions is None else vars(v.dimensions).copy(),
                "samples": int(len(tr.time)),
                "rate_hz": round(tr.rate_hz, 3),
                "speed_mps": {"min": float(s.speed.min()), "mean": float(s.speed.mean()), "max": float(s.speed.max())},
                "distance_m": float(np.hypot(np.diff(s.north), np.diff(s.east)).sum()),
                "start_ned": [float(s.north[0]), float(s.east[0])],
                "end_ned": [float(s.north[-1]), float(s.east[-1])],
                "on_water": None if harbour is None else water_fraction(s.north, s.east, harbour),
            }
        )
    pairs = []
    for va, vb in combinations(scenario.vessels, 2):
        d, t = closest_approach(va.trajectory, vb.trajectory, start, end)
        pairs.append({"a": va.name, "b": vb.name, "distance_m": d, "time": t, "time_from_start_s": t - start})
    origin = scenario.origin
    return {
        "name": scenario.name,
        "description": scenario.description,
        "source": scenario.source,
        "start": start,
        "start_utc": _iso(start),
        "end": end,
        "duration_s": end - start,
        "rate_hz": round(float(np.median([v.trajectory.rate_hz for v in scenario.vessels])), 3),
        "origin": None if origin is None else {"lat": origin.lat_deg, "lon": origin.lon_deg, "height": origin.height_m},
        "seed": scenario.seed,
        "environment": dict(scenario.environment),
        "rig": scenario.rig,
        "vessels": vessels,
        "closest_approach": pairs,
    }
