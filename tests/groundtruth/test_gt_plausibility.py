"""What `seatwin groundtruth` writes, `seatwin scenario info` reads: teleporting fixes, heading spikes,
numbers `float()` takes but the formats do not (a no-break space, ``1_0``, ``nan``) are errors naming the line."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from gt_synth import BASELINE, ORIGIN, T0, antenna_llh, sample_times, turning_vessel
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.cli.main import run
from seatwin.errors import InputError, ParameterError
from seatwin.groundtruth import VesselSpec, compute_ground_truth, read_antenna_log, write_outputs
from seatwin.groundtruth.examples import EXAMPLES_DIR
from seatwin.groundtruth.log_writers import write_csv, write_gpx, write_pos
from seatwin.groundtruth.read_nmea import nmea_checksum
from seatwin.scenario import load_scenario

ORIGIN_ARG = f"{ORIGIN.lat_deg},{ORIGIN.lon_deg}"


def _edit_pos(src: Path, dst: Path, line: int, column: int, value: str) -> Path:
    """``src`` with field ``column`` (0-based, blank-separated) of ``line`` (1-based) replaced by ``value``."""
    lines = src.read_text().split("\n")
    fields = lines[line - 1].split()
    fields[column] = value
    lines[line - 1] = "   ".join(fields)
    dst.write_text("\n".join(lines))
    return dst


def _havfruen(tmp_path: Path, bow: Path) -> list[VesselSpec]:
    return [VesselSpec("Havfruen", (bow, EXAMPLES_DIR / "havfruen_stern.pos"))]


@pytest.mark.parametrize(
    ("column", "value", "match"),
    [
        (3, "-0", r"line 51: fix at latitude 63\.43\d+, longitude -0\.0 is 5\.1\d+e\+05 m from the fix at line 50, 0\.2 s"),
        (2, "12", r"line 51: fix at latitude 12\.0, .* faster than max_speed 30 m/s\): a teleport"),
    ],
)
def test_teleporting_fix_is_an_error_naming_file_and_line(tmp_path: Path, column: int, value: str, match: str) -> None:
    bow = _edit_pos(EXAMPLES_DIR / "havfruen_bow.pos", tmp_path / "bow.pos", 51, column, value)
    with pytest.raises(InputError, match=match) as err:
        compute_ground_truth(_havfruen(tmp_path, bow), ORIGIN)
    assert err.value.source == str(bow) and "2 steps between fixes in the file are that fast" in err.value.detail
    # A bound loose enough lets it through: then the output is what the reader checks with that bound.
    result = compute_ground_truth(_havfruen(tmp_path, bow), ORIGIN, max_speed=np.inf)
    write_outputs(result, tmp_path / "loose.csv")
    with pytest.raises(InputError, match="a teleport"):
        load_scenario(tmp_path / "loose.csv")


def test_cli_refuses_the_teleport_and_writes_nothing(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bow = _edit_pos(EXAMPLES_DIR / "havfruen_bow.pos", tmp_path / "bow.pos", 51, 3, "-0")
    out = tmp_path / "gt.csv"
    code = run(
        [
            "groundtruth",
            "--origin",
            ORIGIN_ARG,
            "--vessel",
            f"Havfruen={bow},{EXAMPLES_DIR / 'havfruen_stern.pos'}",
            "--out",
            str(out),
        ]
    )
    err = capsys.readouterr().err.strip()
    assert code == 2 and "\n" not in err and err.startswith(f"seatwin: error: {bow}: line 51: fix at latitude")
    assert not out.exists()
    for bad in ("0", "-5", "nan"):
        assert (
            run(
                [
                    "groundtruth",
                    "--origin",
                    ORIGIN_ARG,
                    "--vessel",
                    f"Finn={EXAMPLES_DIR / 'finn.csv'}",
                    "--out",
                    str(out),
                    "--max-speed",
                    bad,
                ]
            )
            == 2
        )
        assert "--max-speed" in capsys.readouterr().err
    with pytest.raises(ParameterError, match="max_turn_rate"):
        compute_ground_truth([VesselSpec("Finn", (EXAMPLES_DIR / "finn.csv",))], ORIGIN, max_turn_rate=0.0)


def test_no_break_space_after_a_number_is_refused(tmp_path: Path) -> None:
    bow = _edit_pos(EXAMPLES_DIR / "havfruen_bow.pos", tmp_path / "bow.pos", 61, 2, "12\u00a0")
    with pytest.raises(InputError, match=r"line 61: expected a number for latitude, got '12\\xa0'") as err:
        read_antenna_log(bow)
    assert err.value.source == str(bow)


def test_the_examples_pass_every_check() -> None:
    files = {p.name: p for p in EXAMPLES_DIR.iterdir()}
    vessels = [
        VesselSpec("Havfruen", (files["havfruen_bow.pos"], files["havfruen_stern.pos"])),
        VesselSpec("milliAmpere", (files["milliampere.nmea"],)),
        VesselSpec("Finn", (files["finn.gpx"],)),
    ]
    assert len(compute_ground_truth(vessels, ORIGIN).vessels) == 3
    assert len(compute_ground_truth([VesselSpec("Finn", (files["finn.csv"],))], ORIGIN).vessels) == 1


def test_heading_spike_from_a_bad_bow_fix_names_the_fixes(tmp_path: Path) -> None:
    """The bow antenna behind the stern for one fix: 3.5 m in 0.2 s is no teleport, but the heading flips and back."""
    truth = turning_vessel(duration=20.0)
    t = sample_times(T0, 20.0, 5.0)
    bow = antenna_llh(truth, t, BASELINE / 2, 0.0, 1, "bow")
    stern = antenna_llh(truth, t, -BASELINE / 2, 0.0, 1, "stern")
    bad = antenna_llh(truth, t[[40]], -BASELINE / 2 - 0.6, 0.0, 1, "bad")
    for a, b in zip(bow, bad):
        a[40] = b[0]
    p_bow = write_pos(tmp_path / "bow.pos", t, *bow)
    p_stern = write_pos(tmp_path / "stern.pos", t, *stern)
    vessels = [VesselSpec("Boat", (p_bow, p_stern))]
    with pytest.raises(
        InputError, match=r"vessel 'Boat' heading \(antennas \(eq\. 3\.6\)\) jumps 1[0-9]{2}\.\d° and back"
    ) as err:
        compute_ground_truth(vessels, ORIGIN, rate_hz=5.0)
    line = 40 + 1 + sum(1 for x in p_bow.read_text().split("\n") if x.startswith("%"))
    assert err.value.source == f"{p_bow} line {line}, {p_stern} line {line}"
    assert len(compute_ground_truth(vessels, ORIGIN, rate_hz=5.0, max_turn_rate=np.inf).vessels) == 1


def _nmea_line(body: str) -> str:
    return f"${body}*{nmea_checksum(body):02X}"


@pytest.mark.parametrize(
    ("fmt", "edit", "match"),
    [
        ("csv", lambda s: s.replace(",63.", ",\u0663.", 1), r"line 2: expected a number for lat, got '\u0663\."),
        ("csv", lambda s: s.replace(",10.", ",1_0.", 1), r"line 2: expected a number for lon, got '1_0\."),
        ("csv", lambda s: s.replace(",10.", ",10\u00a0", 1), r"line 2: expected a number for lon, got '10\\xa0"),
        ("csv", lambda s: s.replace(",40.0000\n", ",inf\n", 1), r"line 2: expected a finite number for height, got 'inf'"),
        ("csv", lambda s: s.replace("\n1600164000.0,", "\nnan,", 1), r"line 2: expected POSIX seconds or an ISO 8601 time"),
        (
            "gpx",
            lambda s: s.replace('lat="63.', 'lat="\u00a063.', 1),
            r"line \d+: expected a number for latitude, got '\\xa063\.",
        ),
        ("gpx", lambda s: s.replace('lon="10.390000000"', 'lon="NaN"', 1), r"expected a finite number for longitude, got 'NaN'"),
        (
            "gpx",
            lambda s: s.replace("<ele>40.000</ele>", "<ele>1e999</ele>", 1),
            r"expected a finite number for elevation, got '1e999'",
        ),
        (
            "gpx",
            lambda s: s.replace("<ele>40.000</ele>", "<ele>40&#160;</ele>", 1),
            r"expected a number for elevation, got '40&#160;'",
        ),
        (
            "pos",
            lambda s: s.replace("   40.0000   ", "   nan   ", 1),
            r"line \d+: expected a finite number for height, got 'nan'",
        ),
        ("pos", lambda s: s.replace("   40.0000   ", "   4_0.0   ", 1), r"line \d+: expected a number for height, got '4_0\.0'"),
    ],
)
def test_numbers_the_formats_do_not_allow(tmp_path: Path, fmt: str, edit, match: str) -> None:  # type: ignore[no-untyped-def]
    t = T0 + np.arange(3) * 0.2
    lat, lon, h = np.full(3, 63.43), np.full(3, 10.39), np.full(3, 40.0)
    writer = {"csv": write_csv, "gpx": write_gpx, "pos": write_pos}[fmt]
    path = writer(tmp_path / f"log.{fmt}", t, lat, lon, h)
    text = path.read_text()
    changed = edit(text)
    assert changed != text
    path.write_text(changed, encoding="utf-8")
    with pytest.raises(InputError, match=match) as err:
        read_antenna_log(path)
    assert err.value.source == str(path)


def test_nmea_numbers(tmp_path: Path) -> None:
    rmc = _nmea_line("GPRMC,100000.00,A,6326.0000,N,01023.4000,E,0.0,0.0,150920,,,A")
    for gga, match in (
        ("GPGGA,100000.00,6326.0000,N,01023.4000,E,4,12,0.7,nan,M,0.0,M,,", r"expected a finite number for altitude, got 'nan'"),
        ("GPGGA,100000.00,6326.0000,N,01023.4000,E,4,12,0.7,1e999,M,0.0,M,,", r"expected a finite number for altitude"),
        ("GPGGA,100000.00,6326.0000,N,01023.4000,E,4,12,0.7,4_0,M,0.0,M,,", r"expected a number for altitude, got '4_0'"),
        ("GPZDA,100000.00,1_5,09,2020,,", r"expected ZDA day,month,year, got '1_5,09,2020'"),
    ):
        path = tmp_path / "log.nmea"
        path.write_text(f"{rmc}\n{_nmea_line(gga)}\n")
        with pytest.raises(InputError, match=match) as err:
            read_antenna_log(path)
        assert err.value.where == "line 2"


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 58), st.sampled_from([2, 3]), st.floats(-1e4, 1e4).map(lambda x: f"{x:.6f}"))
def test_any_one_changed_coordinate_is_read_checked_or_refused(k: int, column: int, value: str) -> None:
    """One coordinate of the bow log replaced by any number: either the ground truth is built and its
    CSV reads back, or one InputError names the bow file and the line."""
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        line = 4 + k
        bow = _edit_pos(EXAMPLES_DIR / "havfruen_bow.pos", tmp / "bow.pos", line, column, value)
        shutil.copy(EXAMPLES_DIR / "havfruen_stern.pos", tmp / "stern.pos")
        try:
            result = compute_ground_truth([VesselSpec("Havfruen", (bow, tmp / "stern.pos"))], ORIGIN)
        except InputError as exc:
            assert str(bow) in str(exc.source) and "line " in str(exc)
            return
        write_outputs(result, tmp / "gt.csv")
        load_scenario(tmp / "gt.csv")


def test_heights_beyond_any_vessel_are_refused(tmp_path: Path) -> None:
    t = T0 + np.arange(3) * 0.2
    path = write_csv(tmp_path / "h.csv", t, np.full(3, 63.43), np.full(3, 10.39), np.array([40.0, 99999999999999999999.0, 40.0]))
    with pytest.raises(InputError, match=r"line 3: height 1e\+20 outside \[-11000, 100000\] m"):
        read_antenna_log(path)
