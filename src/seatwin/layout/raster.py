"""Land/water rasters: a harbour's 2-D map as a grid (the Ravnkloa base-map format).

``NAME.yaml`` (``map_width``, ``map_height``, ``grid_resolution``, ``origin_x_coordinate`` =
east of column 0, ``origin_y_coordinate`` = north of row 0) beside ``NAME.bin`` (uint8,
row-major, 1 = water, 0 = land; row 0 the southern edge).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from seatwin.errors import InputError
from seatwin.layout.alignment import IDENTITY, Alignment
from seatwin.layout.model import MooredBoat
from seatwin.safe_yaml import load_yaml


@dataclass(frozen=True)
class LandRaster:
    """A land/water grid: ``water[r, c]`` True on water; cell (r, c) covers
    north ``origin_north + r·res`` … ``+res`` and east ``origin_east + c·res`` … ``+res`` in the
    raster's own frame. ``alignment`` takes a scenario-frame point into that frame
    (:class:`~seatwin.layout.alignment.Alignment`); :meth:`is_water` takes scenario-frame points."""

    water: np.ndarray
    origin_north: float
    origin_east: float
    resolution: float = 1.0
    source: str = "<memory>"
    alignment: Alignment = IDENTITY
    moored_boats: tuple[MooredBoat, ...] = ()
    """Boats moored in this harbour, in the raster's own frame (:meth:`moored` gives them in the scenario frame)."""

    def moored(self) -> tuple[MooredBoat, ...]:
        """The moored boats placed in the scenario frame by the alignment."""
        out = []
        for b in self.moored_boats:
            n, e = self.alignment.from_map(b.north, b.east)
            out.append(replace(b, north=float(n), east=float(e), heading_deg=b.heading_deg - self.alignment.rotation_deg))
        return tuple(out)

    def aligned(self, alignment: Alignment) -> LandRaster:
        """The same grid placed in a scenario frame by ``alignment``."""
        return replace(self, alignment=alignment)

    def cells(self, north: np.ndarray, east: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(row, column, inside the grid) of scenario-frame (north, east), taken into the raster's own frame by
        the alignment first."""
        if not self.alignment.is_identity:
            north, east = self.alignment.to_map(north, east)
        r = np.floor((np.asarray(north, float) - self.origin_north) / self.resolution).astype(np.int64)
        c = np.floor((np.asarray(east, float) - self.origin_east) / self.resolution).astype(np.int64)
        r, c = np.broadcast_arrays(r, c)
        inside = (r >= 0) & (r < self.water.shape[0]) & (c >= 0) & (c < self.water.shape[1])
        return r, c, inside

    def is_water(self, north: np.ndarray, east: np.ndarray, outside: bool = True) -> np.ndarray:
        """True where scenario-frame (north, east) falls on a water cell; points outside the grid count
        as ``outside`` (water for building a harbour, land for masking sensor returns)."""
        r, c, inside = self.cells(north, east)
        out = np.full(r.shape, outside, dtype=bool)
        out[inside] = self.water[r[inside], c[inside]]
        return out


def read_land_raster(path: str | Path) -> LandRaster:
    """Read a ``.bin`` + ``.yaml`` land/water raster (uint8 rows from the south, 1 = water, 0 = land).

    ``path`` is either file; the other is found beside it.
    """
    p = Path(path)
    meta_path, bin_path = p.with_suffix(".yaml"), p.with_suffix(".bin")
    for q in (meta_path, bin_path):
        if not q.is_file():
            raise InputError(q, "map raster file not found (a map raster is NAME.yaml and NAME.bin side by side)")
    meta = load_yaml(meta_path, "a map raster's YAML")
    need = ("map_width", "map_height", "origin_x_coordinate", "origin_y_coordinate")
    for key in need:
        if not isinstance(meta, dict) or key not in meta:
            raise InputError(meta_path, f"missing key {key!r} (expected {', '.join(need)}, grid_resolution)", where=key)
    meta.setdefault("grid_resolution", 1.0)
    for key in ("map_width", "map_height"):
        if type(meta[key]) is not int or meta[key] <= 0:
            raise InputError(meta_path, f"expected a positive integer, got {meta[key]!r}", where=key)
    for key in ("grid_resolution", "origin_x_coordinate", "origin_y_coordinate"):
        if type(meta[key]) not in (int, float) or (key == "grid_resolution" and not meta[key] > 0):
            what = "a positive number" if key == "grid_resolution" else "a number"
            raise InputError(meta_path, f"expected {what}, got {meta[key]!r}", where=key)
    w, h = meta["map_width"], meta["map_height"]
    res = float(meta["grid_resolution"])
    data = np.fromfile(bin_path, dtype=np.uint8)
    if data.size != w * h:
        raise InputError(bin_path, f"holds {data.size} bytes, expected map_width × map_height = {w} × {h} = {w * h} bytes")
    bad = np.flatnonzero(data > 1)
    if bad.size:
        raise InputError(bin_path, f"cell values must be 0 (land) or 1 (water), got {data[bad[0]]}", where=f"byte {bad[0]}")
    return LandRaster(
        data.reshape(h, w).astype(bool),
        origin_north=float(meta["origin_y_coordinate"]),
        origin_east=float(meta["origin_x_coordinate"]),
        resolution=res,
        source=str(bin_path),
    )


def write_land_raster(raster: LandRaster, path: str | Path) -> tuple[Path, Path]:
    """Write ``raster`` as ``NAME.yaml`` + ``NAME.bin`` (the format :func:`read_land_raster` reads; its alignment is
    not written: a raster's alignment lives in ``NAME.alignment.yaml``); both through temporary files renamed at the
    end, missing folders made. ``path`` is either file's name."""
    import os

    p = Path(path)
    meta_path, bin_path = p.with_suffix(".yaml"), p.with_suffix(".bin")
    rows, cols = raster.water.shape
    p.parent.mkdir(parents=True, exist_ok=True)
    meta = (
        f"# A land/water raster: {bin_path.name} holds map_height rows of map_width uint8 cells (1 = water, 0 = land),\n"
        "# row 0 the southern edge; cell (r, c) covers north origin_y_coordinate + r·grid_resolution and east\n"
        "# origin_x_coordinate + c·grid_resolution [m] in the scenario's local frame.\n"
        f"map_width: {cols}\nmap_height: {rows}\ngrid_resolution: {float(raster.resolution)!r}\n"
        f"origin_x_coordinate: {float(raster.origin_east)!r}\norigin_y_coordinate: {float(raster.origin_north)!r}\n"
    )
    written = []
    try:
        for final, write in (
            (bin_path, lambda f: f.write_bytes(np.ascontiguousarray(raster.water, dtype=np.uint8).tobytes())),
            (meta_path, lambda f: f.write_text(meta, encoding="utf-8")),
        ):
            tmp = final.with_name(f".{final.name}.part")
            written.append(tmp)
            write(tmp)
        for tmp, final in zip(written, (bin_path, meta_path), strict=True):
            os.replace(tmp, final)
    finally:
        for tmp in written:
            tmp.unlink(missing_ok=True)
    return meta_path, bin_path
