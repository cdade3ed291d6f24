"""Heading helpers and thesis eq. 3.6."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.geo import deg_to_rad_heading, heading_from_antennas, rad_to_deg_heading, unwrap, wrap_to_pi


def test_wrap_to_pi_range_and_ends() -> None:
    assert wrap_to_pi(math.pi) == pytest.approx(-math.pi)
    assert wrap_to_pi(-math.pi) == pytest.approx(-math.pi)
    assert wrap_to_pi(1.5 * math.pi) == pytest.approx(-0.5 * math.pi)
    assert wrap_to_pi(-7.0) == pytest.approx(-7.0 + 2 * math.pi)
    a = wrap_to_pi(np.linspace(-20, 20, 1001))
    assert isinstance(a, np.ndarray) and a.min() >= -math.pi and a.max() < math.pi
    assert isinstance(wrap_to_pi(0.3), float)


def test_degrees_at_file_boundaries() -> None:
    assert deg_to_rad_heading(270.0) == pytest.approx(-math.pi / 2)
    assert deg_to_rad_heading(90.0) == pytest.approx(math.pi / 2)
    assert rad_to_deg_heading(math.pi) == pytest.approx(-180.0)
    assert -180.0 <= rad_to_deg_heading(math.nextafter(math.pi, 0.0)) < 180.0
    d = np.linspace(-180.0, 179.9, 50)
    np.testing.assert_allclose(rad_to_deg_heading(deg_to_rad_heading(d)), d, atol=1e-9)


def test_unwrap_removes_jumps() -> None:
    h = np.array([3.0, -3.1, -2.9, 3.0])
    u = unwrap(h)
    assert np.all(np.abs(np.diff(u)) < math.pi)
    np.testing.assert_allclose(wrap_to_pi(u), wrap_to_pi(h))


@pytest.mark.parametrize(
    ("bow", "stern", "expected"),
    [
        ((1.0, 0.0), (0.0, 0.0), 0.0),  # bow north of stern
        ((0.0, 1.0), (0.0, 0.0), math.pi / 2),  # east
        ((1.0, 1.0), (0.0, 0.0), math.pi / 4),
        ((0.0, -2.0), (0.0, 0.0), -math.pi / 2),  # west
        ((-1.0, 0.0), (0.0, 0.0), -math.pi),  # south: −π, in [−π, π)
        ((10.0, 20.0), (10.0 - 2.93 * math.cos(2.0), 20.0 - 2.93 * math.sin(2.0)), 2.0),
    ],
)
def test_eq_3_6_hand_values(bow: tuple[float, float], stern: tuple[float, float], expected: float) -> None:
    assert heading_from_antennas(bow[0], bow[1], stern[0], stern[1]) == pytest.approx(expected, abs=1e-12)


def test_eq_3_6_vectorised() -> None:
    psi = np.linspace(-math.pi, math.pi, 73, endpoint=False)
    h = heading_from_antennas(np.cos(psi), np.sin(psi), np.zeros_like(psi), np.zeros_like(psi))
    np.testing.assert_allclose(wrap_to_pi(np.asarray(h) - psi), 0.0, atol=1e-12)
