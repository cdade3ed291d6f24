"""End to end: a known turning vessel → noisy bow/stern logs in every format →
``seatwin groundtruth`` → the trajectory is recovered; flags, report, plots and errors."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from gt_synth import (
    BASELINE,
    DURATION,
    ORIGIN,
    T0,
    WRITERS,
    antenna_llh,
    sample_times,
    turning_vessel,
    write_gpx,
    write_nmea,
    write_pos,
)

from seatwin.cli.main import run
from seatwin.scenario.gemini_csv import read_gemini_csv

SIGMA = 0.02  # antenna noise per axis [m] (RTK-grade)
RATES = {"gpx": 1.0, "nmea": 5.0, "rtklib": 5.0, "csv": 2.0}  # fix rates as in the thesis receivers
# Recovery tolerances (measured: position RMS 0.018 m / max 0.051 m, heading RMS 0.47° / max 1.9°).
POS_RMS, POS_MAX = 0.03, 0.12
HEAD_RMS, HEAD_MAX = 0.8, 3.0
ORIGIN_ARG = f"{ORIGIN.lat_deg},{ORIGIN.lon_deg}"


def errors(csv: Path, number: int, truth) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(times, position error [m], heading error [deg]) of vessel ``number`` in ``csv``."""
    tr = read_gemini_csv(csv)[number]
    n, e, psi = truth.at(tr.time)
    dpsi = np.degrees((tr.heading - psi + np.pi) % (2 * np.pi) - np.pi)
    return tr.time, np.hypot(tr.north - n, tr.east - e), dpsi


def antenna_files(tmp_path: Path, fmt: str, truth, seed: int = 1, **kw) -> list[Path]:
    writer, ext = WRITERS[fmt]
    rate = RATES[fmt]
    files = []
    for role, along, offset in (("bow", BASELINE / 2, 0.0), ("stern", -BASELINE / 2, 0.1 if rate > 1 else 0.0)):
        t = sample_times(T0, DURATION, rate, offset)
        lat, lon, h = antenna_llh(truth, t, along, SIGMA, seed, f"{fmt}/{role}")
        files.append(writer(tmp_path / f"{fmt}_{role}{ext}", t, lat, lon, h, **kw))
    return files


@pytest.fixture(scope="module")
def truth():
    return turning_vessel()


@pytest.mark.parametrize("fmt", sorted(WRITERS))
def test_recovers_trajectory_from_each_format(tmp_path: Path, truth, fmt: str) -> None:
    bow, stern = antenna_files(tmp_path, fmt, truth)
    out = tmp_path / "scenario.csv"
    assert run(["groundtruth", "--origin", ORIGIN_ARG, "--vessel", f"Finn={bow},{stern}", "--out", str(out)]) == 0
    t, dp, dpsi = errors(out, 1, truth)
    assert np.allclose(np.round((t - T0) * 10.0), (t - T0) * 10.0, atol=1e-4), "10 Hz grid of multiples of 0.1 s"
    assert np.median(np.diff(t)) == pytest.approx(0.1)
    assert t[0] - T0 <= 0.2 and T0 + DURATION - t[-1] <= 0.5
    assert np.sqrt(np.mean(dp**2)) < POS_RMS and dp.max() < POS_MAX
    assert np.sqrt(np.mean(dpsi**2)) < HEAD_RMS and np.abs(dpsi).max() < HEAD_MAX


