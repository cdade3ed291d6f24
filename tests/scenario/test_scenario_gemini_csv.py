"""Gemini CSV: round trips with POSIX and TimeOfDay times, and malformed files."""

from __future__ import annotations

import datetime as dt
from pathlib import Path

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.scenario.gemini_csv import read_gemini_csv, write_gemini_csv
from seatwin.scenario.model import Trajectory

START = 1600171085.3  # 2020-09-15 11:58:05.3 UTC


def _trajectories() -> list[Trajectory]:
    t = START + np.arange(50) / 10.0
    k = np.arange(50)
    return [
        Trajectory(t, -300 + 0.3 * k, -315 + 0.2 * k, np.radians(175.0 + 0.4 * k)),  # crosses ±180°
        Trajectory(t, 10.0 + 0.0 * k, 5.0 - 0.25 * k, np.full(50, -np.pi / 2)),
        Trajectory(t, -36.1 + 0.01 * k, 15.1 + 0.0 * k, np.radians(-125.0 + 0.1 * k)),
    ]


def _assert_same(a: dict[int, Trajectory], b: list[Trajectory], time_atol: float = 0.0) -> None:
    assert sorted(a) == [1, 2, 3]
    for n, ref in enumerate(b, start=1):
        got = a[n]
        np.testing.assert_allclose(got.time, ref.time, rtol=0, atol=time_atol)
        np.testing.assert_allclose(got.north, ref.north, rtol=0, atol=1e-12)
        np.testing.assert_allclose(got.east, ref.east, rtol=0, atol=1e-12)
        dh = np.angle(np.exp(1j * (got.heading - ref.heading)))
        assert np.abs(dh).max() < 1e-12


def test_posix_round_trip_is_exact(tmp_path: Path):
    trs = _trajectories()
    assert write_gemini_csv(tmp_path / "s.csv", trs) is None
    back = read_gemini_csv(tmp_path / "s.csv")
    _assert_same(back, trs)
    assert (tmp_path / "s.csv").read_text().splitlines()[0] == (
        "TimeInSecondsPosix,V1x,V1y,V1Heading,V2x,V2y,V2Heading,V3x,V3y,V3Heading"
    )
    assert not list(tmp_path.glob("*.part"))


def test_time_of_day_round_trip_needs_the_date(tmp_path: Path):
    trs = _trajectories()
    date = write_gemini_csv(tmp_path / "s.csv", trs, time_format="time_of_day")
    assert date == dt.date(2020, 9, 15)
    lines = (tmp_path / "s.csv").read_text().splitlines()
    assert lines[0].startswith("TimeOfDay,V1x")
    assert lines[1].startswith("11:58:05.300,")
    with pytest.raises(InputError, match="TimeOfDay; give the recording date"):
        read_gemini_csv(tmp_path / "s.csv")
    _assert_same(read_gemini_csv(tmp_path / "s.csv", date=date), trs, time_atol=1e-6)


def test_time_of_day_cannot_span_midnight(tmp_path: Path):
    t = 1600214399.5 + np.arange(3) * 0.5  # 23:59:59.5 → 00:00:00.5
    tr = Trajectory(t, [0, 1, 2], [0, 0, 0], [0, 0, 0])
    with pytest.raises(InputError, match="midnight"):
        write_gemini_csv(tmp_path / "m.csv", [tr], time_format="time_of_day")
    assert not (tmp_path / "m.csv").exists()


HEADER = "TimeInSecondsPosix,V1x,V1y,V1Heading\n"


@pytest.mark.parametrize(
    ("text", "pattern"),
    [
        ("", r"empty file"),
        ("Time,V1x,V1y,V1Heading\n1,0,0,0\n", r"line 1: expected a TimeInSecondsPosix or TimeOfDay column"),
        ("TimeInSecondsPosix,V1x,V1Heading\n1,0,0\n2,0,0\n", r"line 1: missing column\(s\) V1y"),
        ("TimeInSecondsPosix,foo\n1,0\n2,0\n", r"line 1: no vessel columns"),
        (HEADER + "1,0,0,0\n2,0,abc,0\n", r"line 3: expected a number for V1y, got 'abc'"),
        (HEADER + "1,0,0,0\n2,0,0,nan\n", r"line 3: expected a finite number for V1Heading, got 'nan'"),
        (HEADER + "1,0,0,0\n2,0,0,-Infinity\n", r"line 3: expected a finite number for V1Heading, got '-Infinity'"),
        (HEADER + "1,0,0,0\n2,0,0,1e999\n", r"line 3: expected a finite number for V1Heading, got '1e999'"),
        (HEADER + "1,0,0,0\nnan,0,0,0\n", r"line 3: expected a finite number for TimeInSecondsPosix, got 'nan'"),
        (HEADER + "1,0,0,0\n2,12\u00a0,0,0\n", r"line 3: expected a number for V1x, got '12\\xa0'"),
        (HEADER + "1,0,0,0\n2,1_0,0,0\n", r"line 3: expected a number for V1x, got '1_0'"),
        (HEADER + "1,0,0,0\n2,\u0661,0,0\n", r"line 3: expected a number for V1x, got '\u0661'"),
        ("TimeOfDay,V1x,V1y,V1Heading\n12:00:00.0,0,0,0\n12:00:01\u00a0,0,0,0\n", r"line 3: expected HH:MM:SS"),
        (HEADER + "1,0,0,0\n2,0,0\n", r"line 3: expected 4 fields, got 3"),
        (HEADER + "1,0,0,0\n2,0,0,0\n2,1,0,0\n", r"line 4: duplicated time 2 after 2 \(line 3\)"),
        (HEADER + "1,0,0,0\n3,0,0,0\n2,1,0,0\n", r"line 4: decreasing time 2 after 3"),
        (HEADER + "1,0,0,0\n", r"at least 2 data lines"),
        ("TimeOfDay,V1x,V1y,V1Heading\n12:00:00.0,0,0,0\n12:00:xx,0,0,0\n", r"line 3: expected HH:MM:SS"),
    ],
)
def test_malformed_csv_names_file_and_line(tmp_path: Path, text: str, pattern: str):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=pattern) as info:
        read_gemini_csv(path, date=dt.date(2020, 9, 15))
    assert str(path) in str(info.value)


