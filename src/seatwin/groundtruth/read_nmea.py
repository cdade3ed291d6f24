"""NMEA 0183 reader: GGA fixes (position, fix quality), dated by RMC or ZDA sentences.

Every sentence the reader uses has its checksum checked. Any talker (``$GP``, ``$GN``,
``$GL``, …) is accepted; other sentence types (GSV, GSA, VTG, proprietary ``$P…``) are
skipped; text before the ``$`` on a line (a logger's timestamp) is ignored; a non-empty line
without a sentence is an error. GGA with fix quality 0 (no fix, empty position) is skipped
and counted in :attr:`AntennaLog.skipped`.

GGA carries only the UTC time of day: the date comes from the nearest preceding RMC or ZDA
(the first one in the file for GGA before it); a time of day more than 12 h before/after
the dating sentence's is taken to have crossed midnight.
"""

from __future__ import annotations

import calendar
import datetime as dt
import re
from functools import reduce
from pathlib import Path

import numpy as np

from seatwin.errors import InputError, parse_finite, read_text
from seatwin.groundtruth.log import AntennaLog

_SENTENCE = re.compile(r"^\$([A-Z]{2})([A-Z]{3}),")
_DAY = 86_400.0


def nmea_checksum(body: str) -> int:
    """XOR of the characters between ``$`` and ``*``."""
    return reduce(lambda a, c: a ^ ord(c), body, 0)


def _split(line: str, path: Path, line_no: int) -> tuple[str, list[str]] | None:
    """(sentence type, fields) of a checksum-valid sentence; ``None`` for a sentence we do not use."""
    sentence = line.strip()
    m = _SENTENCE.match(sentence)
    if not m:
        if sentence.startswith("$P") or sentence.startswith("!"):
            return None  # proprietary / encapsulated (AIS) sentences
        raise InputError(path, f"expected an NMEA sentence $ttsss,…*hh, got {sentence[:40]!r}", where=f"line {line_no}")
    kind = m.group(2)
    if kind not in ("GGA", "RMC", "ZDA"):
        return None
    star = sentence.rfind("*")
    if star < 0:
        raise InputError(path, f"{kind} sentence without checksum (*hh)", where=f"line {line_no}")
    body, given = sentence[1:star], sentence[star + 1 :].strip()
    if not re.fullmatch(r"[0-9A-Fa-f]{2}", given):
        raise InputError(path, f"checksum must be two hex digits, got {given!r}", where=f"line {line_no}")
    expected = int(given, 16)
    actual = nmea_checksum(body)
    if actual != expected:
        raise InputError(path, f"checksum mismatch: sentence says {expected:02X}, computed {actual:02X}", where=f"line {line_no}")
    return kind, body.split(",")[1:]


def _time_of_day(text: str, path: Path, line_no: int) -> float:
    m = re.fullmatch(r"(\d{2})(\d{2})(\d{2}(?:\.\d+)?)", text)
    if not m or int(m.group(1)) > 23 or int(m.group(2)) > 59 or float(m.group(3)) >= 61:
        raise InputError(path, f"expected UTC time hhmmss[.ss], got {text!r}", where=f"line {line_no}")
    return int(m.group(1)) * 3600.0 + int(m.group(2)) * 60.0 + float(m.group(3))


def _angle(text: str, hemi: str, degree_digits: int, name: str, path: Path, line_no: int) -> float:
    pattern = rf"(\d{{{degree_digits}}})(\d{{2}}(?:\.\d+)?)"
    m = re.fullmatch(pattern, text)
    ok_hemi = ("N", "S") if name == "latitude" else ("E", "W")
    if not m or float(m.group(2)) >= 60.0 or hemi not in ok_hemi:
        form = "ddmm.mmmm,N|S" if name == "latitude" else "dddmm.mmmm,E|W"
        raise InputError(path, f"expected {name} {form}, got {text!r},{hemi!r}", where=f"line {line_no}")
    value = int(m.group(1)) + float(m.group(2)) / 60.0
    return -value if hemi in ("S", "W") else value


def _float(text: str, name: str, path: Path, line_no: int, default: float | None = None) -> float:
    if text == "" and default is not None:
        return default
    return parse_finite(text, path, name, line_no)


def _date(day: int, month: int, year: int, path: Path, line_no: int) -> float:
    try:
        return calendar.timegm(dt.date(year, month, day).timetuple())
    except ValueError:
        raise InputError(path, f"invalid date {day:02d}.{month:02d}.{year}", where=f"line {line_no}") from None


