"""Flat-earth LLH↔NED (thesis eqs. 3.2–3.5) against hand values and the exact pymap3d conversion."""

from __future__ import annotations

import math
import re

import numpy as np
import pymap3d
import pytest

from seatwin.geo import (
    WGS84_A,
    WGS84_E2,
    GeodeticOrigin,
    flat_earth,
    llh_to_ned_exact,
    llh_to_ned_flat,
    meridian_radius,
    meridian_radius_printed,
    ned_to_llh_exact,
    ned_to_llh_flat,
    prime_vertical_radius,
)

ORIGIN = GeodeticOrigin(63.43, 10.39, 0.0)
BEARINGS = np.radians(np.arange(0.0, 360.0, 45.0))


def worst_flat_error(distance: float, meridian: str) -> float:
    """Worst horizontal error of the flat-earth NED over eight bearings at ``distance``."""
    n = distance * np.cos(BEARINGS)
    e = distance * np.sin(BEARINGS)
    lat, lon, h = pymap3d.ned2geodetic(n, e, np.zeros_like(n), ORIGIN.lat_deg, ORIGIN.lon_deg, ORIGIN.height_m)
    fn, fe, _ = llh_to_ned_flat(lat, lon, h, ORIGIN, meridian)  # type: ignore[arg-type]
    return float(np.max(np.hypot(fn - n, fe - e)))


# ---- eqs. 3.4 and 3.5, hand-computed -------------------------------------------------


def test_radii_at_equator_and_pole_hand_values() -> None:
    # Equator: R_N = a, R_M = a (1 − e²).  Pole: R_N = R_M = a / √(1 − e²); printed R_M = a.
    assert prime_vertical_radius(0.0) == pytest.approx(6_378_137.0, abs=1e-6)
    assert meridian_radius(0.0) == pytest.approx(6_335_439.327, abs=1e-3)
    assert meridian_radius_printed(0.0) == pytest.approx(6_335_439.327, abs=1e-3)
    assert prime_vertical_radius(math.pi / 2) == pytest.approx(6_399_593.626, abs=1e-3)
    assert meridian_radius(math.pi / 2) == pytest.approx(6_399_593.626, abs=1e-3)
    assert meridian_radius_printed(math.pi / 2) == pytest.approx(6_378_137.0, abs=1e-3)


def test_radii_at_trondheim_hand_values() -> None:
    lat = math.radians(63.43)
    s2 = math.sin(lat) ** 2  # 0.799 930 9 …
    w = 1.0 - WGS84_E2 * s2
    assert prime_vertical_radius(lat) == pytest.approx(WGS84_A / math.sqrt(w), rel=1e-15)
    assert prime_vertical_radius(lat) == pytest.approx(6_395_283.49, abs=0.01)
    assert meridian_radius(lat) == pytest.approx(6_386_671.92, abs=0.01)
    assert meridian_radius_printed(lat) == pytest.approx(6_369_548.52, abs=0.01)
    # The printed eq. 3.5 is √(1 − e² sin² x₀) ≈ 1 − 2.68 ‰ of the correct one.
    assert meridian_radius_printed(lat) / meridian_radius(lat) == pytest.approx(math.sqrt(w), rel=1e-14)
    assert 1 - meridian_radius_printed(lat) / meridian_radius(lat) == pytest.approx(2.681e-3, abs=1e-6)


def test_thesis_eccentricity_rounding_is_small() -> None:
    # The thesis quotes e = 0.0818; WGS-84 e = 0.081819 19…
    assert math.sqrt(WGS84_E2) == pytest.approx(0.0818, abs=2e-5)


# ---- eqs. 3.2 and 3.3, hand-computed -------------------------------------------------


def test_one_arcminute_at_equator() -> None:
    o = GeodeticOrigin(0.0, 0.0)
    n, e, d = llh_to_ned_flat(1 / 60, 1 / 60, 5.0, o)
    assert n == pytest.approx(6_335_439.327 * math.pi / 10_800, abs=1e-3)  # 1842.905 m
    assert e == pytest.approx(6_378_137.0 * math.pi / 10_800, abs=1e-3)  # 1855.325 m
    assert d == -5.0


def test_east_scale_uses_cos_lat0() -> None:
    # At 60° N a degree of longitude is half as long (cos 60° = 0.5) times R_N(60°)/a.
    o = GeodeticOrigin(60.0, 5.0)
    _, e, _ = llh_to_ned_flat(60.0, 6.0, 0.0, o)
    r_n = WGS84_A / math.sqrt(1 - WGS84_E2 * 0.75)
    assert e == pytest.approx(math.radians(1.0) * r_n * 0.5, rel=1e-12)


