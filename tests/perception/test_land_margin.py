"""Returns near land are dropped before tracking (issue 21): the lidar's quay face within ``land_margin``,
radar plots within ``land_margin`` + range · tan ``land_margin_deg`` of land."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.layout.raster import LandRaster
from seatwin.perception.frames import FLU_TO_FRD, Mount, sensor_pose
from seatwin.perception.lidar import LidarClustering, lidar_scan
from seatwin.perception.map_mask import LayoutMask, NoMask, RasterMask
from seatwin.perception.radar import RadarPlots, radar_scan


def _canal() -> RasterMask:
    """Water for east in [−20, 20) m, land beyond (1 m cells from −50 m), north −50 … 150 m."""
    water = np.zeros((200, 100), bool)
    water[:, 30:70] = True
    return RasterMask(LandRaster(water, -50.0, -50.0, 1.0))


def test_raster_clear_of_land_is_the_distance_to_the_nearest_land_cell() -> None:
    mask = _canal()
    east = np.array([0.5, 15.5, 17.5, 18.5, 19.5, 20.5])  # cell centres; land from east 20
    north = np.zeros_like(east)
    assert mask.clear_of_land(north, east, 0.0).tolist() == [True] * 5 + [False]
    assert mask.clear_of_land(north, east, 1.5).tolist() == [True, True, True, True, False, False]
    assert mask.clear_of_land(north, east, 2.5).tolist() == [True, True, True, False, False, False]
    assert mask.clear_of_land([500.0], [0.0], 0.0).tolist() == [False]  # outside the raster: land
    assert mask.clear_of_land(north, east, np.array([0, 0, 0, 3.0, 0, 0])).tolist() == [True, True, True, False, True, False]


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.floats(-60, 160), st.floats(-60, 60)), min_size=1, max_size=30),
    st.floats(0.0, 10.0),
    st.floats(0.0, 10.0),
)
def test_clear_of_land_is_water_at_zero_and_shrinks_with_the_margin(points, m1, m2) -> None:
    mask = _canal()
    n, e = np.array(points).T
    assert (mask.clear_of_land(n, e, 0.0) == mask.is_water(n, e)).all()
    lo, hi = sorted((m1, m2))
    small, large = mask.clear_of_land(n, e, lo), mask.clear_of_land(n, e, hi)
    assert not (large & ~small).any()  # a wider margin never adds water
    layout = LayoutMask()
    assert not (layout.clear_of_land(n, e, hi) & ~layout.is_water(n, e)).any()
    assert NoMask().clear_of_land(n, e, hi).all()


def test_lidar_drops_the_quay_face_and_keeps_a_boat_off_it() -> None:
    pose = sensor_pose(0.0, 0.0, 0.0, Mount((0.0, 0.0, -2.0), FLU_TO_FRD))
    rng = np.random.default_rng(0)
    # A vertical quay face on the land edge (east 20 m), 0–1.5 m high, north 10–40 m; a boat moored against
    # the quay further north (east 16–19.8 m).
    face = np.column_stack([rng.uniform(10, 40, 300), rng.normal(20.0, 0.3, 300), -rng.uniform(0, 1.5, 300)])
    boat = np.column_stack([rng.uniform(60, 66, 80), rng.uniform(16.0, 19.8, 80), -rng.uniform(0.2, 1.5, 80)])
    world = np.concatenate([face, boat])
    pts = (world - pose.position) @ pose.rotation
    bare = lidar_scan(pts, 1.0, pose, _canal(), LidarClustering(land_margin=0.0))
    assert bare.z.shape[0] == 2  # the face's water-side half makes a cluster on the water
    scan = lidar_scan(pts, 1.0, pose, _canal(), LidarClustering())
    assert scan.z.shape[0] == 1
    outer = boat[boat[:, 1] < 19.0]  # the boat's points more than 1.5 m from the land cells' centres
    np.testing.assert_allclose(scan.positions()[0], outer[:, :2].mean(axis=0), atol=1e-9)


def test_radar_margin_grows_with_range() -> None:
    mask = _canal()
    # Plots 3 m from land (east 17.5) at 20 m and at 140 m from the radar at the origin: the margin, 2 m +
    # range · tan 1°, is 2.35 m at 20 m (kept) and 4.45 m at 140 m (dropped); mid-canal at 140 m is kept.
    plots = np.array([[20.0, 17.5], [140.0, 17.5], [140.0, 0.0]])
    s = radar_scan(plots, 1.0, 0.0, 0.0, mask, RadarPlots(kind="cartesian"))
    assert s.z.tolist() == [[20.0, 17.5], [140.0, 0.0]]
    none = radar_scan(plots, 1.0, 0.0, 0.0, mask, RadarPlots(kind="cartesian", land_margin=0.0, land_margin_deg=0.0))
    assert none.z.shape[0] == 3


def test_raster_clear_of_land_applies_the_harbours_alignment() -> None:
    """Points are taken into the raster's own frame first, as ``is_water`` does: with margin 0 both agree
    in an aligned harbour (a rotated canal), and a point on water in the scenario frame is clear of land."""
    from seatwin.layout.alignment import Alignment

    raster = _canal().raster.aligned(Alignment(rotation_deg=30.0, shift_north=3.0))
    mask = RasterMask(raster)
    rng = np.random.default_rng(0)
    north, east = rng.uniform(-60, 160, 500), rng.uniform(-60, 60, 500)
    water = mask.is_water(north, east)
    assert 0 < water.sum() < len(water)
    np.testing.assert_array_equal(mask.clear_of_land(north, east, 0.0), water)
