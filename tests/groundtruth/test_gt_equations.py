"""Thesis §3.3.2 equations (3.6, 3.7), velocity and course, GPS time — against hand values."""

from __future__ import annotations

import calendar
import math

import numpy as np
import pytest

from seatwin.groundtruth import (
    antenna_distance,
    antenna_midpoint,
    course_over_ground,
    gnss_baseline_error,
    gps_minus_utc,
    gps_week_to_utc,
    gpst_to_utc,
    velocity_central,
)
from seatwin.groundtruth.equations import heading_from_antennas


def test_eq_3_7_hand_values() -> None:
    # Antennas exactly the Finn baseline apart: ε = 0.
    assert gnss_baseline_error(2.93, 0.0, 0.0, 0.0, 2.93) == pytest.approx(0.0, abs=1e-15)
    # 3-4-5 triangle: measured 5 m, Havfruen baseline 2.01 m → 2.99 m.
    assert gnss_baseline_error(3.0, 4.0, 0.0, 0.0, 2.01) == pytest.approx(2.99, abs=1e-12)
    # Measured shorter than the baseline: absolute value.
    assert gnss_baseline_error(10.0, 20.0, 10.6, 20.8, 2.01) == pytest.approx(1.01, abs=1e-12)
    e = gnss_baseline_error(np.array([1.0, 0.0]), np.array([0.0, 2.0]), 0.0, 0.0, 1.5)
    np.testing.assert_allclose(e, [0.5, 0.5])


def test_antenna_distance_and_midpoint() -> None:
    assert antenna_distance(3.0, 4.0, 0.0, 0.0) == pytest.approx(5.0)
    assert antenna_midpoint(2.0, 4.0, 0.0, 0.0) == (pytest.approx(1.0), pytest.approx(2.0))


def test_eq_3_6_reexported() -> None:
    assert heading_from_antennas(0.0, 1.0, 0.0, 0.0) == pytest.approx(math.pi / 2)


def test_velocity_central_exact_for_linear_motion() -> None:
    t = 1.6e9 + np.arange(0.0, 10.0, 0.1)
    vn, ve = velocity_central(t, 2.0 * (t - t[0]), -1.5 * (t - t[0]), window=1)
    np.testing.assert_allclose(vn, 2.0, rtol=1e-6)
    np.testing.assert_allclose(ve, -1.5, rtol=1e-6)
    vn, ve = velocity_central(t, 2.0 * (t - t[0]), -1.5 * (t - t[0]), window=11)
    np.testing.assert_allclose(vn, 2.0, rtol=1e-6)


def test_velocity_central_hand_values_and_smoothing() -> None:
    t = np.array([0.0, 1.0, 2.0, 3.0])
    n = np.array([0.0, 1.0, 4.0, 9.0])  # n = t²
    vn, _ = velocity_central(t, n, np.zeros(4))
    np.testing.assert_allclose(vn, [1.0, 2.0, 4.0, 5.0])  # one-sided, central, central, one-sided
    vn3, _ = velocity_central(t, n, np.zeros(4), window=3)
    np.testing.assert_allclose(vn3, [1.5, 7 / 3, 11 / 3, 4.5])  # window shrinks at the ends


def test_course_over_ground() -> None:
    np.testing.assert_allclose(
        course_over_ground([1.0, 0.0, -1.0, 0.0], [0.0, 1.0, 0.0, -1.0]), [0.0, math.pi / 2, -math.pi, -math.pi / 2]
    )


def test_leap_seconds() -> None:
    day = lambda y, m, d: float(calendar.timegm((y, m, d, 0, 0, 0)))  # noqa: E731
    assert gps_minus_utc(day(2020, 9, 15)) == 18
    assert gps_minus_utc(day(2016, 12, 31) + 86_399 + 17) == 17  # 23:59:59 UTC in GPST
    assert gps_minus_utc(day(2017, 1, 1) + 18) == 18  # 00:00:00 UTC in GPST
    assert gps_minus_utc(day(2010, 6, 1)) == 15
    assert gps_minus_utc(day(1980, 1, 6)) == 0
    assert gpst_to_utc(day(2020, 9, 15) + 36_018) == day(2020, 9, 15) + 36_000
    with pytest.raises(ValueError):
        gps_minus_utc(day(1979, 1, 1))


def test_gps_week_to_utc_hand_value() -> None:
    # GPS week 2123 began Sunday 2020-09-13; Tuesday 10:00:18 GPST = 2·86400 + 36018 s of week
    # = 10:00:00 UTC on 2020-09-15.
    assert gps_week_to_utc(2123, 208_818.0) == calendar.timegm((2020, 9, 15, 10, 0, 0))
