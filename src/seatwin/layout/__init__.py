"""The harbour's 2-D layout, as data: where water, quays, piers and buildings are.

Below both :mod:`seatwin.scenario` (built-in scenarios keep to the water, plots draw the
outline) and :mod:`seatwin.world` (which builds the 3-D harbour from it), so neither of
those imports the other for it.

* :mod:`.model` — :class:`HarbourLayout` and :data:`DEFAULT_LAYOUT`, the built-in harbour.
* :mod:`.raster` — :class:`LandRaster`, a land/water grid read by :func:`read_land_raster`.
* :mod:`.harbours` — harbours by name (``default``, ``ravnkloa``, ``none``) or raster file → :func:`harbour_map`;
  the real Ravnkloa raster is found with :func:`find_data_file` (``$SEATWIN_DATA``, ``shared/data``);
  :func:`harbour_moored_boats` / :func:`moored_boat_positions` — a harbour's (or a run's map hint's) moored boats.
* :mod:`.alignment` — a raster's rigid transform to the scenario frame, and its fit (vessels on water).
"""

from seatwin.layout.harbours import (
    HARBOUR_NAMES,
    find_data_file,
    harbour_file,
    harbour_map,
    harbour_moored_boats,
    harbour_name,
    moored_boat_positions,
)
from seatwin.layout.model import DEFAULT_LAYOUT, Box, HarbourLayout, MooredBoat
from seatwin.layout.raster import LandRaster, read_land_raster

__all__ = [
    "DEFAULT_LAYOUT",
    "HARBOUR_NAMES",
    "Box",
    "HarbourLayout",
    "LandRaster",
    "MooredBoat",
    "find_data_file",
    "harbour_file",
    "harbour_map",
    "harbour_moored_boats",
    "harbour_name",
    "moored_boat_positions",
    "read_land_raster",
]
