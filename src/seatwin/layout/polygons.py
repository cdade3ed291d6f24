"""A harbour from land polygons: a GeoJSON file of land → a :class:`~seatwin.layout.raster.LandRaster`.

:func:`read_land_geojson` reads the polygons (RFC 7946: ``[longitude, latitude]`` on WGS-84; a
``FeatureCollection``, a ``Feature`` or a bare ``Polygon``/``MultiPolygon``; holes — water inside land —
as a polygon's later rings) and puts them in a scenario's local NED frame about ``origin``;
:func:`rasterize_land` samples them on a grid (a cell is land when its centre is inside a polygon and
outside its holes); :func:`land_raster_from_geojson` does both, and
:func:`seatwin.layout.raster.write_land_raster` writes the result as a raster harbour
(``NAME.yaml`` + ``NAME.bin``) that a scenario names in ``environment.harbour``.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.geo import GeodeticOrigin, llh_to_ned_flat
from seatwin.layout.raster import LandRaster

MAX_CELLS = 25_000_000
"""The most cells a rasterised harbour may have (5 km × 5 km at 1 m), so a far-flung polygon is an error, not a hang."""


@dataclass(frozen=True)
class LandPolygon:
    """One land polygon in the local NED frame [m]: its outer ring and its holes, each an (n, 2) array of
    (north, east)."""

    outer: NDArray[np.float64]
    holes: tuple[NDArray[np.float64], ...] = ()


def _ring(path: Path, ring: object, where: str, origin: GeodeticOrigin) -> NDArray[np.float64]:
    pts = np.asarray(ring, dtype=object)
    ok = pts.ndim == 2 and pts.shape[0] >= 4 and pts.shape[1] in (2, 3)
    if ok:
        try:
            lonlat = np.asarray(pts[:, :2], dtype=float)
        except (TypeError, ValueError):
            ok = False
    if not ok:
        raise InputError(path, "expected a ring of at least 4 [longitude, latitude] positions", where=where)
    if not np.isfinite(lonlat).all() or (np.abs(lonlat[:, 1]) > 90).any() or (np.abs(lonlat[:, 0]) > 180).any():
        what = "expected finite [longitude, latitude] in degrees (longitude first, as GeoJSON has it)"
        raise InputError(path, what, where=where)
    n, e, _ = llh_to_ned_flat(lonlat[:, 1], lonlat[:, 0], np.zeros(len(lonlat)), origin)
    return np.column_stack([n, e])


def _geometries(path: Path, data: object) -> list[tuple[str, dict]]:
    """(where, geometry) of every Polygon/MultiPolygon in a GeoJSON object."""
    if not isinstance(data, dict) or "type" not in data:
        raise InputError(path, "expected a GeoJSON object with a 'type'")
    kind = data["type"]
    if kind == "FeatureCollection":
        feats = data.get("features")
        if not isinstance(feats, list):
            raise InputError(path, "expected a list 'features'", where="features")
        out = []
        for i, f in enumerate(feats):
            geom = f.get("geometry") if isinstance(f, dict) else None
            if not isinstance(geom, dict):
                raise InputError(path, "expected a Feature with a geometry", where=f"features[{i}]")
            out += [(f"features[{i}].geometry{w}", g) for w, g in _geometries(path, geom)]
        return out
    if kind == "Feature":
        geom = data.get("geometry")
        if not isinstance(geom, dict):
            raise InputError(path, "expected a Feature with a geometry", where="geometry")
        return [(f".geometry{w}", g) for w, g in _geometries(path, geom)]
    if kind in ("Polygon", "MultiPolygon"):
        return [("", data)]
    raise InputError(path, f"expected Polygon or MultiPolygon land (or features of them), got type {kind!r}", where="type")


def read_land_geojson(path: str | Path, origin: GeodeticOrigin) -> list[LandPolygon]:
    """The land polygons of a GeoJSON file in the local NED frame about ``origin``; an :class:`InputError` names the
    file and the feature/ring that is not a polygon of [longitude, latitude] positions."""
    p = Path(path)
    if not p.is_file():
        raise InputError(p, "GeoJSON file not found")
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(p, f"not JSON: {exc}") from None
    polygons = []
    for where, geom in _geometries(p, data):
        coords = geom.get("coordinates")
        polys = [coords] if geom["type"] == "Polygon" else coords
        if not isinstance(polys, list) or not all(isinstance(rings, list) and rings for rings in polys):
            raise InputError(p, f"expected the coordinates of a {geom['type']}", where=f"{where}.coordinates".lstrip("."))
        for k, rings in enumerate(polys):
            base = f"{where}.coordinates" + ("" if geom["type"] == "Polygon" else f"[{k}]")
            ned = [_ring(p, r, f"{base}[{j}]".lstrip("."), origin) for j, r in enumerate(rings)]
            polygons.append(LandPolygon(ned[0], tuple(ned[1:])))
    if not polygons:
        raise InputError(p, "holds no land polygon")
    return polygons


def _inside(ring: NDArray[np.float64], north: NDArray[np.float64], east: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Even–odd rule: points (north, east) inside the closed ``ring``."""
    inside = np.zeros(north.shape, dtype=bool)
    n0, e0 = ring[:, 0], ring[:, 1]
    n1, e1 = np.roll(n0, -1), np.roll(e0, -1)
    for a_n, a_e, b_n, b_e in zip(n0, e0, n1, e1, strict=True):
        if a_n == b_n:
            continue
        crosses = (a_n > north) != (b_n > north)
        e_at = a_e + (north - a_n) * (b_e - a_e) / (b_n - a_n)
        inside ^= crosses & (east < e_at)
    return inside


