"""Readers: GPX, NMEA 0183, RTKLIB .pos, generic CSV — valid files and every kind of malformed input."""

from __future__ import annotations

import calendar
from pathlib import Path

import numpy as np
import pytest
from gt_synth import gga, rmc, write_csv, write_gpx, write_nmea, write_pos

from seatwin.errors import InputError
from seatwin.groundtruth import (
    AntennaLog,
    detect_format,
    read_antenna_log,
    read_csv_log,
    read_gpx,
    read_nmea,
    read_rtklib_pos,
)
from seatwin.groundtruth.read_nmea import nmea_checksum

T0 = float(calendar.timegm((2020, 9, 15, 10, 0, 0)))
LAT = np.array([63.43, 63.4301, 63.4302])
LON = np.array([10.39, 10.3901, 10.3902])
H = np.array([40.0, 40.1, 40.2])


def fix(body: str) -> str:
    return f"${body}*{nmea_checksum(body):02X}"


def write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def error_of(reader, path: Path) -> InputError:
    with pytest.raises(InputError) as exc:
        reader(path)
    assert str(path) in str(exc.value), "the error names the file"
    return exc.value


# ---------------------------------------------------------------- AntennaLog


def test_antenna_log_validation() -> None:
    ok = AntennaLog([1.0, 2.0], [63.0, 63.0], [10.0, 10.0], None, "x", "test")
    assert len(ok) == 2 and ok.quality_counts() is None
    with pytest.raises(InputError, match="duplicated"):
        AntennaLog([1.0, 1.0], [63.0, 63.0], [10.0, 10.0], None, "x", "test", lines=[5, 6])
    with pytest.raises(InputError, match="line 6"):
        AntennaLog([1.0, 0.5], [63.0, 63.0], [10.0, 10.0], None, "x", "test", lines=[5, 6])
    with pytest.raises(InputError, match="at least 2"):
        AntennaLog([1.0], [63.0], [10.0], None, "x", "test")
    with pytest.raises(InputError, match="latitude is not a finite"):
        AntennaLog([1.0, 2.0], [63.0, np.nan], [10.0, 10.0], None, "x", "test")
    with pytest.raises(InputError, match="height is not a finite"):
        AntennaLog([1.0, 2.0], [63.0, 63.0], [10.0, 10.0], [np.inf, 0.0], "x", "test")
    with pytest.raises(InputError, match="outside"):
        AntennaLog([1.0, 2.0], [63.0, 95.0], [10.0, 10.0], None, "x", "test")


# ---------------------------------------------------------------- GPX


def test_gpx_valid(tmp_path: Path) -> None:
    p = write_gpx(tmp_path / "a.gpx", T0 + np.array([0.0, 1.0, 2.5]), LAT, LON, H)
    log = read_gpx(p)
    np.testing.assert_allclose(log.time, T0 + np.array([0.0, 1.0, 2.5]))
    np.testing.assert_allclose(log.lat, LAT)
    np.testing.assert_allclose(log.height, H)
    assert log.quality is None and log.format == "gpx"
    assert list(log.lines) == [6, 10, 14]


def test_gpx_zone_offset_and_no_elevation(tmp_path: Path) -> None:
    text = (
        '<gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>\n'
        '<trkpt lat="63.43" lon="10.39"><time>2020-09-15T12:00:00+02:00</time></trkpt>\n'
        '<trkpt lat="63.44" lon="10.39"><time>2020-09-15T10:00:01</time></trkpt>\n'
        "</trkseg></trk></gpx>\n"
    )
    log = read_gpx(write(tmp_path, "a.gpx", text))
    np.testing.assert_allclose(log.time, [T0, T0 + 1])
    assert log.height is None


GPX_HEAD = '<gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>\n'
GPX_TAIL = "</trkseg></trk></gpx>\n"
PT = '<trkpt lat="{lat}" lon="10.39"><ele>1</ele><time>{time}</time></trkpt>\n'


