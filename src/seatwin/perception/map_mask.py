"""Land/water masks: which world points lie on open water (the rest is land, quay or pier).

* :class:`LayoutMask` — the built-in harbour (:data:`seatwin.layout.DEFAULT_LAYOUT`),
  vectorised.
* :class:`RasterMask` — a land/water raster in the Ravnkloa base-map format, read by
  :func:`seatwin.layout.read_land_raster`. Points outside the raster count as land.
* :func:`load_mask` — ``harbour``, ``none``, ``ravnkloa`` or a raster's ``.yaml``/``.bin`` path; a raster
  comes with its harbour's alignment to the scenario frame (:func:`seatwin.layout.harbour_map`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.layout import DEFAULT_LAYOUT, HarbourLayout
from seatwin.layout.raster import LandRaster, read_land_raster


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
    """A land/water raster (:class:`seatwin.layout.LandRaster`) as a mask: outside the raster is land."""

    raster: LandRaster

    @classmethod
    def load(cls, path: str | Path) -> RasterMask:
        """Load ``NAME.yaml`` + ``NAME.bin`` (either path may be given) with :func:`seatwin.layout.read_land_raster`."""
        return cls(read_land_raster(path))

    @property
    def water(self) -> NDArray[np.bool_]:
        """(rows, cols); row 0 is the southern edge."""
        return self.raster.water

    def is_water(self, north: ArrayLike, east: ArrayLike) -> NDArray[np.bool_]:
        return self.raster.is_water(north, east, outside=False)


WaterMask = NoMask | LayoutMask | RasterMask


def load_mask(spec: str | Path | None) -> WaterMask:
    """``harbour``/``default`` (built-in layout), ``none``, ``ravnkloa`` (the real raster, found by
    :func:`seatwin.layout.harbours.harbour_file`), or a raster path (``.yaml`` or ``.bin``)."""
    from seatwin.layout.harbours import harbour_map, harbour_name

    if spec is None or harbour_name(str(spec)) == "none":
        return NoMask()
    if harbour_name(str(spec)) == "default":
        return LayoutMask()
    # The raster with the harbour's alignment to the scenario frame (ravnkloa: the Gemini scenarios'),
    # the same map the world was built from.
    raster = harbour_map(str(spec))
    if not isinstance(raster, LandRaster):
        raise InputError(str(spec), "expected a land raster .yaml/.bin, 'harbour', 'none' or 'ravnkloa'")
    return RasterMask(raster)
