"""The default built-in harbour, as data: a channel about 150 m wide with quays, like Ravnkloa.

Local NED frame (x north, y east), metres, heights above the calm water surface (z = 0).
The channel runs north–south: water for |east| < ``half_width``; land (quays at
``quay_height``) beyond. Built-in scenarios keep their vessels on the water of this layout;
:mod:`seatwin.world.harbour` builds its 3-D form.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray


@dataclass(frozen=True)
class Box:
    """An axis-aligned block: north/east extents, from the water (or ``base``) up to ``top``."""

    name: str
    north_min: float
    north_max: float
    east_min: float
    east_max: float
    top: float
    base: float = -2.0


@dataclass(frozen=True)
class MooredBoat:
    """A boat moored in a harbour: its middle (north, east [m]), heading [deg, compass], length, beam and height
    above the water [m]. Real, but without GNSS: tracking comparisons treat it as a don't-care region."""

    name: str
    north: float
    east: float
    heading_deg: float
    length: float
    beam: float
    height: float


@dataclass(frozen=True)
class HarbourLayout:
    half_width: float = 75.0
    """Half the channel width [m]: water for |east| < half_width."""
    north_min: float = -400.0
    north_max: float = 400.0
    land_depth: float = 60.0
    """How far the quay land extends beyond the water edge [m]."""
    quay_height: float = 1.8
    """Quay top above the water [m] (Ravnkloa's quays are about 1.5–2 m)."""
    piers: tuple[Box, ...] = field(
        default_factory=lambda: (
            # A pier from the west quay: the obstacle a target emerges from behind (scenario 9).
            Box("west_pier", 40.0, 52.0, -75.0, -30.0, 1.2),
            # A short floating pier on the east side with moored boats.
            Box("east_pier", -120.0, -116.0, 45.0, 75.0, 0.6),
        )
    )
    buildings: tuple[Box, ...] = field(
        default_factory=lambda: (
            Box("warehouse_west", -200.0, -120.0, -130.0, -85.0, 12.0, base=0.0),
            Box("market_hall", 90.0, 150.0, -125.0, -88.0, 9.0, base=0.0),
            Box("office_east", -60.0, 10.0, 88.0, 125.0, 18.0, base=0.0),
            Box("boathouse_east", 160.0, 200.0, 85.0, 110.0, 7.0, base=0.0),
            # A shed on the west pier: it hides a small boat behind the pier from the ownship's
            # lidar about 3 m above the water (the "tunnel" of thesis scenario 9).
            Box("west_pier_shed", 41.0, 51.0, -72.0, -34.0, 4.5, base=1.2),
        )
    )
    moored_boats: tuple[MooredBoat, ...] = field(
        default_factory=lambda: (
            MooredBoat("moored_sailboat", -100.0, 67.0, 0.0, 9.0, 3.0, 1.6),
            MooredBoat("moored_launch", -130.0, 68.0, 180.0, 6.0, 2.2, 1.2),
            MooredBoat("moored_trawler", 120.0, 67.0, 0.0, 18.0, 5.5, 4.0),
            MooredBoat("moored_dinghy", 30.0, -70.0, 90.0, 3.5, 1.5, 0.6),
            MooredBoat("moored_cruiser", -30.0, -69.0, 180.0, 11.0, 3.6, 2.8),
        )
    )

    def is_water(self, north: ArrayLike, east: ArrayLike) -> NDArray[np.bool_] | bool:
        """True on open water (inside the channel and not under a pier); element-wise for arrays."""
        n, e = np.broadcast_arrays(np.asarray(north, float), np.asarray(east, float))
        water = (self.north_min <= n) & (n <= self.north_max) & (np.abs(e) < self.half_width)
        for p in self.piers:
            water &= ~((p.north_min <= n) & (n <= p.north_max) & (p.east_min <= e) & (e <= p.east_max))
        return bool(water) if water.ndim == 0 else water


DEFAULT_LAYOUT = HarbourLayout()
