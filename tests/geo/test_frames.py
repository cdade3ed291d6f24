"""Frames and rotations (seatwin.geo.frames) against hand-computed matrices."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.geo import (
    FLU_TO_FRD,
    NED_TO_ENU,
    OPTICAL_TO_FRD,
    enu_to_ned,
    euler_zyx,
    mount_matrix,
    ned_to_enu,
    quaternion_matrix,
    rot_x,
    rot_y,
    rot_z,
    yaw_matrix,
    yaw_rotate,
)


def test_ned_enu_swap() -> None:
    np.testing.assert_array_equal(ned_to_enu([1.0, 2.0, 3.0]), [2.0, 1.0, -3.0])
    np.testing.assert_array_equal(NED_TO_ENU @ [1.0, 2.0, 3.0], [2.0, 1.0, -3.0])
    v = np.arange(12.0).reshape(4, 3)
    np.testing.assert_array_equal(enu_to_ned(ned_to_enu(v)), v)
    np.testing.assert_array_equal(ned_to_enu(v), v @ NED_TO_ENU.T)


def test_flu_frd_and_optical_axes() -> None:
    np.testing.assert_array_equal(FLU_TO_FRD @ [1.0, 1.0, 1.0], [1.0, -1.0, -1.0])  # left → port, up → up (−down)
    np.testing.assert_array_equal(FLU_TO_FRD @ FLU_TO_FRD, np.eye(3))
    np.testing.assert_array_equal(OPTICAL_TO_FRD @ [0.0, 0.0, 1.0], [1.0, 0.0, 0.0])  # optical z = forward
    np.testing.assert_array_equal(OPTICAL_TO_FRD @ [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])  # optical x = starboard
    np.testing.assert_array_equal(OPTICAL_TO_FRD @ [0.0, 1.0, 0.0], [0.0, 0.0, 1.0])  # optical y = down


def test_yaw_is_clockwise_from_north_seen_from_above() -> None:
    # A vessel heading east (π/2): its bow (body x) points east, its starboard (body y) south.
    np.testing.assert_allclose(yaw_matrix(math.pi / 2) @ [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], atol=1e-16)
    np.testing.assert_allclose(yaw_matrix(math.pi / 2) @ [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], atol=1e-16)
    c, s = math.cos(0.3), math.sin(0.3)
    np.testing.assert_array_equal(yaw_matrix(0.3), [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    assert rot_z is yaw_matrix


def test_rot_x_and_rot_y_hand_values() -> None:
    np.testing.assert_allclose(rot_x(math.pi / 2) @ [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], atol=1e-16)  # y → z
    # Pitch about the starboard axis: positive turns the bow up, i.e. towards −down.
    np.testing.assert_allclose(rot_y(math.radians(30)) @ [1.0, 0.0, 0.0], [math.sqrt(3) / 2, 0.0, -0.5], atol=1e-15)


def test_euler_zyx_order() -> None:
    r, p, y = 0.1, -0.2, 0.7
    np.testing.assert_array_equal(euler_zyx(r, p, y), rot_z(y) @ rot_y(p) @ rot_x(r))
    # Z-Y-X as scipy writes it (intrinsic rotations), to rounding
    from scipy.spatial.transform import Rotation

    np.testing.assert_allclose(euler_zyx(r, p, y), Rotation.from_euler("ZYX", [y, p, r]).as_matrix(), atol=1e-15)


def test_mount_matrix() -> None:
    np.testing.assert_array_equal(mount_matrix("flu"), FLU_TO_FRD)
    np.testing.assert_array_equal(mount_matrix("frd"), np.eye(3))
    # milliAmpere's VLP-16: upside down (roll 180°), turned 57.3° to starboard — its z axis points down,
    # its x axis 57.3° to starboard of the bow.
    m = mount_matrix("flu", roll=math.pi, yaw=math.radians(57.3))
    np.testing.assert_allclose(m @ [0.0, 0.0, 1.0], [0.0, 0.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(m @ [1.0, 0.0, 0.0], [math.cos(math.radians(57.3)), math.sin(math.radians(57.3)), 0.0], atol=1e-15)
    with pytest.raises(ValueError, match="convention"):
        mount_matrix("nwu")


def test_quaternion_matrix_hand_values() -> None:
    np.testing.assert_allclose(quaternion_matrix([0.0, 0.0, 0.0, 2.0]), np.eye(3))  # normalised first
    np.testing.assert_allclose(quaternion_matrix([1.0, 0.0, 0.0, 0.0]), FLU_TO_FRD, atol=1e-16)  # half turn about x
    h = math.sqrt(0.5)
    np.testing.assert_allclose(quaternion_matrix([0.0, 0.0, h, h]), yaw_matrix(math.pi / 2), atol=1e-15)


def test_yaw_rotate_is_the_matrix_per_point() -> None:
    h = np.array([0.0, math.pi / 2, 1.0])
    x, y = np.array([1.0, 1.0, 2.0]), np.array([0.0, 0.0, -3.0])
    n, e = yaw_rotate(h, x, y)
    np.testing.assert_allclose(n[:2], [1.0, 0.0], atol=1e-16)
    np.testing.assert_allclose(e[:2], [0.0, 1.0], atol=1e-16)  # bow of an east-heading vessel points east
    np.testing.assert_allclose([n[2], e[2]], (yaw_matrix(1.0) @ [2.0, -3.0, 0.0])[:2], atol=1e-15)