def test_mixed_formats_flags_single_antenna_report_plots(tmp_path: Path, truth) -> None:
    # Havfruen: bow RTKLIB (GPS week/seconds), stern NMEA; a 3 s burst where the bow is 1 m off.
    ferry = turning_vessel(speed=2.0)
    t_bow = sample_times(T0, DURATION, 5.0)
    lat, lon, h = antenna_llh(truth, t_bow, BASELINE / 2, SIGMA, 2, "bow")
    burst = (t_bow >= T0 + 30.0) & (t_bow < T0 + 33.0)
    lat_b, lon_b, _ = antenna_llh(truth, t_bow, BASELINE / 2 + 1.0, SIGMA, 2, "bow")
    lat, lon = np.where(burst, lat_b, lat), np.where(burst, lon_b, lon)
    bow = write_pos(tmp_path / "hav_bow.pos", t_bow, lat, lon, h, q=np.where(burst, 2, 1), week_tow=True)
    t_st = sample_times(T0, DURATION, 5.0, 0.1)
    stern = write_nmea(tmp_path / "hav_stern.nmea", t_st, *antenna_llh(truth, t_st, -BASELINE / 2, SIGMA, 2, "stern"))
    # milliAmpere: one antenna (Hemisphere GGA, fixed with some float), 10 Hz.
    t_f = sample_times(T0 - 5.0, DURATION + 10.0, 10.0)
    q = np.where((t_f > T0 + 10) & (t_f < T0 + 20), 5, 4)
    gnss = write_nmea(tmp_path / "ma.log", t_f, *antenna_llh(ferry, t_f, 0.0, SIGMA, 3, "ma"), quality=q)

    out, qual, plots = tmp_path / "out" / "s.csv", tmp_path / "out" / "q.json", tmp_path / "plots"
    args = ["groundtruth", "--origin", ORIGIN_ARG, "--vessel", f"Havfruen={bow},{stern},{BASELINE}",
            "--vessel", f"milliAmpere={gnss}", "--out", str(out), "--quality", str(qual), "--plots", str(plots)]  # fmt: skip
    assert run(args) == 0

    t, dp, dpsi = errors(out, 1, truth)
    ok = (t < T0 + 29.5) | (t > T0 + 33.5)
    assert dp[ok].max() < POS_MAX and np.abs(dpsi[ok]).max() < HEAD_MAX
    assert dp[~ok].max() > 0.4, "the burst moves the midpoint: flagged, not removed"
    t2, dp2, dpsi2 = errors(out, 2, ferry)
    assert np.array_equal(t, t2)
    assert np.sqrt(np.mean(dp2**2)) < POS_RMS
    steady = np.abs((t2 - T0) - 35.0) > 16.5  # away from the turn's start/end where COG lags a little
    assert np.sqrt(np.mean(dpsi2**2)) < 1.5 and np.abs(dpsi2[steady]).max() < 2.0

    report = json.loads(qual.read_text())
    hav, ma = report["vessels"]
    assert (hav["number"], hav["name"], ma["number"], ma["name"]) == (1, "Havfruen", 2, "milliAmpere")
    assert hav["heading_source"] == "antennas (eq. 3.6)" and ma["heading_source"] == "course over ground"
    assert hav["baseline_m"] == BASELINE and hav["baseline_source"] == "given"
    assert hav["samples"] == len(t) == report["samples"]
    assert hav["flagged_by_reason"]["eps_gnss"] == pytest.approx(30, abs=3)  # 3 s at 10 Hz
    assert hav["flagged_fraction"] == pytest.approx(30 / len(t), abs=0.005)
    assert 0.9 < hav["eps_gnss_m"]["max"] < 1.1 and hav["eps_gnss_m"]["median"] < 0.05
    assert hav["antennas"][0]["fix_quality_counts"] == {"fix": int((~burst).sum()), "float": int(burst.sum())}
    assert hav["antennas"][0]["format"] == "rtklib-pos (GPST)"
    assert ma["eps_gnss_m"] is None and ma["flagged_by_reason"]["low_speed_cog"] == 0
    assert ma["antennas"][0]["fix_quality_counts"] == {"rtk_fixed": int((q == 4).sum()), "rtk_float": int((q == 5).sum())}
    names = sorted(p.name for p in plots.iterdir())
    assert names == ["V1_Havfruen_eps_gnss.png", "V1_Havfruen_fix_quality.png", "V1_Havfruen_relative_positions.png",
                     "V2_milliAmpere_fix_quality.png"]  # fmt: skip
    assert all((plots / n).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for n in names)
    assert not [p for p in tmp_path.rglob("*") if ".tmp" in p.name or p.name.endswith(".part")]


def test_eps_threshold_rate_and_printed_meridian(tmp_path: Path, truth) -> None:
    bow, stern = antenna_files(tmp_path, "csv", truth)
    base = ["groundtruth", "--origin", ORIGIN_ARG, "--vessel", f"Finn={bow},{stern}"]
    q = tmp_path / "q.json"
    assert run([*base, "--out", str(tmp_path / "a.csv"), "--quality", str(q), "--eps-threshold", "0.01"]) == 0
    frac = json.loads(q.read_text())["vessels"][0]["flagged_fraction"]
    assert 0.3 < frac < 0.9  # ε of 2 cm noise: many samples over 1 cm
    assert run([*base, "--out", str(tmp_path / "b.csv"), "--rate", "4", "--meridian", "printed"]) == 0
    a, b = read_gemini_csv(tmp_path / "a.csv")[1], read_gemini_csv(tmp_path / "b.csv")[1]
    assert np.allclose(np.diff(b.time), 0.25)
    sa = a.state_at(b.time)
    # The printed eq. 3.5 shrinks north distances by √(1 − e² sin² x₀) ≈ 1 − 2.68 ‰.
    np.testing.assert_allclose(b.north, sa.north * (1 - 2.681e-3), atol=2e-3)
    np.testing.assert_allclose(b.east, sa.east, atol=1e-6)


