"""Perception: masks, clustering, lidar sweep → range-bearing scan, radar plots, camera bearings."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.layout import DEFAULT_LAYOUT
from seatwin.perception import MeasurementKind, Scan, cartesian_to_polar, polar_to_cartesian
from seatwin.perception.camera import camera_scan, pixel_bearing
from seatwin.perception.cluster import cluster_centroids, cluster_labels
from seatwin.perception.frames import FLU_TO_FRD, Mount, quaternion_matrix, sensor_pose
from seatwin.perception.lidar import LidarClustering, lidar_scan
from seatwin.perception.map_mask import LayoutMask, NoMask, RasterMask, load_mask
from seatwin.perception.radar import RadarPlots, radar_scan


def test_polar_round_trip() -> None:
    p = np.array([[10.0, 0.0], [0.0, 5.0], [-3.0, -4.0]])
    z = cartesian_to_polar(p, (1.0, 1.0))
    assert np.allclose(polar_to_cartesian(z, (1.0, 1.0)), p)
    assert np.allclose(cartesian_to_polar([[0.0, 5.0]])[0], [5.0, np.pi / 2])  # east = bearing +90°


def test_layout_mask_equals_layout_is_water() -> None:
    rng = np.random.default_rng(0)
    n = rng.uniform(-450, 450, 2000)
    e = rng.uniform(-150, 150, 2000)
    expect = np.array([DEFAULT_LAYOUT.is_water(a, b) for a, b in zip(n, e)])
    assert np.array_equal(LayoutMask().is_water(n, e), expect)
    assert isinstance(load_mask("none"), NoMask) and isinstance(load_mask("harbour"), LayoutMask)


def test_raster_mask(tmp_path) -> None:
    water = np.zeros((4, 3), np.uint8)
    water[1, 2] = 1  # row 1 (north 11..12), column 2 (east 22..23)
    (tmp_path / "m.bin").write_bytes(water.tobytes())
    (tmp_path / "m.yaml").write_text(
        "map_width: 3\nmap_height: 4\ngrid_resolution: 1\norigin_x_coordinate: 20.0\norigin_y_coordinate: 10.0\n"
    )
    m = RasterMask.load(tmp_path / "m.yaml")
    assert m.is_water(11.5, 22.5) and not m.is_water(10.5, 22.5) and not m.is_water(11.5, 21.5)
    assert not m.is_water(100.0, 100.0)  # outside the raster = land
    (tmp_path / "bad.bin").write_bytes(b"\x00" * 5)
    (tmp_path / "bad.yaml").write_text((tmp_path / "m.yaml").read_text())
    with pytest.raises(InputError, match="12 bytes"):
        RasterMask.load(tmp_path / "bad.bin")


def test_ravnkloa_raster_matches_scenario_water(shared_data) -> None:
    """The Ravnkloa raster: most trajectory points of the thesis scenarios lie on water (README: 70–100 %)."""
    m = RasterMask.load(shared_data / "ravnkloa" / "ravnkloa_radar_base_map.yaml")
    assert m.water.shape == (825, 617)
    data = np.genfromtxt(shared_data / "gemini-scenarios" / "Scenario3.csv", delimiter=",", names=True)
    frac = m.is_water(data["V1x"], data["V1y"]).mean()
    assert 0.7 <= frac <= 1.0


def test_clustering() -> None:
    rng = np.random.default_rng(2)
    a = rng.normal((10.0, 10.0), 0.3, (30, 2))
    b = rng.normal((30.0, -5.0), 0.3, (20, 2))
    noise = np.array([[100.0, 100.0]])
    labels = cluster_labels(np.concatenate((a, b, noise)), eps=1.5, min_points=3)
    assert labels[-1] == -1 and len(set(labels[:30])) == 1 and len(set(labels[30:50])) == 1
    c, counts = cluster_centroids(np.concatenate((a, b, noise)), 1.5, 3)
    order = np.argsort(counts)[::-1]
    assert np.allclose(c[order[0]], a.mean(0)) and np.allclose(c[order[1]], b.mean(0))
    assert cluster_labels(np.zeros((0, 2)), 1.0).size == 0


def test_mount_quaternion_of_flu_sensor() -> None:
    # A REP-103 sensor mounted straight ahead: x forward, y left (= −starboard), z up (= −down).
    q_flip = (1.0, 0.0, 0.0, 0.0)  # 180° about x
    assert np.allclose(quaternion_matrix(q_flip), FLU_TO_FRD)


def _box(center_n, center_e, half=1.5, n=200, seed=0):
    rng = np.random.default_rng(seed)
    return np.column_stack(
        (
            rng.uniform(center_n - half, center_n + half, n),
            rng.uniform(center_e - half, center_e + half, n),
            rng.uniform(-2.0, -0.2, n),
        )
    )


@pytest.mark.parametrize("heading", [0.0, 0.7, -2.5])
def test_lidar_scan_removes_ownship_and_land(heading) -> None:
    own = (0.0, 0.0)
    pose = sensor_pose(own[0], own[1], heading, Mount((1.0, 0.0, -2.0), FLU_TO_FRD))
    boat = _box(40.0, 10.0)  # on the water of the default harbour
    quay = _box(20.0, 80.0, seed=1)  # east > 75 m: land
    hull = _box(0.0, 0.0, half=1.0, seed=2)  # the ownship's own returns
    world = np.concatenate((boat, quay, hull))
    # world → sensor frame (inverse of SensorPose.to_world)
    sensor_pts = (world - pose.position) @ pose.rotation
    scan = lidar_scan(sensor_pts, 5.0, pose, LayoutMask(), LidarClustering())
    assert scan.kind is MeasurementKind.RANGE_BEARING and scan.z.shape == (1, 2)
    expect = cartesian_to_polar(boat[:, :2].mean(0, keepdims=True), (pose.north, pose.east))
    assert np.allclose(scan.z, expect, atol=1e-9)
    no_mask = lidar_scan(sensor_pts, 5.0, pose, NoMask(), LidarClustering())
    assert no_mask.z.shape == (2, 2)  # the quay appears without the mask; the hull never


def test_radar_scan_mask_merge_and_kinds() -> None:
    plots = np.array([[10.0, 0.0], [11.0, 0.5], [50.0, 200.0], [np.inf, 1.0]])
    s = radar_scan(plots, 1.0, 0.0, 0.0, LayoutMask(), RadarPlots(merge_distance=2.0))
    assert s.z.shape == (1, 2) and np.allclose(s.positions(), [[10.5, 0.25]])
    s = radar_scan(plots, 1.0, 0.0, 0.0, None, RadarPlots(kind=MeasurementKind.CARTESIAN))
    assert s.kind is MeasurementKind.CARTESIAN and s.z.shape == (3, 2)


def test_camera_bearing() -> None:
    assert np.isclose(pixel_bearing(306.0 + 300.0, 300.0, 306.0), np.pi / 4)
    s = camera_scan([306.0, 606.0], 2.0, 300.0, 306.0, np.pi / 2, 1.0, 2.0)
    assert s.kind is MeasurementKind.BEARING and np.allclose(s.z[:, 0], [np.pi / 2, 3 * np.pi / 4])


def test_scan_shapes() -> None:
    s = Scan(0.0, "camera", "bearing", [0.1, 0.2])
    assert s.z.shape == (2, 1)
    with pytest.raises(ValueError):
        s.positions()


def test_load_mask_names(shared_data):
    from seatwin.perception.map_mask import LayoutMask, NoMask, RasterMask, load_mask

    assert isinstance(load_mask("harbour"), LayoutMask) and isinstance(load_mask("default"), LayoutMask)
    assert isinstance(load_mask("none"), NoMask) and isinstance(load_mask(None), NoMask)
    assert isinstance(load_mask("ravnkloa"), RasterMask)
