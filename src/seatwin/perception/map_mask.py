"""Land/water masks: which world points lie on open water (the rest is land, quay or pier).

* :class:`LayoutMask` — the built-in harbour (:data:`seatwin.layout.DEFAULT_LAYOUT`),
  vectorised.
* :class:`RasterMask` — a land/water raster in the Ravnkloa base-map format: ``NAME.yaml``
  (``map_width``, ``map_height``, ``grid_resolution``, ``origin_x_coordinate`` = east of
  column 0, ``origin_y_coordinate`` = north of row 0) beside ``NAME.bin`` (uint8, row-major,
  1 = water, 0 = land; row 0 the southern edge). Points outside the raster count as land.
* :func:`load_mask` — ``harbour``, ``none`` or a raster's ``.yaml``/``.bin`` path.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.layout import DEFAULT_LAYOUT, HarbourLayout


class NoMask:
    """Everything is water (no land masking)."""

    def is_water(self, north: ArrayLike, east: ArrayLike) -> NDArray[np.bool_]:
        return np.ones(np.broadcast(np.asarray(north), np.asarray(east)).shape, dtype=bool)


@dataclass(frozen=True)
class LayoutMask:
    """:meth:`HarbourLayout.is_water` as a mask (inside the channel, not under a pier)."""

    layout: HarbourLayout = DEFAULT_LAYOUT

    def is_water(self, north: ArrayLike, east: ArrayLike) -> NDArray[np.bool_]:
        return np.asarray(self.layout.is_water(north, east), dtype=bool)


@dataclass(frozen=True)
class RasterMask:
    """A 1-bit land/water raster (see the module docstring)."""

    water: NDArray[np.bool_]
    """(rows, cols); row 0 is the southern edge."""
    origin_north: float
    origin_east: float
    resolution: float

    @classmethod
    def load(cls, path: str | Path) -> RasterMask:
        """Load ``NAME.yaml`` + ``NAME.bin`` (either path may be given)."""
        p = Path(path)
        meta_path, bin_path = p.with_suffix(".yaml"), p.with_suffix(".bin")
        for q in (meta_path, bin_path):
            if not q.is_file():
                raise InputError(q, "map raster needs NAME.yaml and NAME.bin side by side; this file is missing")
        try:
            meta = yaml.safe_load(meta_path.read_text())
            w, h = int(meta["map_width"]), int(meta["map_height"])
            res = float(meta.get("grid_resolution", 1.0))
            on, oe = float(meta["origin_y_coordinate"]), float(meta["origin_x_coordinate"])
        except (yaml.YAMLError, KeyError, TypeError, ValueError) as exc:
            raise InputError(
                meta_path,
                f"expected map_width, map_height, grid_resolution, origin_x_coordinate, "
                f"origin_y_coordinate ({type(exc).__name__}: {exc})",
            ) from None
        data = np.fromfile(bin_path, dtype=np.uint8)
        if data.size != w * h:
            raise InputError(bin_path, f"expected {w}×{h} = {w * h} bytes (from {meta_path.name}), found {data.size}")
        return cls(data.reshape(h, w) == 1, on, oe, res)

    def is_water(self, north: ArrayLike, east: ArrayLike) -> NDArray[np.bool_]:
        n, e = np.broadcast_arrays(np.asarray(north, float), np.asarray(east, float))
        r = np.floor((n - self.origin_north) / self.resolution).astype(np.int64)
        c = np.floor((e - self.origin_east) / self.resolution).astype(np.int64)
        rows, cols = self.water.shape
        inside = (r >= 0) & (r < rows) & (c >= 0) & (c < cols)
        out = np.zeros(n.shape, dtype=bool)
        out[inside] = self.water[r[inside], c[inside]]
        return out


WaterMask = NoMask | LayoutMask | RasterMask


def load_mask(spec: str | Path | None) -> WaterMask:
    """``harbour`` (built-in layout), ``none``, or a raster path (``.yaml`` or ``.bin``)."""
    if spec is None or str(spec) == "none":
        return NoMask()
    if str(spec) == "harbour":
        return LayoutMask()
    return RasterMask.load(spec)