def test_gaps_are_flagged(tmp_path: Path, truth) -> None:
    t = sample_times(T0, DURATION, 1.0)
    keep = (t < T0 + 20) | (t > T0 + 30)  # no stern fixes from 19 s to 31 s
    bow = write_gpx(tmp_path / "b.gpx", t, *antenna_llh(truth, t, BASELINE / 2, SIGMA, 5, "b"))
    stern = write_gpx(tmp_path / "s.gpx", t[keep], *antenna_llh(truth, t[keep], -BASELINE / 2, SIGMA, 5, "s"))
    q = tmp_path / "q.json"
    assert run(["groundtruth", "--origin", ORIGIN_ARG, "--vessel", f"Finn={bow},{stern}", "--out", str(tmp_path / "o.csv"),
                "--quality", str(q), "--max-gap", "5"]) == 0  # fmt: skip
    rep = json.loads(q.read_text())["vessels"][0]
    assert rep["flagged_by_reason"]["gap"] == 119  # strictly inside (19 s, 31 s) at 10 Hz
    assert rep["antennas"][1]["samples_across_gaps"] == 119


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert err.startswith("seatwin: error: ") and "\n" not in err and "Traceback" not in err
    return err


def test_errors_leave_no_output(tmp_path: Path, truth, capsys) -> None:
    bow, stern = antenna_files(tmp_path, "nmea", truth)
    late = tmp_path / "late.csv"
    late.write_text(f"time,lat,lon\n{T0 + 500},63.43,10.39\n{T0 + 600},63.43,10.39\n")
    out, q, plots = tmp_path / "o" / "s.csv", tmp_path / "o" / "q.json", tmp_path / "o" / "plots"
    tail = ["--out", str(out), "--quality", str(q), "--plots", str(plots)]
    base = ["groundtruth", "--origin", ORIGIN_ARG]
    cases = [
        ([*base, "--vessel", f"Finn={bow},{stern}", "--vessel", f"Ferry={late}", *tail], "no common time interval"),
        ([*base, "--vessel", f"Finn={bow}", "--vessel", f"Finn={stern}", *tail], "unique"),
        ([*base, "--vessel", f"Finn:{bow}", *tail], "NAME=BOW"),
        ([*base, "--vessel", f"Finn={bow},{tmp_path / 'nope.gpx'}", *tail], "no such file"),
        ([*base, "--vessel", f"Finn={bow},{stern}", "--rate", "0", *tail], "--rate"),
        ([*base, "--vessel", f"Finn={bow},{stern}", "--meridian", "round", *tail], "--meridian"),
        ([*base, "--vessel", f"Finn={bow},{stern}", "--eps-threshold", "-1", *tail], "--eps-threshold"),
        (["groundtruth", "--origin", "63.4", "--vessel", f"Finn={bow},{stern}", *tail], "--origin"),
    ]
    for args, match in cases:
        assert run(args) == 2, match
        assert match in _one_line_error(capsys)
        assert not (tmp_path / "o").exists()
    # An existing output survives a failed run untouched.
    out.parent.mkdir()
    out.write_text("previous\n")
    assert run(cases[0][0]) == 2
    assert "exists already" in _one_line_error(capsys)  # refused before any work, without --overwrite
    assert run([*cases[0][0], "--overwrite"]) == 2
    assert "no common time interval" in _one_line_error(capsys)
    assert out.read_text() == "previous\n" and sorted(p.name for p in out.parent.iterdir()) == ["s.csv"]
    # A malformed antenna file: error names file and line.
    bad = tmp_path / "bad.nmea"
    bad.write_text(stern.read_text().replace("GPGGA,100001.10", "GPGGA,100001.1X", 1))
    assert run([*base, "--vessel", f"Finn={bow},{bad}", *tail, "--overwrite"]) == 2
    err = _one_line_error(capsys)
    assert str(bad) in err and "line " in err