@pytest.mark.parametrize(
    ("body", "match", "where"),
    [
        ("<trkpt lat='63'", "not well-formed XML", "line 2"),
        (
            PT.format(lat="63.43", time="2020-09-15T10:00:00Z") + PT.format(lat="abc", time="2020-09-15T10:00:01Z"),
            "expected a number for latitude, got 'abc'",
            "line 3",
        ),
        (
            PT.format(lat="63.43", time="2020-09-15T10:00:00Z") + '<trkpt lat="63.4"><time>2020-09-15T10:00:01Z</time></trkpt>\n',
            "malformed GPX",
            None,
        ),
        (
            PT.format(lat="63.43", time="2020-09-15T10:00:00Z") + PT.format(lat="63.43", time="garbage"),
            "without a valid <time>",
            "line 3",
        ),
        (
            PT.format(lat="63.43", time="2020-09-15T10:00:00Z")
            + '<trkpt lat="63.4" lon="10.3"><time>2020-09-15T10:00:01Z</time></trkpt>\n',
            "without <ele>",
            "line 3",
        ),
        (
            PT.format(lat="63.43", time="2020-09-15T10:00:00Z") + PT.format(lat="63.44", time="2020-09-15T10:00:00Z"),
            "duplicated time",
            "line 3",
        ),
        (
            PT.format(lat="63.43", time="2020-09-15T10:00:05Z") + PT.format(lat="63.44", time="2020-09-15T10:00:00Z"),
            "decreasing",
            "line 3",
        ),
        (
            PT.format(lat="63.43", time="2020-09-15T10:00:00Z") + PT.format(lat="nan", time="2020-09-15T10:00:01Z"),
            "expected a finite number for latitude, got 'nan'",
            "line 3",
        ),
        (PT.format(lat="63.43", time="2020-09-15T10:00:00Z"), "at least 2 fixes", None),
        ("", "no track points", None),
    ],
)
def test_gpx_malformed(tmp_path: Path, body: str, match: str, where: str | None) -> None:
    err = error_of(read_gpx, write(tmp_path, "bad.gpx", GPX_HEAD + body + GPX_TAIL))
    assert match in str(err)
    if where:
        assert err.where == where


# ---------------------------------------------------------------- NMEA


def test_nmea_valid(tmp_path: Path) -> None:
    p = write_nmea(tmp_path / "a.nmea", T0 + np.array([0.0, 0.2, 0.4]), LAT, LON, H, quality=np.array([4, 5, 4]))
    log = read_nmea(p)
    np.testing.assert_allclose(log.time, T0 + np.array([0.0, 0.2, 0.4]), atol=1e-6)
    np.testing.assert_allclose(log.lat, LAT, atol=1e-9)
    np.testing.assert_allclose(log.lon, LON, atol=1e-9)
    np.testing.assert_allclose(log.height, H, atol=1e-3)  # MSL altitude + geoid separation
    assert list(log.quality) == [4, 5, 4]
    assert log.quality_counts() == {"rtk_fixed": 2, "rtk_float": 1}


def test_nmea_hand_parsed_gga_zda_southwest_prefix_and_no_fix(tmp_path: Path) -> None:
    lines = [
        "2020-09-15 10:00:00 " + fix("GNZDA,100000.00,15,09,2020,00,00"),
        fix("GNGGA,100000.00,6325.8000,S,01023.4000,W,4,12,0.8,10.0,M,39.0,M,1.0,0001"),
        fix("GNGGA,100001.00,,,,,0,00,99.9,,,,,,"),
        fix("GNGSV,3,1,12,01,40,083,46"),
        fix("PGRME,1.0,M,2.0,M,3.0,M"),
        "!AIVDM,1,1,,A,13u?etPv2;0n:dDPwUM1U1Cb069D,0*24",
        fix("GNGGA,100002.00,6325.8060,S,01023.4000,W,5,12,0.8,10.5,M,39.0,M,1.0,0001"),
        "",
    ]
    log = read_nmea(write(tmp_path, "a.log", "\n".join(lines)))
    np.testing.assert_allclose(log.time, [T0, T0 + 2.0])
    assert log.lat[0] == pytest.approx(-(63 + 25.8 / 60))
    assert log.lon[0] == pytest.approx(-(10 + 23.4 / 60))
    assert log.height[0] == pytest.approx(49.0)
    assert log.skipped == {"no fix (GGA quality 0)": 1}
    assert list(log.lines) == [2, 7]


def test_nmea_short_gga_without_geoid_fields(tmp_path: Path) -> None:
    lines = [GOOD[0], fix("GPGGA,100000.00,6325.8000,N,01023.4000,E,1,08,1.0,12.5,M"), GOOD[1].replace("100000.00", "100001.00")]
    lines[2] = fix(_gga_body(time="100001.00"))
    log = read_nmea(write(tmp_path, "a.nmea", "\n".join(lines)))
    assert log.height.tolist() == [12.5, 49.0]