def read_nmea(path: str | Path, date: dt.date | None = None) -> AntennaLog:
    """Read GGA fixes from an NMEA 0183 log. ``date`` (UTC) is used only if the file has no RMC/ZDA."""
    path = Path(path)
    text_lines = read_text(path, "NMEA 0183 sentences", encoding="ascii").split("\n")

    # Fixes as (time of day, lat, lon, height, quality, line, index of the dating sentence before it).
    fixes: list[tuple[float, float, float, float, int, int, int]] = []
    dates: list[tuple[float, float]] = []  # (midnight POSIX, time of day of the dating sentence)
    no_fix = 0
    for line_no, raw in enumerate(text_lines, start=1):
        if not raw.strip():
            continue
        start = raw.find("$")
        if start < 0:
            if raw.lstrip().startswith("!"):
                continue
            raise InputError(path, f"expected an NMEA sentence $ttsss,…*hh, got {raw.strip()[:40]!r}", where=f"line {line_no}")
        parsed = _split(raw[start:], path, line_no)
        if parsed is None:
            continue
        kind, f = parsed
        if kind == "GGA":
            if len(f) < 10:  # up to the altitude unit; geoid separation, age and station are optional
                raise InputError(path, f"GGA needs at least 10 fields, got {len(f)}", where=f"line {line_no}")
            quality_text = f[5]
            if not quality_text.isdigit():
                raise InputError(path, f"expected GGA fix quality 0–8, got {quality_text!r}", where=f"line {line_no}")
            quality = int(quality_text)
            if quality == 0:
                no_fix += 1
                continue
            tod = _time_of_day(f[0], path, line_no)
            lat = _angle(f[1], f[2], 2, "latitude", path, line_no)
            lon = _angle(f[3], f[4], 3, "longitude", path, line_no)
            alt = _float(f[8], "altitude", path, line_no, default=np.nan)
            sep = _float(f[10] if len(f) > 10 else "", "geoid separation", path, line_no, default=0.0)
            fixes.append((tod, lat, lon, alt + sep, quality, line_no, len(dates) - 1))
        elif kind == "RMC":
            if len(f) < 9:
                raise InputError(path, f"RMC needs at least 9 fields, got {len(f)}", where=f"line {line_no}")
            if f[0] == "" or f[8] == "":
                continue  # receiver without time yet
            tod = _time_of_day(f[0], path, line_no)
            m = re.fullmatch(r"(\d{2})(\d{2})(\d{2})", f[8])
            if not m:
                raise InputError(path, f"expected RMC date ddmmyy, got {f[8]!r}", where=f"line {line_no}")
            yy = int(m.group(3))
            dates.append((_date(int(m.group(1)), int(m.group(2)), 2000 + yy if yy < 80 else 1900 + yy, path, line_no), tod))
        else:  # ZDA
            if len(f) < 4:
                raise InputError(path, f"ZDA needs at least 4 fields, got {len(f)}", where=f"line {line_no}")
            if "" in f[:4]:
                continue
            tod = _time_of_day(f[0], path, line_no)
            if not all(re.fullmatch(r"[0-9]{1,4}", x) for x in f[1:4]):
                raise InputError(path, f"expected ZDA day,month,year, got {','.join(f[1:4])!r}", where=f"line {line_no}")
            d, mo, y = int(f[1]), int(f[2]), int(f[3])
            dates.append((_date(d, mo, y, path, line_no), tod))

    if not fixes:
        raise InputError(path, "no GGA sentence with a fix in the file")
    if not dates:
        if date is None:
            raise InputError(path, "no RMC or ZDA sentence gives the date of the GGA fixes")
        dates = [(float(calendar.timegm(date.timetuple())), fixes[0][0])]
    arr = np.array([x[:5] for x in fixes], dtype=float)
    ref = np.array([max(x[6], 0) for x in fixes], dtype=int)
    midnight = np.array([dates[k][0] for k in ref])
    ref_tod = np.array([dates[k][1] for k in ref])
    tod = arr[:, 0]
    day_shift = np.where(tod < ref_tod - _DAY / 2, 1.0, 0.0) - np.where(tod > ref_tod + _DAY / 2, 1.0, 0.0)
    time = midnight + day_shift * _DAY + tod
    height = arr[:, 3]
    return AntennaLog(
        time=time,
        lat=arr[:, 1],
        lon=arr[:, 2],
        height=None if np.isnan(height).all() else height,
        source=str(path),
        format="nmea",
        quality=arr[:, 4].astype(np.int64),
        quality_scheme="nmea-gga",
        lines=np.array([x[5] for x in fixes], dtype=np.int64),
        skipped={"no fix (GGA quality 0)": no_fix} if no_fix else {},
    )