def rasterize_land(
    polygons: list[LandPolygon], resolution: float = 1.0, margin: float = 20.0, source: str = "<polygons>"
) -> LandRaster:
    """A :class:`LandRaster` covering the polygons and ``margin`` [m] of water around them, cells of ``resolution`` [m]:
    land where a cell's centre is inside a polygon's outer ring and outside its holes."""
    if not (math.isfinite(resolution) and resolution > 0):
        raise ParameterError("resolution", f"must be a positive number of metres, got {resolution!r}")
    if not (math.isfinite(margin) and margin >= 0):
        raise ParameterError("margin", f"must be zero or a positive number of metres, got {margin!r}")
    if not polygons:
        raise ParameterError("polygons", "give at least one land polygon")
    pts = np.vstack([p.outer for p in polygons])
    lo = np.floor((pts.min(axis=0) - margin) / resolution) * resolution
    hi = np.ceil((pts.max(axis=0) + margin) / resolution) * resolution
    rows, cols = (int(round(x)) for x in (hi - lo) / resolution)
    if rows * cols > MAX_CELLS:
        span = f"{hi[0] - lo[0]:.0f} m × {hi[1] - lo[1]:.0f} m"
        raise ParameterError(
            "resolution",
            f"the polygons span {span}: {rows * cols} cells at {resolution} m (at most {MAX_CELLS}); "
            "a coarser resolution, or polygons near the origin?",
        )
    north = lo[0] + (np.arange(rows) + 0.5) * resolution
    east = lo[1] + (np.arange(cols) + 0.5) * resolution
    nn, ee = np.meshgrid(north, east, indexing="ij")
    land = np.zeros((rows, cols), dtype=bool)
    for poly in polygons:
        inside = _inside(poly.outer, nn, ee)
        for hole in poly.holes:
            inside &= ~_inside(hole, nn, ee)
        land |= inside
    return LandRaster(~land, origin_north=float(lo[0]), origin_east=float(lo[1]), resolution=float(resolution), source=source)


def land_raster_from_geojson(
    path: str | Path, origin: GeodeticOrigin, resolution: float = 1.0, margin: float = 20.0
) -> LandRaster:
    """The GeoJSON land polygons of ``path`` (about ``origin``) as a raster (:func:`read_land_geojson`,
    :func:`rasterize_land`)."""
    return rasterize_land(read_land_geojson(path, origin), resolution, margin, source=str(path))