def test_nmea_midnight_rollover(tmp_path: Path) -> None:
    lines = [
        rmc(T0 + 14 * 3600 - 1, 63.43, 10.39),  # 23:59:59 on 15.09
        gga(T0 + 14 * 3600 - 1, 63.43, 10.39, 40.0),
        gga(T0 + 14 * 3600, 63.43, 10.39, 40.0),  # 00:00:00, no RMC yet for the new day
        gga(T0 + 14 * 3600 + 1, 63.43, 10.39, 40.0),
    ]
    log = read_nmea(write(tmp_path, "a.nmea", "\n".join(lines)))
    np.testing.assert_allclose(log.time, T0 + 14 * 3600 + np.array([-1.0, 0.0, 1.0]))


def test_nmea_gga_before_first_date(tmp_path: Path) -> None:
    lines = [gga(T0, 63.43, 10.39, 40.0), gga(T0 + 1, 63.43, 10.39, 40.0), rmc(T0 + 1, 63.43, 10.39)]
    log = read_nmea(write(tmp_path, "a.txt", "\n".join(lines)))
    np.testing.assert_allclose(log.time, [T0, T0 + 1])


def _gga_body(lat: str = "6325.8000,N", time: str = "100001.00", q: str = "4") -> str:
    return f"GPGGA,{time},{lat},01023.4000,E,{q},12,0.8,10.0,M,39.0,M,1.0,0001"


GOOD = [rmc(T0, 63.43, 10.39), fix(_gga_body(time="100000.00"))]


@pytest.mark.parametrize(
    ("line", "match"),
    [
        ("$" + _gga_body() + "*00", "checksum mismatch"),
        ("$" + _gga_body(), "without checksum"),
        ("$" + _gga_body() + "*G1", "two hex digits"),
        (fix("GPGGA,100001.00,6325.8000,N,01023.4000,E,4"), "at least 10 fields"),
        (fix(_gga_body(lat="6365.8000,N")), "latitude"),
        (fix(_gga_body(lat="6325.8000,X")), "latitude"),
        (fix(_gga_body(lat="63.43,N")), "latitude"),
        (fix(_gga_body(time="250001.00")), "hhmmss"),
        (fix(_gga_body(time="10:00:01")), "hhmmss"),
        (fix(_gga_body(q="x")), "fix quality"),
        (fix(_gga_body().replace("10.0,M", "ten,M")), "altitude"),
        (fix(_gga_body(time="100000.00")), "duplicated"),
        (fix(_gga_body(time="095959.00")), "decreasing"),
        ("ERROR: receiver memory full", "expected an NMEA sentence"),
        ("$gpgga,foo*00", "expected an NMEA sentence"),
        (fix("GPRMC,100001.00,A,6325.8,N,01023.4,E,0,0,150920"[:-6] + "1509"), "ddmmyy"),
        (fix("GPZDA,100001.00,15,xx,2020,00,00"), "day,month,year"),
        (fix("GPRMC,100001.00,A,6325.8,N,01023.4,E,0,0,320920,,,A"), "invalid date"),
    ],
)
def test_nmea_malformed(tmp_path: Path, line: str, match: str) -> None:
    err = error_of(read_nmea, write(tmp_path, "bad.nmea", "\n".join([*GOOD, line, ""])))
    assert match in str(err)
    assert err.where == "line 3", "the error names the line"


def test_nmea_no_date_no_fix_non_ascii(tmp_path: Path) -> None:
    assert "no RMC or ZDA" in str(error_of(read_nmea, write(tmp_path, "a.nmea", "\n".join(GOOD[1:] + [fix(_gga_body())]))))
    assert "no GGA" in str(error_of(read_nmea, write(tmp_path, "b.nmea", GOOD[0] + "\n")))
    p = tmp_path / "c.nmea"
    p.write_bytes(b"\xff\xfe$GPGGA\n")
    assert "not ASCII" in str(error_of(read_nmea, p))
    assert "cannot open" in str(error_of(read_nmea, tmp_path / "missing.nmea"))


# ---------------------------------------------------------------- RTKLIB .pos


@pytest.mark.parametrize("week_tow", [False, True])
def test_pos_gpst_to_utc(tmp_path: Path, week_tow: bool) -> None:
    t = T0 + np.array([0.0, 0.2, 0.4])
    log = read_rtklib_pos(write_pos(tmp_path / "a.pos", t, LAT, LON, H, q=np.array([1, 2, 1]), week_tow=week_tow))
    np.testing.assert_allclose(log.time, t, atol=1e-6)  # written as GPST = UTC + 18 s
    np.testing.assert_allclose(log.lat, LAT)
    assert log.quality_counts() == {"fix": 2, "float": 1}
    assert log.format == "rtklib-pos (GPST)"


