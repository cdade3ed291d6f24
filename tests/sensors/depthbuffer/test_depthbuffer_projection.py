"""Thesis 4.1.1–4.1.2 and 4.2.2: projection (4.3–4.9), filter (4.10–4.19), back-projection (4.37–4.42)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.sensors.depthbuffer import filter as filter_module
from seatwin.sensors.depthbuffer.filter import (
    AzimuthGrid,
    grid_angles,
    grid_columns,
    grid_directions,
    grid_radius,
    legacy_grid,
    point_cloud_depth,
    project_reference,
    reference_point,
    sensor_angles,
    spherical_filter,
    split_cameras,
)
from seatwin.sensors.depthbuffer.projection import (
    VIEW_TO_SENSOR,
    DepthCamera,
    aspect_ratio,
    back_project,
    camera_hfov,
    camera_vfov,
    camera_width,
    depth_to_discrete,
    discrete_coordinates,
    discrete_to_depth,
    image_to_discrete,
    pixel_ray,
    projection_matrix,
    quantise,
    rotation_y,
    to_image_space,
    unite_clouds,
)

D = math.radians
RGB = DepthCamera(612, 512, D(65.4), 0.08, 1e4)
LIDAR = DepthCamera(4433, 3104, camera_vfov(D(30), D(45)), 0.05, 100.0)


def test_aspect_ratio_4_3() -> None:
    # tan(37.5°)/tan(32.7°) = 0.767327 / 0.641989
    assert aspect_ratio(D(75.0), D(65.4)) == pytest.approx(1.195234, rel=1e-5)
    assert RGB.aspect == pytest.approx(612 / 512)
    assert math.degrees(RGB.hfov_c) == pytest.approx(75.0, abs=0.01)  # the RGB row of Table 4.1 is consistent


def test_projection_matrix_4_5() -> None:
    t = projection_matrix(RGB)
    assert t[0, 0] == pytest.approx(512 / 612 / math.tan(D(32.7)))  # 1.303140
    assert t[0, 0] == pytest.approx(1.303140, rel=1e-6)
    assert t[1, 1] == pytest.approx(1.557660, rel=1e-6)
    assert t[2, 2] == pytest.approx(-10000.08 / 9999.92)
    assert t[2, 3] == pytest.approx(-2 * 1e4 * 0.08 / 9999.92)
    assert t[3].tolist() == [0, 0, -1, 0]


def test_image_space_4_6_4_7_near_far_and_corner() -> None:
    h = math.tan(RGB.hfov_c / 2)
    v = math.tan(RGB.vfov_c / 2)
    q = np.array([[0, 0, -RGB.near], [0, 0, -RGB.far], [-5 * h, -5 * v, -5.0], [5 * h, 5 * v, -5.0]])
    qi = to_image_space(q, RGB)
    assert qi[0, 2] == pytest.approx(-1.0) and qi[1, 2] == pytest.approx(1.0)
    # x^i = -(N_ch/N_cw) cot(V/2) x/z: the left edge (x < 0) maps to −1, the right to +1
    assert qi[2, :2] == pytest.approx([-1.0, -1.0]) and qi[3, :2] == pytest.approx([1.0, 1.0])


def test_component_form_4_9_equals_matrix_form_4_8() -> None:
    rng = np.random.default_rng(1)
    z = -rng.uniform(RGB.near, RGB.far, 200)
    x = z * rng.uniform(-1, 1, 200) * math.tan(RGB.hfov_c / 2)
    y = z * rng.uniform(-1, 1, 200) * math.tan(RGB.vfov_c / 2)
    q = np.stack([x, y, z], 1)
    np.testing.assert_allclose(discrete_coordinates(q, RGB), image_to_discrete(to_image_space(q, RGB), RGB), rtol=1e-9, atol=1e-6)
    # z^d spans [0, N_cd] from the near to the far plane (the printed N_cd inside 4.9 is a typo)
    assert depth_to_discrete(-RGB.near, RGB) == pytest.approx(0.0, abs=1e-6)
    assert depth_to_discrete(-RGB.far, RGB) == pytest.approx(RGB.n_cd)
    assert discrete_to_depth(depth_to_discrete(-37.0, RGB), RGB) == pytest.approx(-37.0)


def test_quantise_4_8_truncates_and_clips() -> None:
    q = quantise([[0.99, 511.2, 1e9], [-0.5, 3.0, 12.7]], RGB)
    assert q.tolist() == [[0, 511, RGB.n_cd - 1], [0, 3, 12]]
    assert q.dtype.kind == "i"


def test_back_projection_4_37_to_4_40_inverts_projection() -> None:
    # A point at a pixel centre and an exact z^d level comes back exactly.
    zd = 12_345_678
    z = discrete_to_depth(zd, RGB)
    ray = pixel_ray(100, 200, RGB)[None, :]
    p = -z * ray  # on the pixel-centre ray at depth −z
    q_d = np.array([[100, 200, zd]])
    np.testing.assert_allclose(back_project(q_d, RGB), p, rtol=1e-9)
    # literal 4.37 (pixel corner) differs by half a pixel
    corner = back_project(q_d, RGB, xy_offset=0.0)
    assert not np.allclose(corner, p)


def test_rotation_4_41_and_union_4_42() -> None:
    r = rotation_y(2, 8)  # 90°
    np.testing.assert_allclose(r, [[0, 0, 1], [0, 1, 0], [-1, 0, 0]], atol=1e-12)
    # camera c looks along −z of its own view space; in camera 0's frame that is azimuth 2πc/N_c
    fwd = unite_clouds([[0, 0, -1.0]], [1], 8)[0]
    s = VIEW_TO_SENSOR @ fwd
    assert math.atan2(s[1], s[0]) == pytest.approx(math.pi / 4)
    assert np.linalg.det(VIEW_TO_SENSOR) == pytest.approx(1.0)


def test_fov_and_width_4_14_4_16_4_17() -> None:
    assert camera_hfov(8) == pytest.approx(math.pi / 4)
    assert math.degrees(camera_vfov(D(30), D(45))) == pytest.approx(32.347, abs=1e-3)
    assert math.degrees(camera_vfov(D(30), D(90))) == pytest.approx(41.507, abs=1e-3)  # Table 4.1's 41.5°
    assert camera_width(3104, D(30), D(45)) == pytest.approx(4433.114, abs=1e-3)
    assert camera_width(3104, D(30), D(90)) == pytest.approx(8191.327, abs=1e-3)
    # 4.16 is 4.15 with 4.17 substituted
    v = camera_vfov(D(30), D(45))
    assert 3104 / camera_width(3104, D(30), D(45)) == pytest.approx(math.tan(v / 2) / math.tan(D(22.5)))


def test_reference_model_4_10_and_grid_4_12_4_13() -> None:
    np.testing.assert_allclose(reference_point(D(30), D(10), 2.0), [-0.984808, 0.347296, -1.705737], atol=1e-6)
    theta, phi = grid_angles(256, 16, 4, D(30))
    assert len(theta) == 64 and len(phi) == 16
    assert np.degrees(theta[:2]) == pytest.approx([-45.0, -43.59375])
    assert np.degrees(phi[:2]) == pytest.approx([-15.0, -13.125])
    assert grid_radius([0, 2**24], 0.05, 100.0, 2**24) == pytest.approx([0.05, 100.0])
    with pytest.raises(ValueError, match="multiple"):
        grid_angles(250, 16, 4, D(30))


def test_filter_projection_4_18_is_4_9_of_the_reference_model() -> None:
    rng = np.random.default_rng(2)
    th = rng.uniform(-math.pi / 8, math.pi / 8, 100)
    ph = rng.uniform(-D(15), D(15), 100)
    r = rng.uniform(1, 99, 100)
    np.testing.assert_allclose(
        project_reference(th, ph, r, LIDAR), discrete_coordinates(reference_point(th, ph, r), LIDAR), rtol=1e-9, atol=1e-6
    )
    # 4.17 makes the top beam at the sector edge land exactly on the image's top edge
    top = project_reference(math.pi / 8, D(15), 50.0, LIDAR)
    assert top[1] == pytest.approx(LIDAR.n_ch, abs=1e-6)
    assert top[0] == pytest.approx(0.0, abs=0.2)  # N_cw rounded from 4433.11
    assert point_cloud_depth(top[2], LIDAR) == pytest.approx(top[2] / 2**24)  # 4.19


def test_split_cameras_sector_bounds() -> None:
    c, th = split_cameras(np.radians([0, 22.4, 22.6, 180, -22.6, 359]), 8)
    assert c.tolist() == [0, 0, 1, 4, 7, 0]
    assert np.all(np.abs(th) <= math.pi / 8 + 1e-12)


def test_filter_mask_fig_4_6_one_pixel_per_beam() -> None:
    cam = DepthCamera(169, 64, camera_vfov(D(30), D(90)), 0.05, 100.0)
    # The first column of each camera lies exactly on a sector boundary: its camera comes
    # from the integer column index (grid_columns), the same on every CPU.
    m = spherical_filter(grid_directions(256, 16, 4, D(30)), cam, 4, grid_columns(256, 16, 4))
    assert len(m) == 256 * 16
    assert np.bincount(m.camera).tolist() == [1024] * 4
    assert m.mask(0).sum() == 1024  # every beam has its own pixel: N_sw·N_sh ≤ N_cw·N_ch, no collisions
    # rows bend away from the centre towards the sector edges (tan φ / cos θ), the bow-tie of Fig. 4.6
    top_row = m.y_d[(m.camera == 0)].reshape(16, 64)[-1]
    assert top_row[0] > top_row[32] and top_row[-1] > top_row[32]


def test_azimuth_grid_cameras_hand_values() -> None:
    # 8 columns at 0°, 45°, …, 315° and 4 cameras of 90° centred on 0°, 90°, …: a beam on a
    # boundary (45°, 135°, 225°, 315° = −45°) opens the next sector, [−45°, 45°) is camera 0.
    assert AzimuthGrid(np.arange(8), 8).cameras(4).tolist() == [0, 1, 1, 2, 2, 3, 3, 0]
    assert AzimuthGrid(np.array([-1, -7, 8, 15]), 8).cameras(4).tolist() == [0, 1, 0, 0]  # indices wrap
    assert AzimuthGrid.lidar(4, 2).index.tolist() == [0, 0, -1, -1, -2, -2, -3, -3]  # clockwise columns
    g = grid_columns(256, 16, 4)
    assert g.matches(sensor_angles(grid_directions(256, 16, 4, D(30)))[0])
    assert np.bincount(g.cameras(4)).tolist() == [1024] * 4
    assert not g.matches(sensor_angles(grid_directions(256, 16, 4, D(30)))[0] + 1e-4)


def _boundary_azimuths(grid: AzimuthGrid, ulps: int) -> np.ndarray:
    """The exact grid azimuths, each moved ``ulps`` floating-point steps (as trigonometry might)."""
    a = grid.azimuth()
    for _ in range(abs(ulps)):
        a = np.nextafter(a, np.inf if ulps > 0 else -np.inf)
    return a


@pytest.mark.parametrize("use_filter", [True, False])
def test_boundary_beams_are_assigned_from_integers(monkeypatch: pytest.MonkeyPatch, use_filter: bool) -> None:
    cam = DepthCamera(169, 64, camera_vfov(D(30), D(90)), 0.05, 100.0)
    dirs = grid_directions(256, 16, 4, D(30))
    grid = grid_columns(256, 16, 4)
    make = spherical_filter if use_filter else legacy_grid
    true_sensor_angles = sensor_angles
    maps = {}
    for ulps in (-2, -1, 0, 1, 2):
        # Trigonometry one or two ulps off (another CPU's sin/cos/atan2): the boundary beams'
        # azimuths fall either side of the sector boundary.
        def perturbed(d: np.ndarray, u: int = ulps) -> tuple[np.ndarray, np.ndarray]:
            return _boundary_azimuths(grid, u), true_sensor_angles(d)[1]

        monkeypatch.setattr(filter_module, "sensor_angles", perturbed)
        maps[ulps] = (make(dirs, cam, 4, grid), make(dirs, cam, 4))
    with_grid = [m for m, _ in maps.values()]
    for m in with_grid:
        assert np.array_equal(m.camera, grid.cameras(4))
        assert np.bincount(m.camera).tolist() == [1024] * 4
        assert np.array_equal(m.x_d, with_grid[0].x_d) and np.array_equal(m.y_d, with_grid[0].y_d)
    # Without the integers the same perturbations move the boundary columns between cameras.
    assert len({tuple(np.bincount(m.camera, minlength=4)) for _, m in maps.values()}) > 1


def test_azimuth_grid_rejects_directions_off_the_grid() -> None:
    from seatwin.sensors.depthbuffer.model import DepthBufferConfig, DepthBufferLidar
    from seatwin.sensors.lidar_config import VLP16

    dirs = VLP16.with_(columns=64).sensor_directions()
    DepthBufferLidar(dirs, DepthBufferConfig(), AzimuthGrid.lidar(64, VLP16.rings))  # on the grid
    with pytest.raises(ValueError, match="azimuth grid"):
        DepthBufferLidar(dirs, DepthBufferConfig(), AzimuthGrid(-np.repeat(np.arange(64), VLP16.rings), 65))  # 65 columns


def test_legacy_grid_rows_are_flat() -> None:
    cam = DepthCamera(169, 64, camera_vfov(D(30), D(90)), 0.05, 100.0)
    m = legacy_grid(grid_directions(256, 16, 4, D(30)), cam, 4)
    rows = m.y_d[m.camera == 0].reshape(16, 64)
    assert np.all(rows == rows[:, :1])  # one image row per laser: the beam shape error
    assert not m.filtered
