"""GPX track reader (``gpxpy``): every track point of every track and segment, in file order."""

from __future__ import annotations

import datetime as dt
import re
from pathlib import Path

import numpy as np

from seatwin.errors import InputError, parse_finite, read_text
from seatwin.groundtruth.log import AntennaLog

_TRKPT = re.compile(r"<(?:\w+:)?trkpt\b")
_TRKPT_TAG = re.compile(r"<(?:\w+:)?trkpt\b([^>]*)>")
_LATLON = re.compile(r"\b(lat|lon)\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
_ELE = re.compile(r"<(?:\w+:)?ele>([^<]*)<")


def _check_numbers(text: str, path: Path) -> None:
    """Track-point latitudes, longitudes and elevations must be ASCII decimal numbers as GPX's
    ``xsd:decimal`` says (``float()``, which gpxpy uses, also takes ``nan``, ``1_0`` or a no-break space)."""
    names = {"lat": "latitude", "lon": "longitude"}
    for m in _TRKPT_TAG.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        for a in _LATLON.finditer(m.group(1)):
            parse_finite(a.group(2) if a.group(2) is not None else a.group(3), path, names[a.group(1)], line)
    for m in _ELE.finditer(text):
        parse_finite(m.group(1).strip(" \t\r\n"), path, "elevation", text.count("\n", 0, m.start()) + 1)


def _point_lines(text: str) -> list[int]:
    """Line number of each ``<trkpt`` opening tag, in document order."""
    return [text.count("\n", 0, m.start()) + 1 for m in _TRKPT.finditer(text)]


def _line_of(text: str, token: str) -> str | None:
    i = text.find(token)
    return None if i < 0 or not token else f"line {text.count(chr(10), 0, i) + 1}"


def read_gpx(path: str | Path) -> AntennaLog:
    """Read a GPX file's track points; times in the file are UTC (a time without zone is taken as UTC)."""
    import gpxpy
    import gpxpy.gpx

    path = Path(path)
    text = read_text(path, "a GPX file")
    _check_numbers(text, path)
    try:
        gpx = gpxpy.parse(text)
    except gpxpy.gpx.GPXXMLSyntaxException as exc:
        msg = " ".join(str(exc).removeprefix("Error parsing XML: ").split())  # the parser's message may span lines
        m = re.search(r"line (\d+)", msg)
        raise InputError(path, f"not well-formed XML: {msg}", where=f"line {m.group(1)}" if m else None) from None
    except gpxpy.gpx.GPXException as exc:
        msg = str(exc)
        m = re.search(r"\.\.\. (.*) \(", msg)
        where = _line_of(text, f'"{m.group(1)}"') or _line_of(text, f">{m.group(1)}<") if m else None
        raise InputError(path, f"malformed GPX: {msg}", where=where) from None
    points = [p for trk in gpx.tracks for seg in trk.segments for p in seg.points]
    if not points:
        raise InputError(path, "no track points (<trkpt>) in the GPX file")
    lines = _point_lines(text)
    if len(lines) != len(points):  # should not happen; fall back to point numbers
        lines = []
    where = lambda i: f"line {lines[i]}" if lines else f"track point {i + 1}"  # noqa: E731
    time = np.empty(len(points))
    for i, p in enumerate(points):
        if p.time is None:
            raise InputError(path, "track point without a valid <time> (expected ISO 8601 UTC)", where=where(i))
        t = p.time if p.time.tzinfo is not None else p.time.replace(tzinfo=dt.UTC)
        time[i] = t.timestamp()
    elev = [p.elevation for p in points]
    n_missing = sum(e is None for e in elev)
    if 0 < n_missing < len(points):
        i = next(i for i, e in enumerate(elev) if e is None)
        raise InputError(path, "track point without <ele> while others have one", where=where(i))
    height = None if n_missing else np.array(elev, dtype=float)
    return AntennaLog(
        time=time,
        lat=np.array([p.latitude for p in points], dtype=float),
        lon=np.array([p.longitude for p in points], dtype=float),
        height=height,
        source=str(path),
        format="gpx",
        lines=np.array(lines, dtype=np.int64) if lines else None,
    )