def test_longitude_difference_wraps_across_antimeridian() -> None:
    o = GeodeticOrigin(0.0, 179.999)
    _, e, _ = llh_to_ned_flat(0.0, -179.999, 0.0, o)
    assert e == pytest.approx(math.radians(0.002) * WGS84_A, rel=1e-9)


# ---- against the exact conversion ------------------------------------------------------

MEASURED = {  # distance → (correct, printed) worst horizontal error [m], see flat_earth.py
    100.0: (0.0017, 0.27),
    1000.0: (0.17, 2.7),
    5000.0: (4.4, 13.4),
}


@pytest.mark.parametrize("distance", sorted(MEASURED))
def test_flat_vs_exact(distance: float) -> None:
    correct, printed = MEASURED[distance]
    assert worst_flat_error(distance, "correct") == pytest.approx(correct, rel=0.05)
    assert worst_flat_error(distance, "printed") == pytest.approx(printed, rel=0.05)


def test_docstring_table_matches_measurement() -> None:
    doc = flat_earth.__doc__ or ""
    rows = re.findall(r"^(\d+) (m|km)\s+([\d.]+) m\s+([\d.]+) m\s*$", doc, flags=re.M)
    assert len(rows) == 3, "the table in flat_earth.py's docstring changed shape"
    for value, unit, correct, printed in rows:
        d = float(value) * (1000.0 if unit == "km" else 1.0)
        assert worst_flat_error(d, "correct") == pytest.approx(float(correct), rel=0.05), (d, "correct")
        assert worst_flat_error(d, "printed") == pytest.approx(float(printed), rel=0.05), (d, "printed")


def test_exact_matches_pymap3d_and_height_sign() -> None:
    n, e, d = llh_to_ned_exact(63.44, 10.40, 12.0, ORIGIN)
    rn, re_, rd = pymap3d.geodetic2ned(63.44, 10.40, 12.0, ORIGIN.lat_deg, ORIGIN.lon_deg, 0.0)
    assert (n, e, d) == pytest.approx((rn, re_, rd), abs=1e-9)
    assert llh_to_ned_flat(63.43, 10.39, 12.0, ORIGIN)[2] == -12.0


# ---- round trips ----------------------------------------------------------------------


@pytest.mark.parametrize("meridian", ["correct", "printed"])
def test_flat_round_trip(meridian: str) -> None:
    n = np.array([0.0, 123.4, -4000.0, 2500.0])
    e = np.array([0.0, -77.7, 3000.0, 4999.0])
    d = np.array([0.0, -3.0, 1.5, -40.0])
    lat, lon, h = ned_to_llh_flat(n, e, d, ORIGIN, meridian)  # type: ignore[arg-type]
    n2, e2, d2 = llh_to_ned_flat(lat, lon, h, ORIGIN, meridian)  # type: ignore[arg-type]
    np.testing.assert_allclose(np.c_[n2, e2, d2], np.c_[n, e, d], atol=1e-8)


def test_exact_round_trip() -> None:
    n = np.array([0.0, 123.4, -4000.0, 2500.0])
    e = np.array([0.0, -77.7, 3000.0, 4999.0])
    d = np.array([0.0, -3.0, 1.5, -40.0])
    lat, lon, h = ned_to_llh_exact(n, e, d, ORIGIN)
    np.testing.assert_allclose(np.vstack(llh_to_ned_exact(lat, lon, h, ORIGIN)), np.vstack([n, e, d]), atol=1e-6)


def test_unknown_meridian_rejected() -> None:
    with pytest.raises(ValueError, match="meridian"):
        llh_to_ned_flat(63.0, 10.0, 0.0, ORIGIN, "spherical")  # type: ignore[arg-type]


# ---- GeodeticOrigin checks its values ----------------------------------------------------


@pytest.mark.parametrize(
    ("values", "match"),
    [
        ((95.0, 10.0), "latitude"),
        ((63.0, -200.0), "longitude"),
        ((math.nan, 10.0), "finite"),
        ((63.0, 10.0, math.inf), "finite"),
    ],
)
def test_origin_rejects_bad_values_with_value_error(values: tuple[float, ...], match: str) -> None:
    with pytest.raises(ValueError, match=match) as exc:
        GeodeticOrigin(*values)
    assert type(exc.value) is ValueError  # geo is a leaf: no seatwin error types
