"""Command-line value syntax (``seatwin.cli.parsing``): origins and vessels, errors naming the flag."""

from __future__ import annotations

from pathlib import Path

import pytest

from seatwin.cli.parsing import parse_origin, parse_vessel
from seatwin.errors import InputError
from seatwin.geo import GeodeticOrigin
from seatwin.groundtruth import VesselSpec


def test_origin_ok() -> None:
    assert parse_origin("63.43, 10.39") == GeodeticOrigin(63.43, 10.39, 0.0)
    assert parse_origin("63.43,10.39,5.5") == GeodeticOrigin(63.43, 10.39, 5.5)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("63.43", "LAT,LON"),
        ("1,2,3,4", "LAT,LON"),
        ("north,east", "numbers"),
        ("63.4,", "numbers"),
        ("95,10", "latitude"),
        ("63,-200", "longitude"),
        ("nan,10", "finite"),
        ("63,inf", "finite"),
    ],
)
def test_origin_errors_name_the_flag(text: str, match: str) -> None:
    with pytest.raises(InputError, match=match) as exc:
        parse_origin(text)
    assert str(exc.value).startswith("--origin: ")


def test_vessel_ok() -> None:
    assert parse_vessel("Finn=bow.gpx,stern.gpx") == VesselSpec("Finn", (Path("bow.gpx"), Path("stern.gpx")))
    s = parse_vessel(" Havfruen = a.pos , b.pos , 2.01 ")
    assert s.name == "Havfruen" and len(s.files) == 2 and s.baseline_m == 2.01
    s = parse_vessel("milliAmpere=gnss.nmea")
    assert len(s.files) == 1 and s.baseline_m is None


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("Finn", "NAME=BOW"),
        ("=a.gpx", "NAME=BOW"),
        ("Finn=", "NAME=BOW"),
        ("Finn=a,,b", "NAME=BOW"),
        ("Finn=a,b,c,d", "NAME=BOW"),
        ("Finn=a,b,long", "baseline must be a number"),
        ("Finn=a,b,-1", "positive"),
        ("Finn=a,b,nan", "positive"),
    ],
)
def test_vessel_errors_name_the_flag(text: str, match: str) -> None:
    with pytest.raises(InputError, match=match) as exc:
        parse_vessel(text)
    assert str(exc.value).startswith("--vessel: ")
