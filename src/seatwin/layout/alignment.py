"""A harbour map's alignment to the scenario frame: a rigid transform, fitted from "vessels sail on water".

:class:`Alignment` maps a scenario's local NED point into the map's (raster's) own frame:
rotate by ``rotation_deg`` (compass sense: clockwise seen from above) about ``centre``, then move
by ``shift``. :meth:`Alignment.from_map` is its inverse (world building puts the map's land into
the scenario frame with it). It is stored as a small YAML beside the harbour's definition
(:func:`read_alignment`, :func:`write_alignment`) with the provenance of its fit.

:func:`fit_alignment` fits it: every vessel of every given scenario should be on water. The
objective is smooth — the mean over vessels of the mean over samples of a logistic function of the
signed distance to the shore (a distance transform of the raster; positive on water), scale
``margin_m`` — so a sample a few metres into a quay costs a little, not everything. A grid over
rotation (translation 0) is followed by a Nelder–Mead refinement of rotation and translation
(translation held near 0 by a Gaussian prior, ``shift_sigma_m``). The on-water constraint bounds
the rotation only to an interval (the rotations whose worst vessel stays within ``tolerance`` of
the best); the fit reports that interval and takes its middle, the rotation with the most slack on
both sides (see ``docs/architecture/harbour.md``).
"""

from __future__ import annotations

import datetime as dt
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.safe_yaml import load_yaml

ALIGNMENT_KEYS = ("rotation_deg", "centre_north", "centre_east", "shift_north", "shift_east")


