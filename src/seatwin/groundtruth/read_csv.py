"""Generic CSV reader: ``time, lat, lon[, height][, quality]``.

With a header line, columns are found by name (case-insensitive): time ``time|t|timestamp|
posix|utc``, latitude ``lat|latitude``, longitude ``lon|lng|long|longitude``, height
``height|h|alt|altitude|ele|elevation`` and ``quality`` (integer fix-quality code); without a
header (the first field is a number or a date), columns are positional: time, lat, lon[, height].
Times are POSIX seconds or ISO 8601 (a time without zone is taken as UTC). Lat/lon in degrees.
"""

from __future__ import annotations

import datetime as dt
from pathlib import Path

import numpy as np

from seatwin.errors import NUMBER, InputError, parse_csv, parse_finite, read_text
from seatwin.groundtruth.log import AntennaLog

_NAMES = {
    "time": ("time", "t", "timestamp", "posix", "utc", "time_s", "timeinsecondsposix"),
    "lat": ("lat", "latitude", "lat_deg"),
    "lon": ("lon", "lng", "long", "longitude", "lon_deg"),
    "height": ("height", "h", "alt", "altitude", "ele", "elevation", "height_m"),
    "quality": ("quality", "q", "fix", "fix_quality"),
}


def _parse_time(text: str, path: Path, line: int) -> float:
    """POSIX seconds (ASCII digits) or an ISO 8601 time (UTC when it has no zone)."""
    s = text.strip(" \t")
    if NUMBER.fullmatch(s) is None and s.isascii():
        try:
            t = dt.datetime.fromisoformat(s)
            return (t if t.tzinfo is not None else t.replace(tzinfo=dt.UTC)).timestamp()
        except (ValueError, OverflowError):
            pass
    try:
        return parse_finite(s, path, "time", line)
    except InputError:
        raise InputError(
            path, f"expected POSIX seconds or an ISO 8601 time for time, got {text!r}", where=f"line {line}"
        ) from None


def _looks_like_data(cell: str) -> bool:
    try:
        _parse_time(cell, Path(), 0)
        return True
    except InputError:
        return False


def read_csv_log(path: str | Path) -> AntennaLog:
    """Read a generic CSV antenna log (see the module docstring)."""
    path = Path(path)
    rows = parse_csv(path, read_text(path, "a CSV file"), list)
    numbered = [(i, r) for i, r in enumerate(rows, start=1) if r and any(c.strip() for c in r)]
    if not numbered:
        raise InputError(path, "empty file, expected time, lat, lon[, height] lines")
    first_no, first = numbered[0]
    if _looks_like_data(first[0]):
        width = len(first)
        if width not in (3, 4):
            raise InputError(
                path,
                f"without a header line expected 3 or 4 columns (time, lat, lon[, height]), got {width}",
                where=f"line {first_no}",
            )
        cols = {"time": 0, "lat": 1, "lon": 2} | ({"height": 3} if width == 4 else {})
        header = ["time", "lat", "lon", "height"][:width]
        data = numbered
    else:
        header = [h.strip().lower() for h in first]
        width = len(header)
        cols = {}
        for key, names in _NAMES.items():
            hits = [i for i, h in enumerate(header) if h in names]
            if len(hits) > 1:
                raise InputError(path, f"more than one {key} column: {[first[i] for i in hits]}", where=f"line {first_no}")
            if hits:
                cols[key] = hits[0]
        missing = [k for k in ("time", "lat", "lon") if k not in cols]
        if missing:
            raise InputError(
                path,
                f"no {', '.join(missing)} column in header {first}; expected e.g. time,lat,lon,height",
                where=f"line {first_no}",
            )
        data = numbered[1:]
    if len(data) < 2:
        raise InputError(path, f"expected at least 2 data lines, got {len(data)}")
    n = len(data)
    out = {k: np.empty(n) for k in cols}
    lines = np.empty(n, dtype=np.int64)
    for j, (line_no, row) in enumerate(data):
        if len(row) != width:
            raise InputError(path, f"expected {width} fields, got {len(row)}", where=f"line {line_no}")
        lines[j] = line_no
        for key, i in cols.items():
            if key == "time":
                out[key][j] = _parse_time(row[i], path, line_no)
                continue
            v = parse_finite(row[i], path, header[i], line_no)
            if key == "quality" and v != int(v):
                raise InputError(
                    path, f"expected an integer quality code for {header[i]}, got {row[i]!r}", where=f"line {line_no}"
                )
            out[key][j] = v
    return AntennaLog(
        time=out["time"],
        lat=out["lat"],
        lon=out["lon"],
        height=out.get("height"),
        source=str(path),
        format="csv",
        quality=out["quality"].astype(np.int64) if "quality" in out else None,
        quality_scheme="csv" if "quality" in out else None,
        lines=lines,
    )
