"""The 2-D harbour layout (seatwin.layout): water of the default harbour, scalars and arrays alike."""

from __future__ import annotations

import numpy as np

from seatwin.layout import DEFAULT_LAYOUT, HarbourLayout, LandRaster


def test_is_water_hand_points() -> None:
    lay = DEFAULT_LAYOUT
    assert lay.is_water(0.0, 0.0) is True
    assert lay.is_water(0.0, lay.half_width) is False  # the quay edge is land
    assert lay.is_water(lay.north_max + 1.0, 0.0) is False  # beyond the channel's ends
    pier = lay.piers[0]
    mid = (0.5 * (pier.north_min + pier.north_max), 0.5 * (pier.east_min + pier.east_max))
    assert lay.is_water(*mid) is False
    assert HarbourLayout(piers=()).is_water(*mid) is True


def test_is_water_arrays_match_points() -> None:
    rng = np.random.default_rng(7)
    n, e = rng.uniform(-450, 450, 2000), rng.uniform(-100, 100, 2000)
    water = DEFAULT_LAYOUT.is_water(n, e)
    assert water.dtype == bool and water.shape == (2000,)
    assert water.tolist() == [DEFAULT_LAYOUT.is_water(float(a), float(b)) for a, b in zip(n, e)]
    assert 0.2 < water.mean() < 0.9


def test_land_raster_cells() -> None:
    water = np.array([[True, False], [True, True]])  # row 0 is the southern edge
    r = LandRaster(water, origin_north=10.0, origin_east=20.0, resolution=2.0)
    assert r.is_water(np.array([10.5, 10.5, 12.5, 50.0]), np.array([20.5, 22.5, 22.5, 0.0])).tolist() == [True, False, True, True]