@dataclass(frozen=True)
class Alignment:
    """Scenario frame → map frame: ``map = R(rotation)·(p − centre) + centre + shift`` (north, east [m])."""

    rotation_deg: float = 0.0
    centre_north: float = 0.0
    centre_east: float = 0.0
    shift_north: float = 0.0
    shift_east: float = 0.0

    @property
    def is_identity(self) -> bool:
        return self.rotation_deg == 0.0 and self.shift_north == 0.0 and self.shift_east == 0.0

    def _rot(self, sign: float) -> tuple[float, float]:
        th = np.radians(sign * self.rotation_deg)
        return float(np.cos(th)), float(np.sin(th))

    def to_map(self, north: ArrayLike, east: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Scenario-frame points → the map's frame."""
        c, s = self._rot(1.0)
        n = np.asarray(north, float) - self.centre_north
        e = np.asarray(east, float) - self.centre_east
        return c * n - s * e + self.centre_north + self.shift_north, s * n + c * e + self.centre_east + self.shift_east

    def from_map(self, north: ArrayLike, east: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Map-frame points → the scenario frame (the inverse of :meth:`to_map`)."""
        c, s = self._rot(-1.0)
        n = np.asarray(north, float) - self.centre_north - self.shift_north
        e = np.asarray(east, float) - self.centre_east - self.shift_east
        return c * n - s * e + self.centre_north, s * n + c * e + self.centre_east

    def from_map_matrix(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(3×3 rotation, 3-vector) taking map-frame NED points (z kept) into the scenario frame."""
        c, s = self._rot(-1.0)
        rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        cn, ce = self.centre_north, self.centre_east
        offset = np.array([cn, ce, 0.0]) - rot @ np.array([cn + self.shift_north, ce + self.shift_east, 0.0])
        return rot, offset


IDENTITY = Alignment()


def read_alignment(path: str | Path) -> tuple[Alignment, dict[str, Any]]:
    """(alignment, provenance) from a YAML file with the keys of :class:`Alignment` (missing: 0) and an
    optional ``provenance`` mapping; an :class:`InputError` naming the file and key otherwise."""
    p = Path(path)
    data = load_yaml(p, "an alignment YAML file")
    if not isinstance(data, dict):
        raise InputError(p, f"expected a mapping with {', '.join(ALIGNMENT_KEYS)}")
    unknown = sorted(set(data) - set(ALIGNMENT_KEYS) - {"provenance"})
    if unknown:
        raise InputError(p, f"unknown key {unknown[0]!r}; expected {', '.join(ALIGNMENT_KEYS)}, provenance", where=unknown[0])
    values = {}
    for key in ALIGNMENT_KEYS:
        v = data.get(key, 0.0)
        if isinstance(v, bool) or not isinstance(v, int | float) or not np.isfinite(v):
            raise InputError(p, f"expected a finite number, got {v!r}", where=key)
        values[key] = float(v)
    prov = data.get("provenance") or {}
    if not isinstance(prov, dict):
        raise InputError(p, "expected a mapping", where="provenance")
    return Alignment(**values), prov


def write_alignment(path: str | Path, alignment: Alignment, provenance: dict[str, Any] | None = None) -> Path:
    """Write ``alignment`` (and ``provenance``) as YAML at ``path`` (missing folders made; through a temporary file
    renamed at the end); returns the path."""
    from seatwin.outputs import write_text_atomic

    p = Path(path)
    data: dict[str, Any] = {k: round(float(v), 6) for k, v in asdict(alignment).items()}
    if provenance:
        data["provenance"] = provenance
    write_text_atomic(
        p,
        "# Scenario frame -> map frame: map = R(rotation_deg, clockwise)·(p − centre) + centre + shift (metres, NED).\n"
        + yaml.safe_dump(data, sort_keys=False, allow_unicode=True),
    )
    return p


@dataclass(frozen=True)
class VesselPath:
    """One vessel's positions (scenario frame) for a fit: ``label`` names it (scenario / vessel)."""

    label: str
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    time: NDArray[np.float64] | None = None


@dataclass(frozen=True)
class AlignmentFit:
    """A fitted :class:`Alignment` with its figures."""

    alignment: Alignment
    rotation_interval_deg: tuple[float, float]
    """Rotations (translation as fitted) whose worst vessel's on-water fraction is within the tolerance of the best."""
    tolerance: float
    on_water_before: dict[str, float]
    on_water_after: dict[str, float]
    objective: float
    sources: list[str] = field(default_factory=list)

    @property
    def worst_after(self) -> float:
        return min(self.on_water_after.values()) if self.on_water_after else 1.0

    def provenance(self) -> dict[str, Any]:
        """The fit's provenance, as stored beside the alignment."""
        lo, hi = self.rotation_interval_deg
        return {
            "fitted_by": "seatwin.layout.alignment.fit_alignment (vessels on water)",
            "date": dt.date.today().isoformat(),
            "sources": list(self.sources),
            "rotation_interval_deg": [round(lo, 3), round(hi, 3)],
            "tolerance": self.tolerance,
            "vessels": len(self.on_water_after),
            "worst_on_water_before": round(min(self.on_water_before.values()), 5) if self.on_water_before else None,
            "worst_on_water_after": round(self.worst_after, 5),
        }


def signed_distance(water: NDArray[np.bool_], resolution: float = 1.0) -> NDArray[np.float64]:
    """Distance [m] of each cell to the nearest cell of the other kind: positive on water, negative on land."""
    from scipy.ndimage import distance_transform_edt

    return (distance_transform_edt(water) - distance_transform_edt(~water)) * resolution


class _Objective:
    """The fit's smooth objective and hard on-water fractions on one raster."""

    def __init__(self, raster: Any, paths: Sequence[VesselPath], margin_m: float):
        self.raster = raster
        self.paths = paths
        self.margin = margin_m
        self.sd = signed_distance(raster.water, raster.resolution)
        self.outside = -float(max(raster.water.shape) * raster.resolution)

    def _dist(self, al: Alignment, p: VesselPath) -> NDArray[np.float64]:
        from scipy.ndimage import map_coordinates

        n, e = al.to_map(p.north, p.east)
        r = (n - self.raster.origin_north) / self.raster.resolution - 0.5
        c = (e - self.raster.origin_east) / self.raster.resolution - 0.5
        return map_coordinates(self.sd, [r, c], order=1, mode="constant", cval=self.outside)

    def soft(self, al: Alignment) -> float:
        vals = [float(np.mean(0.5 * (1.0 + np.tanh(self._dist(al, p) / (2.0 * self.margin))))) for p in self.paths]
        return float(np.mean(vals))

    def fractions(self, al: Alignment) -> dict[str, float]:
        return {p.label: float(np.mean(self.raster.is_water(*al.to_map(p.north, p.east), outside=False))) for p in self.paths}


def fit_alignment(
    raster: Any,
    paths: Sequence[VesselPath],
    *,
    centre: tuple[float, float] = (0.0, 0.0),
    rotation_range_deg: tuple[float, float] = (-45.0, 45.0),
    grid_step_deg: float = 0.5,
    margin_m: float = 3.0,
    shift_sigma_m: float = 5.0,
    tolerance: float = 0.005,
    sources: Sequence[str] = (),
) -> AlignmentFit:
    """Fit the :class:`Alignment` that puts the vessels ``paths`` on ``raster``'s water (see the module).

    ``centre``: the rotation's centre in the scenario frame; ``tolerance``: how far (as a fraction of
    samples) the worst vessel may fall below its best to count a rotation as consistent.
    """
    from scipy.optimize import minimize

    if not paths or not any(len(p.north) for p in paths):
        raise InputError(None, "no vessel positions to fit an alignment to")
    cn, ce = centre
    obj = _Objective(raster, [p for p in paths if len(p.north)], margin_m)

    def align(x: Sequence[float]) -> Alignment:
        return Alignment(float(x[0]), cn, ce, float(x[1]), float(x[2]))

    def cost(x: NDArray[np.float64]) -> float:
        return -obj.soft(align(x)) + 1e-3 * (x[1] ** 2 + x[2] ** 2) / shift_sigma_m**2

    grid = np.arange(rotation_range_deg[0], rotation_range_deg[1] + 1e-9, grid_step_deg)
    start = float(grid[int(np.argmin([cost(np.array([th, 0.0, 0.0])) for th in grid]))])
    simplex = np.array([[start, 0, 0], [start + grid_step_deg, 0, 0], [start, 2.0, 0], [start, 0, 2.0]], float)
    res = minimize(cost, simplex[0], method="Nelder-Mead", options={"initial_simplex": simplex, "xatol": 1e-3, "fatol": 1e-9})
    best = res.x
    # The interval of consistent rotations (translation as fitted) and its middle.
    step = grid_step_deg / 2
    worst = {}
    fine = np.arange(rotation_range_deg[0], rotation_range_deg[1] + 1e-9, step)
    for th in fine:
        worst[float(th)] = min(obj.fractions(align([th, best[1], best[2]])).values())
    top = max(worst.values())
    i0 = int(np.argmin(np.abs(fine - best[0])))
    if worst[float(fine[i0])] < top - tolerance:  # the smooth optimum is off the hard plateau: use the plateau's best point
        i0 = int(np.argmax([worst[float(t)] for t in fine]))
    lo = hi = i0
    while lo > 0 and worst[float(fine[lo - 1])] >= top - tolerance:
        lo -= 1
    while hi < len(fine) - 1 and worst[float(fine[hi + 1])] >= top - tolerance:
        hi += 1
    mid = 0.5 * (float(fine[lo]) + float(fine[hi]))
    # Translation refined once more at the chosen rotation.
    opts = {"xatol": 1e-3, "fatol": 1e-9}
    res2 = minimize(lambda t: cost(np.array([mid, t[0], t[1]])), best[1:], method="Nelder-Mead", options=opts)
    final = align([mid, res2.x[0], res2.x[1]])
    return AlignmentFit(
        alignment=final,
        rotation_interval_deg=(float(fine[lo]), float(fine[hi])),
        tolerance=tolerance,
        on_water_before=obj.fractions(IDENTITY),
        on_water_after=obj.fractions(final),
        objective=obj.soft(final),
        sources=list(sources),
    )
