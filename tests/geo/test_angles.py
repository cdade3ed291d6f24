"""Angle wrapping, unwrapping and circular means (seatwin.geo.angles) against hand values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.geo import TWO_PI, circular_mean, unwrap, wrap_to_2pi, wrap_to_180, wrap_to_pi


def test_wrap_to_pi_hand_values() -> None:
    np.testing.assert_allclose(
        wrap_to_pi([0.0, 3.0, 4.0, -4.0, 7.0, -math.pi]), [0.0, 3.0, 4.0 - TWO_PI, TWO_PI - 4.0, 7.0 - TWO_PI, -math.pi]
    )
    assert wrap_to_pi(math.pi) == -math.pi  # the interval is [−π, π)
    assert isinstance(wrap_to_pi(1), float)  # ints are angles too


def test_wrap_to_2pi_hand_values() -> None:
    np.testing.assert_allclose(wrap_to_2pi([0.0, -1.0, 7.0, TWO_PI]), [0.0, TWO_PI - 1.0, 7.0 - TWO_PI, 0.0])
    assert isinstance(wrap_to_2pi(-0.5), float)


def test_wrap_to_180_hand_values() -> None:
    deg = [0.0, 180.0, -180.0, 190.0, -190.0, 359.5, 720.0]
    np.testing.assert_allclose(wrap_to_180(deg), [0.0, -180.0, -180.0, -170.0, 170.0, -0.5, 0.0])


def test_wrapping_keeps_float32_and_matches_the_inline_form_bit_for_bit() -> None:
    a32 = np.linspace(-20, 20, 101, dtype=np.float32)
    assert wrap_to_pi(a32).dtype == np.float32 and wrap_to_2pi(a32).dtype == np.float32
    a = np.random.default_rng(3).uniform(-50, 50, 1000)
    assert np.array_equal(wrap_to_pi(a), (a + np.pi) % (2 * np.pi) - np.pi)  # the forms it replaced
    assert np.array_equal(wrap_to_2pi(a), a % (2 * np.pi))


def test_circular_mean_hand_values() -> None:
    assert circular_mean([math.radians(350), math.radians(10)]) == pytest.approx(0.0, abs=1e-15)
    assert circular_mean([3.0, -3.0]) == pytest.approx(math.pi)
    # weights: atan2(Σ w sin, Σ w cos) with w = 3, 1 at 0 and π/2 → atan2(1, 3)
    assert circular_mean([0.0, math.pi / 2], weights=[3.0, 1.0]) == pytest.approx(math.atan2(1.0, 3.0))
    expect = [0.2, math.atan2(math.sin(3.0) + math.sin(-3.1), math.cos(3.0) + math.cos(-3.1))]
    np.testing.assert_allclose(circular_mean([[0.1, 0.3], [3.0, -3.1]], axis=1), expect)


def test_unwrap_removes_jumps() -> None:
    np.testing.assert_allclose(unwrap([3.0, -3.0, -2.9]), [3.0, TWO_PI - 3.0, TWO_PI - 2.9])
