"""RTKLIB solution (``.pos``) reader, llh format, latitude/longitude in degrees or d m s.

Times are ``YYYY/MM/DD HH:MM:SS.sss`` or GPS ``week seconds-of-week``, in the time system
named by the column header line (``% GPST …``, ``% UTC …`` or ``% JST …``; GPST when the
file has no header, RTKLIB's default). GPST is converted to UTC with the leap-second table.
The ``Q`` column (1 fix, 2 float, 3 sbas, 4 dgps, 5 single, 6 ppp) is kept as fix quality.
"""

from __future__ import annotations

import calendar
import re
from pathlib import Path

import numpy as np

from seatwin.errors import InputError, parse_finite, read_text
from seatwin.groundtruth.gpstime import GPS_EPOCH_POSIX, gps_week_to_posixlike, gpst_to_utc
from seatwin.groundtruth.log import AntennaLog

_DATETIME = re.compile(r"(\d{4})/(\d{1,2})/(\d{1,2})", re.ASCII)
_CLOCK = re.compile(r"(\d{1,2}):(\d{2}):(\d{2}(?:\.\d*)?)", re.ASCII)
_BLANKS = re.compile(r"[ \t]+")


def _header_layout(header: str, path: Path, line_no: int) -> tuple[str, bool]:
    """(time system, dms?) from the column header line ``%  GPST  latitude(deg) …``."""
    tokens = header.lstrip("%").split()
    system = tokens[0].upper() if tokens else ""
    if system not in ("GPST", "UTC", "JST"):
        raise InputError(
            path, f"unknown time system {tokens[0] if tokens else ''!r}, expected GPST, UTC or JST", where=f"line {line_no}"
        )
    low = header.lower()
    if "latitude(deg)" in low:
        return system, False
    if "latitude(d" in low:
        return system, True
    raise InputError(path, "expected RTKLIB llh output (latitude/longitude/height), not xyz-ecef or enu", where=f"line {line_no}")


def _number(tok: str, name: str, path: Path, line_no: int) -> float:
    return parse_finite(tok, path, name, line_no)


def _time(tok0: str, tok1: str, path: Path, line_no: int) -> float:
    """POSIX-like seconds of the calendar reading (in the file's time system)."""
    d, c = _DATETIME.fullmatch(tok0), _CLOCK.fullmatch(tok1)
    if d and c:
        y, mo, dd = (int(g) for g in d.groups())
        h, mi, s = int(c.group(1)), int(c.group(2)), float(c.group(3))
        if not (1 <= mo <= 12 and 1 <= dd <= 31 and h < 24 and mi < 60 and s < 61):
            raise InputError(path, f"invalid date/time {tok0} {tok1}", where=f"line {line_no}")
        return calendar.timegm((y, mo, dd, 0, 0, 0)) + h * 3600.0 + mi * 60.0 + s
    if re.fullmatch(r"[0-9]{1,5}", tok0):
        tow = _number(tok1, "GPS seconds of week", path, line_no)
        if not 0.0 <= tow < 604_800.0:
            raise InputError(path, f"GPS seconds of week {tok1} outside [0, 604800)", where=f"line {line_no}")
        return float(gps_week_to_posixlike(int(tok0), tow))
    raise InputError(
        path, f"expected time 'YYYY/MM/DD HH:MM:SS.sss' or 'WEEK SECONDS', got {tok0 + ' ' + tok1!r}", where=f"line {line_no}"
    )


def _dms(toks: list[str], name: str, path: Path, line_no: int) -> float:
    d, m, s = (_number(t, name, path, line_no) for t in toks)
    sign = -1.0 if toks[0].startswith("-") else 1.0
    return sign * (abs(d) + m / 60.0 + s / 3600.0)


def read_rtklib_pos(path: str | Path) -> AntennaLog:
    """Read an RTKLIB ``.pos`` solution file (llh) into an :class:`AntennaLog` (UTC times)."""
    path = Path(path)
    # Lines end at LF (CR LF) only and fields are separated by ASCII blanks: Unicode line or space
    # characters (a no-break space after a number) stay inside a field and make it an error.
    text_lines = read_text(path, "an RTKLIB .pos file").split("\n")
    system, dms = "GPST", False
    rows: list[tuple[float, float, float, float, int, int]] = []
    for line_no, raw in enumerate(text_lines, start=1):
        line = raw.strip(" \t\r")
        if not line:
            continue
        if line.startswith("%"):
            body = line.lstrip("%").split()
            if body and body[0].upper() in ("GPST", "UTC", "JST") or "latitude(" in line.lower() or "ecef" in line.lower():
                system, dms = _header_layout(line, path, line_no)
            continue
        toks = _BLANKS.split(line)
        need = 2 + (6 if dms else 2) + 2  # time, lat, lon, height, Q
        if len(toks) < need:
            raise InputError(
                path, f"expected at least {need} columns (time, lat, lon, height, Q), got {len(toks)}", where=f"line {line_no}"
            )
        t = _time(toks[0], toks[1], path, line_no)
        if dms:
            lat, lon = _dms(toks[2:5], "latitude", path, line_no), _dms(toks[5:8], "longitude", path, line_no)
            k = 8
        else:
            lat, lon = _number(toks[2], "latitude", path, line_no), _number(toks[3], "longitude", path, line_no)
            k = 4
        h = _number(toks[k], "height", path, line_no)
        if not re.fullmatch(r"[0-9]", toks[k + 1]):
            raise InputError(path, f"expected quality Q 1–6, got {toks[k + 1]!r}", where=f"line {line_no}")
        rows.append((t, lat, lon, h, int(toks[k + 1]), line_no))
    if not rows:
        raise InputError(path, "no solution lines in the RTKLIB .pos file")
    arr = np.array(rows, dtype=float)
    t = arr[:, 0]
    early = np.flatnonzero(t < GPS_EPOCH_POSIX)
    if early.size:
        raise InputError(path, "time before the GPS epoch 1980-01-06", where=f"line {int(arr[early[0], 5])}")
    if system == "GPST":
        t = gpst_to_utc(t)
    elif system == "JST":
        t = t - 9 * 3600.0
    return AntennaLog(
        time=t,
        lat=arr[:, 1],
        lon=arr[:, 2],
        height=arr[:, 3],
        source=str(path),
        format=f"rtklib-pos ({system})",
        quality=arr[:, 4].astype(np.int64),
        quality_scheme="rtklib",
        lines=arr[:, 5].astype(np.int64),
    )
