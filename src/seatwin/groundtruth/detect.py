"""Which reader a file needs: by extension (.gpx, .pos, .csv), else by its content."""

from __future__ import annotations

import re
from pathlib import Path

from seatwin.errors import InputError
from seatwin.groundtruth.log import AntennaLog

FORMATS = ("gpx", "nmea", "rtklib", "csv")
_EXTENSIONS = {".gpx": "gpx", ".pos": "rtklib", ".csv": "csv", ".nmea": "nmea"}
_NMEA = re.compile(r"\$[A-Z]{2}(GGA|RMC|ZDA),")


def detect_format(path: str | Path) -> str:
    """``"gpx"``, ``"nmea"``, ``"rtklib"`` or ``"csv"`` for ``path`` (an :class:`InputError` if unknown)."""
    path = Path(path)
    by_ext = _EXTENSIONS.get(path.suffix.lower())
    if by_ext is not None:
        return by_ext
    try:
        with path.open("rb") as f:
            head = f.read(8192).decode("utf-8", errors="replace")
    except OSError as exc:
        raise InputError(path, f"cannot open: {exc.strerror}") from None
    if _NMEA.search(head):
        return "nmea"
    stripped = head.lstrip("\ufeff \t\r\n")
    if stripped.startswith("<?xml") or stripped.startswith("<gpx"):
        return "gpx"
    if stripped.startswith("%") and ("RTKPOST" in head or "latitude(" in head or "GPST" in head):
        return "rtklib"
    raise InputError(
        path,
        "cannot tell the file format: expected .gpx, .pos (RTKLIB), .csv, or NMEA 0183 text "
        "(.nmea/.log/.txt with $GPGGA sentences)",
    )


def read_antenna_log(path: str | Path, fmt: str | None = None) -> AntennaLog:
    """Read one antenna's log with the reader for its format (detected when ``fmt`` is ``None``)."""
    from seatwin.groundtruth.read_csv import read_csv_log
    from seatwin.groundtruth.read_gpx import read_gpx
    from seatwin.groundtruth.read_nmea import read_nmea
    from seatwin.groundtruth.read_rtklib import read_rtklib_pos

    path = Path(path)
    if not path.is_file():
        raise InputError(path, "no such file" if not path.exists() else "not a regular file")
    fmt = fmt or detect_format(path)
    readers = {"gpx": read_gpx, "nmea": read_nmea, "rtklib": read_rtklib_pos, "csv": read_csv_log}
    if fmt not in readers:
        raise InputError(path, f"unknown format {fmt!r}, expected one of {', '.join(FORMATS)}")
    return readers[fmt](path)
