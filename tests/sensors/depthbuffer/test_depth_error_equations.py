"""Thesis 4.1.3: numerical error of depth buffers (4.20–4.36), against hand-computed values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.sensors.depthbuffer.errors import (
    c1,
    c2,
    camera_count_gain,
    discrete_step,
    error,
    error_components,
    error_gradient,
    height_from_memory,
    max_error,
    max_error_conditions,
    max_error_numeric,
    max_error_point,
    video_memory,
    video_memory_lidar,
)
from seatwin.sensors.depthbuffer.projection import DepthCamera, camera_vfov, discrete_coordinates

D = math.radians
LIDAR_PRINTED = DepthCamera(4433, 3104, D(41.5), 0.05, 100.0)
LIDAR = DepthCamera(4433, 3104, camera_vfov(D(30), D(45)), 0.05, 100.0)
RGB = DepthCamera(612, 512, D(65.4), 0.08, 1e4)


def test_constants_c1_c2() -> None:
    # C1 = 2^24 · 0.05 · 100 / 99.95; C2 = 2 C1 tan(20.75°) / 3104
    assert c1(LIDAR_PRINTED) == pytest.approx(16777216 * 5 / 99.95)
    assert c1(LIDAR_PRINTED) == pytest.approx(839280.44, abs=0.01)
    assert c2(LIDAR_PRINTED) == pytest.approx(204.8807, abs=1e-3)
    assert c1(RGB) == pytest.approx(1342188.0175, abs=1e-3)


def test_c2_lidar_form_4_34() -> None:
    want = 2 * c1(LIDAR) / 3104 * math.tan(D(15)) / math.cos(math.pi / 8)
    assert c2(LIDAR) == pytest.approx(want)


def test_discrete_step_4_20_is_the_difference_of_4_9() -> None:
    p0, p1 = np.array([[1.0, -2.0, -30.0]]), np.array([[1.3, -2.1, -30.4]])
    want = discrete_coordinates(p1, LIDAR) - discrete_coordinates(p0, LIDAR)
    np.testing.assert_allclose(discrete_step(p0, p1, LIDAR), want, rtol=1e-6)


def test_components_4_21_are_one_discrete_step() -> None:
    p0 = np.array([[3.0, -4.0, -60.0]])
    e = error_components(p0, LIDAR)
    # z: one depth step z^d_ε = 1; x, y: one pixel (sign of the step is the thesis's convention)
    step = discrete_step(p0, p0 + e, LIDAR)[0]
    assert step[2] == pytest.approx(1.0, rel=1e-6)
    assert abs(step[0]) == pytest.approx(1.0, rel=1e-6) and abs(step[1]) == pytest.approx(1.0, rel=1e-6)
    # hand values at z = −60: z_ε = −3600 / (C1 − 60)
    assert e[0, 2] == pytest.approx(-3600 / (c1(LIDAR) - 60))


def test_error_4_22_hand_value_at_the_table_corner() -> None:
    q = max_error_point(LIDAR_PRINTED, D(45))
    np.testing.assert_allclose(q, [-41.42136, -37.88661, -100.0], atol=1e-4)  # 4.32
    # |z/(C1+z)| · sqrt((x−C2)² + (y−C2)² + z²) = 100/839180.44 · sqrt(246.3021² + 242.7674² + 100²)
    hand = 100 / 839180.44 * math.sqrt(246.3021**2 + 242.7674**2 + 100**2)
    assert error(q, LIDAR_PRINTED)[0] == pytest.approx(hand, rel=1e-5)
    assert hand == pytest.approx(0.042899, abs=1e-6)
    # 4.22 is the norm of 4.21
    p = np.array([[2.0, 1.0, -10.0]])
    assert error(p, LIDAR)[0] == pytest.approx(np.linalg.norm(error_components(p, LIDAR)))


def test_gradient_4_23_matches_finite_differences_and_vanishes_at_the_candidate() -> None:
    p = np.array([10.0, -5.0, -40.0])
    g = error_gradient(p, LIDAR)[0]
    h = 1e-4
    fd = [(error(p + h * e, LIDAR)[0] - error(p - h * e, LIDAR)[0]) / (2 * h) for e in np.eye(3)]
    np.testing.assert_allclose(g, fd, rtol=1e-5)
    # maxima candidate x = y = C2, z = −2 C1 (text after 4.24)
    cand = np.array([c2(LIDAR), c2(LIDAR), -2 * c1(LIDAR)])
    np.testing.assert_allclose(error_gradient(cand, LIDAR)[0], 0.0, atol=1e-12)


def test_gradient_negative_inside_the_frustum_4_26_4_29_4_31() -> None:
    rng = np.random.default_rng(3)
    z = -rng.uniform(LIDAR.near, LIDAR.far, 500)
    x = -z * rng.uniform(-1, 1, 500) * math.tan(D(22.5))
    y = -z * rng.uniform(-1, 1, 500) * math.tan(LIDAR.vfov_c / 2)
    assert np.all(error_gradient(np.stack([x, y, z], 1), LIDAR) < 0)


def test_max_error_4_32_values_and_conditions_4_33() -> None:
    assert max_error(LIDAR_PRINTED, D(45)) == pytest.approx(0.0429, abs=5e-5)  # Table 4.1: 0.04
    assert max_error(LIDAR) == pytest.approx(0.0345, abs=5e-5)  # consistent VFOV_c (4.17)
    assert max_error(RGB, D(75)) == pytest.approx(133.78, abs=0.01)  # Table 4.1: 140
    assert all(max_error_conditions(LIDAR).values())
    rgb_cond = max_error_conditions(RGB)
    assert not rgb_cond["f < n(2 N_cd/N_ch + 1) (4.29, 4.33)"]  # 1e4 ≥ 0.08 · 65537
    assert not rgb_cond["f < n(2 N_cd/N_cw + 1) (4.31, 4.33)"]  # 1e4 ≥ 0.08 · 54828
    printed_width = DepthCamera(32768, 3104, D(41.5), 0.05, 100.0)
    assert not max_error_conditions(printed_width)["f < n(2 N_cd/N_cw + 1) (4.31, 4.33)"]  # 100 ≥ 51.25
    # the corner is the maximum over the frustum, also for the RGB row where 4.33 fails
    assert max_error_numeric(LIDAR) == pytest.approx(max_error(LIDAR), rel=1e-9)
    assert max_error_numeric(RGB, D(75)) == pytest.approx(max_error(RGB, D(75)), rel=1e-9)


def test_rgb_depth_error_below_1cm_at_100m() -> None:
    # thesis 4.2.3: "the depth error ... being less than 1cm at a 100m distance"
    e = error_components([[0.0, 0.0, -100.0]], RGB)[0, 2]
    assert abs(e) == pytest.approx(10000 / (c1(RGB) - 100))
    assert abs(e) < 0.01


def test_video_memory_4_35_and_height_4_36() -> None:
    assert video_memory(4433, 3104, 8, 2**24) == 330_240_768  # 3 bytes · 4433 · 3104 · 8
    assert video_memory(612, 512, 1, 2**24) == 940_032  # Table 4.1 prints 9.4·10^4
    assert video_memory(612, 512, 1, 2**16) == 626_688  # 2 bytes a pixel
    bs = video_memory_lidar(3104, 8, 2**24, D(30))
    assert bs == pytest.approx(3 * 3104 * 4433.114 * 8, rel=1e-6)  # B with the unrounded N_cw of 4.16
    assert height_from_memory(bs, 8, 2**24, D(30)) == pytest.approx(3104)
    assert height_from_memory(3.3e8, 8, 2**24, D(30)) == pytest.approx(3102.83, abs=0.01)


def test_camera_gain_fig_4_8() -> None:
    g = camera_count_gain([3, 4, 8])
    assert g == pytest.approx([2.0, math.sqrt(2), 1.0823922], rel=1e-6)
    assert g[2] / g[0] == pytest.approx(0.541, abs=1e-3)  # "more than 8 cameras almost halves the error of 3"
