"""The vectorised NED → WGS-84 conversion gives pymap3d's bits (and so sub-millimetre agreement)."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.geo import GeodeticOrigin, ned_to_llh_exact
from seatwin.geo.geodetic import ned_to_llh_wgs84

ORIGINS = [
    GeodeticOrigin(63.4336, 10.3926, 0.0),
    GeodeticOrigin(-33.9, 151.2, 12.5),
    GeodeticOrigin(0.0, 0.0, 0.0),
    GeodeticOrigin(89.99, -170.0, 3.0),
]


@pytest.mark.parametrize("origin", ORIGINS)
@pytest.mark.parametrize("n", [1, 2, 3, 7, 16, 33, 1000])
def test_same_bits_as_pymap3d(origin: GeodeticOrigin, n: int) -> None:
    rng = np.random.default_rng(n)
    north, east = rng.normal(0.0, 3000.0, (2, n))
    down = rng.normal(0.0, 20.0, n)
    for ref, got in zip(ned_to_llh_exact(north, east, down, origin), ned_to_llh_wgs84(north, east, down, origin), strict=True):
        assert got.shape == ref.shape == (n,)
        assert np.array_equal(got, ref)


def test_scalars_and_a_hand_value() -> None:
    o = ORIGINS[0]
    lat, lon, h = ned_to_llh_wgs84(0.0, 0.0, 0.0, o)
    assert (float(lat), float(lon)) == pytest.approx((63.4336, 10.3926), abs=1e-12) and abs(float(h)) < 1e-6
    # 1 km north: a meridian arc at 63.43° N, R_M = a(1 − e²)/(1 − e² sin² φ)^1.5 ≈ 6 386.7 km → 0.0089711°.
    lat, lon, _ = ned_to_llh_wgs84(1000.0, 0.0, 0.0, o)
    assert float(lat) - 63.4336 == pytest.approx(0.0089711, abs=2e-7) and float(lon) == pytest.approx(10.3926, abs=1e-9)


def test_degenerate_points_go_to_pymap3d() -> None:
    # The Earth's centre (6378 km down from a point on the equator): pymap3d's patched branch.
    o = ORIGINS[2]
    got = ned_to_llh_wgs84(np.array([0.0]), np.array([0.0]), np.array([6378137.0]), o)
    ref = ned_to_llh_exact(np.array([0.0]), np.array([0.0]), np.array([6378137.0]), o)
    for a, b in zip(got, ref, strict=True):
        assert np.array_equal(a, b, equal_nan=True)