def test_missing_file(tmp_path: Path):
    with pytest.raises(InputError, match="cannot open"):
        read_gemini_csv(tmp_path / "nope.csv")


def test_line_numbers_count_blank_lines(tmp_path: Path):
    path = tmp_path / "gaps.csv"
    path.write_text(HEADER + "1,0,0,0\n\n2,0,0,0\n\n1.5,0,0,0\n")
    with pytest.raises(InputError, match=r"line 6: decreasing time 1\.5 after 2 \(line 4\)"):
        read_gemini_csv(path)


HEADING_ROWS = ["1.0,0,0,10", "1.1,0.1,0,11", "1.2,0.2,0,12", "1.3,0.3,0,13", "1.4,0.4,0,14"]


@pytest.mark.parametrize(
    ("spike", "pattern"),
    [
        ("192", r"line 4, column V1Heading: vessel 1 heading jumps 179\.0° and back \(from 11° after line 3 to 192° to 13°"),
        ("-80", r"line 4, column V1Heading: vessel 1 heading jumps 91\.0° and back"),
        ("370", None),  # 370° is 10°: no spike
        ("100", None),  # 88° each way: within the jump
    ],
)
def test_one_row_heading_spike_is_an_error(tmp_path: Path, spike: str, pattern: str | None):
    rows = list(HEADING_ROWS)
    rows[2] = rows[2].rsplit(",", 1)[0] + "," + spike
    path = tmp_path / "spike.csv"
    path.write_text(HEADER + "\n".join(rows) + "\n")
    if pattern is None:
        assert len(read_gemini_csv(path)[1].time) == 5
        return
    with pytest.raises(InputError, match=pattern) as info:
        read_gemini_csv(path)
    assert str(info.value).startswith(f"{path}: line 4, column V1Heading:") and "faster than max_turn_rate 180 °/s" in str(
        info.value
    )
    assert len(read_gemini_csv(path, max_turn_rate=float("inf"))[1].time) == 5


def test_a_turn_that_does_not_come_back_or_is_slow_is_no_spike(tmp_path: Path):
    path = tmp_path / "turn.csv"
    path.write_text(HEADER + "1.0,0,0,0\n1.1,0,0.1,0\n1.2,0,0.2,180\n1.3,0,0.3,180\n")  # a reversal: one jump, no return
    assert len(read_gemini_csv(path)[1].time) == 4
    path.write_text(HEADER + "1,0,0,0\n2,0,0.1,150\n3,0,0.2,0\n")  # 150°/s: a boat spinning, not a corrupt row
    assert len(read_gemini_csv(path)[1].time) == 3
    with pytest.raises(InputError, match="heading spike"):
        read_gemini_csv(path, max_turn_rate=100.0)


def test_max_turn_rate_is_checked():
    from seatwin.errors import ParameterError

    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(ParameterError, match="max_turn_rate"):
            read_gemini_csv("unused.csv", max_turn_rate=bad)


def test_builtin_scenarios_have_no_teleport_or_heading_spike():
    from seatwin.scenario import builtin_names, builtin_scenario
    from seatwin.scenario.plausibility import first_heading_spike, first_teleport

    for name in builtin_names():
        for v in builtin_scenario(name).vessels:
            tr = v.trajectory
            assert first_teleport(tr.time, tr.north, tr.east) is None, (name, v.name)
            assert first_heading_spike(tr.time, np.degrees(tr.heading)) is None, (name, v.name)


def test_vessel_numbers_are_ascii_and_bounded(tmp_path: Path):
    path = tmp_path / "v.csv"
    path.write_text("TimeInSecondsPosix,V" + "9" * 5000 + "x,V1y,V1Heading\n1,0,0,0\n2,0,0,0\n")
    with pytest.raises(InputError, match=r"line 1: vessel number of 5000 digits"):
        read_gemini_csv(path)
    path.write_text("TimeInSecondsPosix,V\u0663x,V\u0663y,V\u0663Heading\n1,0,0,0\n2,0,0,0\n")
    with pytest.raises(InputError, match=r"line 1: no vessel columns"):
        read_gemini_csv(path)
