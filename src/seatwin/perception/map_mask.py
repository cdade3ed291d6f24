"""Land/water masks: which world points lie on open water (the rest is land, quay or pier).

* :class:`LayoutMask` — the built-in harbour (:data:`seatwin.layout.DEFAULT_LAYOUT`),
  vectorised.
* :class:`RasterMask` — a land/water raster in the Ravnkloa base-map format, read by
  :func:`seatwin.layout.read_land_raster`. Points outside the raster count as land.
* :func:`load_mask` — ``harbour``, ``none``, ``ravnkloa`` or a raster's ``.yaml``/``.bin`` path; a raster
  comes with its harbour's alignment to the scenario frame (:func:`seatwin.layout.harbour_map`).

Every mask also answers ``clear_of_land(north, east, margin)``: on water and farther than ``margin``
metres (per point) from land — the land dilated, which drops returns from a vertical quay face at the
water's edge and radar echoes of a quay smeared into the water by the beam.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
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

    def clear_of_land(self, north: ArrayLike, east: ArrayLike, margin: ArrayLike) -> NDArray[np.bool_]:
        """No land: everything."""
        return self.is_water(north, east)


RING = 16
"""Points on the circle of radius ``margin`` that :meth:`LayoutMask.clear_of_land` checks around a point."""


@dataclass(frozen=True)
class LayoutMask:
    """:meth:`HarbourLayout.is_water` as a mask (inside the channel, not under a pier)."""

    layout: HarbourLayout = DEFAULT_LAYOUT

    def is_water(self, north: ArrayLike, east: ArrayLike) -> NDArray[np.bool_]:
        return np.asarray(self.layout.is_water(north, east), dtype=bool)

    def clear_of_land(self, north: ArrayLike, east: ArrayLike, margin: ArrayLike) -> NDArray[np.bool_]:
        """On water, and so are :data:`RING` points at ``margin`` [m] around (land narrower than the gap
        between those points can slip through)."""
        n, e, m = np.broadcast_arrays(np.asarray(north, float), np.asarray(east, float), np.asarray(margin, float))
        out = self.is_water(n, e).copy()
        for k in range(RING):
            a = 2.0 * math.pi * k / RING
            out &= self.is_water(n + m * math.cos(a), e + m * math.sin(a))
        return out


@dataclass(frozen=True)
class RasterMask:
    """A land/water raster (:class:`seatwin.layout.LandRaster`) as a mask: outside the raster is land."""

    raster: LandRaster
    _distance: list[NDArray[np.float64]] = field(default_factory=list, compare=False, repr=False, hash=False)

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

    def land_distance(self) -> NDArray[np.float64]:
        """(rows, cols) distance [m] from each cell's centre to the nearest land cell's centre (0 on land;
        outside the raster counts as land). Computed once."""
        if not self._distance:
            from scipy.ndimage import distance_transform_edt

            water = np.pad(self.raster.water, 1, constant_values=False)
            self._distance.append(np.asarray(distance_transform_edt(water), float)[1:-1, 1:-1] * self.raster.resolution)
        return self._distance[0]

    def clear_of_land(self, north: ArrayLike, east: ArrayLike, margin: ArrayLike) -> NDArray[np.bool_]:
        """On a water cell farther than ``margin`` [m] from every land cell (centre to centre)."""
        n, e, m = np.broadcast_arrays(np.asarray(north, float), np.asarray(east, float), np.asarray(margin, float))
        i, j, inside = self.raster.cells(n, e)  # the cells is_water looks up (alignment applied)
        out = np.zeros(n.shape, dtype=bool)
        out[inside] = self.land_distance()[i[inside], j[inside]] > m[inside]
        return out


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