def test_pos_hand_values_utc_jst_dms(tmp_path: Path) -> None:
    rest = "   1  12   0.0050   0.0040   0.0110  -0.0010   0.0010  -0.0030   1.00  999.9"
    utc = write(tmp_path, "u.pos", "%  UTC  latitude(deg) longitude(deg)  height(m)  Q\n"
                f"2020/09/15 10:00:00.000  63.43  10.39  40.0{rest}\n"
                f"2020/09/15 10:00:01.000  63.43  10.39  40.0{rest}\n")  # fmt: skip
    assert read_rtklib_pos(utc).time[0] == T0
    jst = write(tmp_path, "j.pos", "%  JST  latitude(deg) longitude(deg)  height(m)  Q\n"
                f"2020/09/15 19:00:00.000  63.43  10.39  40.0{rest}\n"
                f"2020/09/15 19:00:01.000  63.43  10.39  40.0{rest}\n")  # fmt: skip
    assert read_rtklib_pos(jst).time[0] == T0
    dms = write(tmp_path, "d.pos", "%  GPST  latitude(d'\")  longitude(d'\")  height(m)  Q\n"
                f"2020/09/15 10:00:18.000  63 25 48.000  -10 23 24.000  40.0{rest}\n"
                f"2020/09/15 10:00:19.000  63 25 48.000  -10 23 24.000  40.0{rest}\n")  # fmt: skip
    log = read_rtklib_pos(dms)
    assert log.time[0] == T0
    assert log.lat[0] == pytest.approx(63 + 25 / 60 + 48 / 3600)
    assert log.lon[0] == pytest.approx(-(10 + 23 / 60 + 24 / 3600))


POS_HEAD = "% program : RTKPOST ver.2.4.3\n%  GPST   latitude(deg) longitude(deg)  height(m)   Q  ns\n"
ROW0 = "2020/09/15 10:00:18.000   63.430000000   10.390000000    40.0000   1  12\n"


@pytest.mark.parametrize(
    ("row", "match"),
    [
        ("2020/09/15 10:00:19.000   63.43   10.39\n", "at least 6 columns"),
        ("2020/13/15 10:00:19.000   63.43   10.39  40.0  1  12\n", "invalid date"),
        ("2020-09-15 10:00:19.000   63.43   10.39  40.0  1  12\n", "expected time"),
        ("2123 700000.000   63.43   10.39  40.0  1  12\n", "seconds of week"),
        ("2020/09/15 10:00:19.000   north   10.39  40.0  1  12\n", "latitude"),
        ("2020/09/15 10:00:19.000   63.43   10.39  nan  1  12\n", "finite"),
        ("2020/09/15 10:00:19.000   63.43   10.39  40.0  fix  12\n", "quality Q"),
        ("2020/09/15 10:00:18.000   63.43   10.39  40.0  1  12\n", "duplicated"),
        ("2020/09/15 10:00:17.000   63.43   10.39  40.0  1  12\n", "decreasing"),
        ("2020/09/15 10:00:19.000   95.43   10.39  40.0  1  12\n", "outside"),
        ("1970/01/01 00:00:19.000   63.43   10.39  40.0  1  12\n", "before the GPS epoch"),
    ],
)
def test_pos_malformed(tmp_path: Path, row: str, match: str) -> None:
    err = error_of(read_rtklib_pos, write(tmp_path, "bad.pos", POS_HEAD + ROW0 + row))
    assert match in str(err)
    assert err.where == "line 4"


def test_pos_bad_headers(tmp_path: Path) -> None:
    xyz = write(tmp_path, "x.pos", "%  GPST   x-ecef(m)  y-ecef(m)  z-ecef(m)  Q\n" + ROW0)
    assert "llh" in str(error_of(read_rtklib_pos, xyz))
    tai = write(tmp_path, "t.pos", "%  TAI   latitude(deg) longitude(deg)  height(m)  Q\n" + ROW0)
    assert "time system" in str(error_of(read_rtklib_pos, tai))
    assert "no solution lines" in str(error_of(read_rtklib_pos, write(tmp_path, "e.pos", POS_HEAD)))


