"""Common clock, resampling, vessel specs, parameter errors and the per-vessel ground truth."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seatwin.errors import InputError, ParameterError
from seatwin.geo import GeodeticOrigin, ned_to_llh_flat
from seatwin.groundtruth import (
    FLAG_EPS,
    FLAG_GAP,
    FLAG_LOW_SPEED,
    AntennaLog,
    VesselSpec,
    build_vessel,
    common_clock,
    compute_ground_truth,
    resample_log,
)
from seatwin.groundtruth.vessel import HEADING_ANTENNAS, HEADING_COG

T0 = 1_600_164_000.0
ORIGIN = GeodeticOrigin(63.4346, 10.3977)


def log_of(t, lat=None, lon=None, name="a.csv", quality=None) -> AntennaLog:
    t = np.asarray(t, float)
    lat = np.full(len(t), 63.43) if lat is None else lat
    lon = np.full(len(t), 10.39) if lon is None else lon
    return AntennaLog(
        t, lat, lon, None, name, "test", quality=quality, quality_scheme="nmea-gga" if quality is not None else None
    )


# ---------------------------------------------------------------- common clock


def test_clock_is_aligned_to_multiples_of_the_period_over_the_overlap() -> None:
    a = log_of(T0 + np.array([0.03, 5.0, 9.97]))
    b = log_of(T0 + np.array([-3.0, 4.0, 12.0]))
    t = common_clock([a, b], 10.0)
    assert t[0] == pytest.approx(T0 + 0.1) and t[-1] == pytest.approx(T0 + 9.9)
    assert len(t) == 99
    np.testing.assert_array_equal(np.round(t * 10.0), t * 10.0)
    t4 = common_clock([a, b], 4.0)
    assert t4[0] == T0 + 0.25 and t4[-1] == T0 + 9.75
    assert common_clock([log_of(T0 + np.array([0.0, 1.0]))], 10.0)[[0, -1]].tolist() == [T0, T0 + 1.0]


def test_no_common_interval_names_the_files() -> None:
    a = log_of(T0 + np.array([0.0, 10.0]), name="bow.gpx")
    b = log_of(T0 + np.array([20.0, 30.0]), name="stern.gpx")
    with pytest.raises(InputError, match="no common time interval") as exc:
        common_clock([a, b], 10.0)
    assert "bow.gpx" in str(exc.value) and "stern.gpx" in str(exc.value)
    c = log_of(T0 + np.array([9.95, 10.05, 30.0]), name="short.nmea")
    with pytest.raises(InputError, match="fewer than 2 samples"):
        common_clock([a, c], 10.0)


@pytest.mark.parametrize("rate", [0.0, -1.0, math.nan, math.inf])
def test_bad_rate(rate: float) -> None:
    with pytest.raises(ParameterError, match="rate_hz") as exc:
        common_clock([log_of([T0, T0 + 1])], rate)
    assert exc.value.param == "rate_hz"


# ---------------------------------------------------------------- resampling


def test_resample_linear_nearest_quality_and_gaps() -> None:
    t = T0 + np.array([0.0, 1.0, 2.0, 10.0])
    log = log_of(t, lat=np.array([63.0, 63.1, 63.2, 64.0]), lon=np.array([179.9, -179.9, -179.7, -179.7]),
                 quality=np.array([4, 5, 4, 1]))  # fmt: skip
    grid = T0 + np.array([0.0, 0.4, 0.5, 1.5, 2.0, 6.0, 10.0])
    r = resample_log(log, grid, max_gap=5.0)
    np.testing.assert_allclose(r.lat, [63.0, 63.04, 63.05, 63.15, 63.2, 63.6, 64.0])
    np.testing.assert_allclose(r.lon[:3], [179.9, 179.98, -180.0 + 0.0], atol=1e-9)  # across ±180°
    assert r.quality.tolist() == [4, 4, 4, 5, 4, 4, 1]  # nearest fix; ties go to the earlier one
    assert r.gap.tolist() == [False, False, False, False, False, True, False]
    assert r.height is None


# ---------------------------------------------------------------- vessel spec


def test_vessel_spec_checks_its_values() -> None:
    with pytest.raises(ParameterError, match="one or two antenna files") as exc:
        VesselSpec("Finn", (Path("a"), Path("b"), Path("c")))
    assert exc.value.param == "vessels"
    with pytest.raises(ParameterError, match="positive"):
        VesselSpec("Finn", (Path("a"), Path("b")), baseline_m=-1.0)
    # The command-line syntax NAME=BOW,STERN[,BASELINE_M] is parsed in the CLI (tests/cli/test_parsing.py).
    assert not hasattr(VesselSpec, "parse")


BAD_SETTINGS = [
    ({"vessels": []}, "vessels"),
    ({"vessels": [VesselSpec("Finn", (Path("a.gpx"),)), VesselSpec("Finn", (Path("b.gpx"),))]}, "vessels"),
    ({"eps_threshold_m": 0.0}, "eps_threshold_m"),
    ({"max_gap_s": math.nan}, "max_gap_s"),
    ({"smooth_s": -1.0}, "smooth_s"),
    ({"min_cog_speed": -0.1}, "min_cog_speed"),
    ({"meridian": "round"}, "meridian"),
]


@pytest.mark.parametrize(("kwargs", "param"), BAD_SETTINGS)
def test_compute_ground_truth_errors_name_the_parameter(kwargs: dict, param: str) -> None:
    args = {"vessels": [VesselSpec("Finn", (Path("a.gpx"), Path("b.gpx")))], "origin": ORIGIN, **kwargs}
    with pytest.raises(ParameterError) as exc:
        compute_ground_truth(**args)
    assert exc.value.param == param and str(exc.value).startswith(f"{param}: ")


def test_every_parameter_error_maps_to_a_groundtruth_option() -> None:
    import typer

    from seatwin.cli.flags import flag_for
    from seatwin.cli.main import app

    options = {o for p in typer.main.get_command(app).commands["groundtruth"].params for o in p.opts}
    for param in [p for _, p in BAD_SETTINGS] + ["rate_hz", "plots_dir"]:
        assert flag_for(param) in options, param


# ---------------------------------------------------------------- vessel ground truth


def _antenna(t, north, east, name) -> AntennaLog:
    lat, lon, _ = ned_to_llh_flat(north, east, np.zeros_like(north), ORIGIN)
    return AntennaLog(t, lat, lon, None, name, "test")


def test_two_antennas_heading_position_eps_flags() -> None:
    t = T0 + np.arange(0.0, 10.01, 0.1)
    psi = np.radians(100.0) + 0.05 * (t - T0)
    n0, e0 = 10.0 + 2.0 * (t - T0), -5.0 + 1.0 * (t - T0)
    half = np.full(len(t), 2.01 / 2)
    half[50:55] += 0.8  # bow antenna 0.8 m too far forward for 5 samples: ε = 0.8
    bow = _antenna(t, n0 + half * np.cos(psi), e0 + half * np.sin(psi), "bow")
    stern = _antenna(t, n0 - 2.01 / 2 * np.cos(psi), e0 - 2.01 / 2 * np.sin(psi), "stern")
    ants = [resample_log(x, t) for x in (bow, stern)]
    v = build_vessel(VesselSpec("HAVFRUEN", (None, None)), ants, ORIGIN)  # type: ignore[arg-type]
    assert v.heading_source == HEADING_ANTENNAS
    assert v.baseline_m == 2.01 and v.baseline_source == "thesis hand measurement"
    np.testing.assert_allclose(np.degrees(v.heading), np.degrees(np.arctan2(np.sin(psi), np.cos(psi))), atol=1e-6)
    ok = np.ones(len(t), bool)
    ok[50:55] = False
    np.testing.assert_allclose(v.north[ok], n0[ok], atol=1e-6)
    np.testing.assert_allclose(v.eps_gnss[ok], 0.0, atol=1e-6)
    np.testing.assert_allclose(v.eps_gnss[~ok], 0.8, atol=1e-6)
    assert np.flatnonzero(v.flags & FLAG_EPS).tolist() == [50, 51, 52, 53, 54]
    assert len(v.time) == len(t), "flagged samples are kept"
    np.testing.assert_allclose(v.v_north[np.r_[5:40, 65 : len(t) - 5]], 2.0, atol=1e-6)  # away from the burst
    np.testing.assert_allclose(np.hypot(v.rel_north, v.rel_east)[ok], 2.01, atol=1e-6)
    given = build_vessel(VesselSpec("boat", (None, None), 2.6), ants, ORIGIN)  # type: ignore[arg-type]
    assert given.baseline_source == "given" and np.flatnonzero(given.flags & FLAG_EPS).size == len(t) - 5
    median = build_vessel(VesselSpec("boat", (None, None)), ants, ORIGIN)  # type: ignore[arg-type]
    assert median.baseline_m == pytest.approx(2.01) and "median" in median.baseline_source
    strict = build_vessel(VesselSpec("finn", (None, None)), ants, ORIGIN, eps_threshold_m=1.0)  # type: ignore[arg-type]
    assert strict.baseline_m == 2.93 and not (strict.flags & FLAG_EPS).any()  # 0.92 m everywhere


def test_one_antenna_course_over_ground_and_low_speed() -> None:
    t = T0 + np.arange(0.0, 20.01, 0.1)
    tau = t - T0
    speed = np.where((tau > 8) & (tau < 12), 0.0, 2.0)  # stops for 4 s
    north = np.cumsum(speed * 0.1) * np.cos(np.radians(-60.0))
    east = np.cumsum(speed * 0.1) * np.sin(np.radians(-60.0))
    ant = resample_log(_antenna(t, north, east, "gnss.nmea"), t)
    v = build_vessel(VesselSpec("ferry", (None,)), [ant], ORIGIN, smooth_s=0.0)  # type: ignore[arg-type]
    assert v.heading_source == HEADING_COG and v.eps_gnss is None
    np.testing.assert_allclose(np.degrees(v.heading), -60.0, atol=1e-6)  # filled across the stop
    low = np.flatnonzero(v.flags & FLAG_LOW_SPEED)
    assert low.size > 30 and tau[low].min() >= 8.0 and tau[low].max() <= 12.1
    assert not (v.flags & FLAG_GAP).any()
    with pytest.raises(InputError, match="never moves"):
        still = resample_log(_antenna(t, np.zeros_like(t), np.zeros_like(t), "moored.nmea"), t)
        build_vessel(VesselSpec("moored", (Path("moored.nmea"),)), [still], ORIGIN)