# ---------------------------------------------------------------- CSV


@pytest.mark.parametrize("iso", [False, True])
def test_csv_valid(tmp_path: Path, iso: bool) -> None:
    t = T0 + np.array([0.0, 0.5, 1.0])
    log = read_csv_log(write_csv(tmp_path / "a.csv", t, LAT, LON, H, iso=iso))
    np.testing.assert_allclose(log.time, t)
    np.testing.assert_allclose(log.lon, LON)
    np.testing.assert_allclose(log.height, H)


def test_csv_headerless_named_columns_quality_naive_iso(tmp_path: Path) -> None:
    log = read_csv_log(write(tmp_path, "a.csv", f"{T0},63.43,10.39\n{T0 + 1},63.44,10.39\n"))
    assert log.height is None and list(log.lines) == [1, 2]
    log = read_csv_log(
        write(
            tmp_path,
            "b.csv",
            "Longitude, Latitude ,Quality,UTC\n10.39,63.43,4,2020-09-15T10:00:00\n10.39,63.43,5,2020-09-15 10:00:01\n",
        )
    )
    np.testing.assert_allclose(log.time, [T0, T0 + 1])
    np.testing.assert_allclose(log.lat, 63.43)
    assert log.quality_counts() == {"code 4": 1, "code 5": 1}


@pytest.mark.parametrize(
    ("text", "match", "where"),
    [
        ("time,lat,lon\n1600164000,63.43,10.39\n15.09.2020 10:00,63.43,10.39\n", "ISO 8601", "line 3"),
        ("time,lat,lon\n1600164000,63.43,10.39\n1600164001,63.43\n", "expected 3 fields", "line 3"),
        ("time,lat,lon\n1600164000,63.43,10.39\n1600164001,N63,10.39\n", "expected a number for lat", "line 3"),
        ("time,lat,lon\n1600164000,63.43,10.39\n1600164001,nan,10.39\n", "expected a finite number for lat", "line 3"),
        ("time,lat,lon\n1600164000,63.43,10.39\n1600164000,63.43,10.39\n", "duplicated", "line 3"),
        ("time,lat,lon\n1600164000,63.43,10.39\n1600163999,63.43,10.39\n", "decreasing", "line 3"),
        (
            "time,lat,lon,quality\n1600164000,63.43,10.39,4\n1600164001,63.43,10.39,4.5\n",
            "integer quality code for quality",
            "line 3",
        ),
        ("time,latitude,lng,lon\n1600164000,63.43,10.39,10.39\n", "more than one lon", "line 1"),
        ("time,x,y\n1600164000,63.43,10.39\n1600164001,63.43,10.39\n", "no lat, lon column", "line 1"),
        ("1600164000,63.43,10.39,4,5\n1600164001,63.43,10.39,4,5\n", "3 or 4 columns", "line 1"),
        ("time,lat,lon\n1600164000,63.43,10.39\n", "at least 2 data lines", None),
        ("\n\n", "empty file", None),
    ],
)
def test_csv_malformed(tmp_path: Path, text: str, match: str, where: str | None) -> None:
    err = error_of(read_csv_log, write(tmp_path, "bad.csv", text))
    assert match in str(err)
    assert err.where == where


# ---------------------------------------------------------------- format detection


def test_detect_format(tmp_path: Path) -> None:
    nmea = write(tmp_path, "rec.txt", "\n".join([*GOOD, fix(_gga_body())]) + "\n")
    assert detect_format(nmea) == "nmea"
    assert read_antenna_log(nmea).format == "nmea"
    assert detect_format(write(tmp_path, "rec.log", "junk\n" + "\n".join(GOOD))) == "nmea"
    assert detect_format(write(tmp_path, "sol.dat", POS_HEAD + ROW0)) == "rtklib"
    assert detect_format(write(tmp_path, "trk.xml", GPX_HEAD + GPX_TAIL)) == "gpx"
    for name in ("a.gpx", "a.pos", "a.csv", "a.NMEA"):
        assert detect_format(tmp_path / name) in ("gpx", "rtklib", "csv", "nmea")
    with pytest.raises(InputError, match="cannot tell the file format"):
        detect_format(write(tmp_path, "havfruen.log", "ERROR 17: no satellites\n" * 3))
    with pytest.raises(InputError, match="no such file"):
        read_antenna_log(tmp_path / "missing.gpx")
    with pytest.raises(InputError, match="not a regular file"):
        read_antenna_log(tmp_path)
