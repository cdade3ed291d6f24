"""Writers of GNSS antenna logs in every format the ground-truth readers take (GPX, NMEA GGA+RMC, RTKLIB .pos, CSV).

They make the shipped example logs (:mod:`seatwin.groundtruth.examples`) and the tests' synthetic
logs; their output is what a receiver of that kind writes (an eTrex GPX track, Hemisphere-style
NMEA with checksums, RTKPOST ``.pos`` in GPST or UTC, calendar or GPS week/seconds).
"""

from __future__ import annotations

import datetime as dt
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from seatwin.groundtruth.read_nmea import nmea_checksum

GPS_MINUS_UTC = 18.0
"""GPS − UTC [s] in the years of the examples (leap seconds since 1980)."""


def _iso(t: float) -> str:
    return dt.datetime.fromtimestamp(t, dt.UTC).strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"


def write_gpx(path: Path, t: ArrayLike, lat: ArrayLike, lon: ArrayLike, h: ArrayLike) -> Path:
    """A GPX 1.1 track (eTrex style) of the fixes."""
    pts = "\n".join(
        f'      <trkpt lat="{a:.9f}" lon="{b:.9f}">\n        <ele>{c:.3f}</ele>\n        <time>{_iso(s)}</time>\n      </trkpt>'
        for s, a, b, c in zip(t, lat, lon, h)
    )
    path.write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<gpx version="1.1" creator="eTrex 10" xmlns="http://www.topografix.com/GPX/1/1">\n'
        f"  <trk>\n    <name>test</name>\n    <trkseg>\n{pts}\n    </trkseg>\n  </trk>\n</gpx>\n"
    )
    return path


def _nmea(body: str) -> str:
    return f"${body}*{nmea_checksum(body):02X}"


def _ddmm(value: float, deg_digits: int, pos: str, neg: str) -> tuple[str, str]:
    a = abs(value)
    d = int(a)
    m = (a - d) * 60.0
    return f"{d:0{deg_digits}d}{m:010.7f}", pos if value >= 0 else neg


def gga(t: float, lat: float, lon: float, h: float, quality: int = 4, talker: str = "GP") -> str:
    """One GGA sentence (geoid separation 39 m, as near Trondheim)."""
    tod = dt.datetime.fromtimestamp(round(t, 2), dt.UTC)
    hms = f"{tod:%H%M%S}.{tod.microsecond // 10000:02d}"
    la, ns = _ddmm(lat, 2, "N", "S")
    lo, ew = _ddmm(lon, 3, "E", "W")
    sep = 39.0
    return _nmea(f"{talker}GGA,{hms},{la},{ns},{lo},{ew},{quality},12,0.8,{h - sep:.3f},M,{sep:.3f},M,1.0,0001")


def rmc(t: float, lat: float, lon: float) -> str:
    """One RMC sentence (it carries the date GGA lacks)."""
    tod = dt.datetime.fromtimestamp(round(t, 2), dt.UTC)
    hms = f"{tod:%H%M%S}.{tod.microsecond // 10000:02d}"
    la, ns = _ddmm(lat, 2, "N", "S")
    lo, ew = _ddmm(lon, 3, "E", "W")
    return _nmea(f"GPRMC,{hms},A,{la},{ns},{lo},{ew},5.8,30.0,{tod:%d%m%y},,,R")


def write_nmea(
    path: Path, t: ArrayLike, lat: ArrayLike, lon: ArrayLike, h: ArrayLike, quality: Sequence[int] | None = None
) -> Path:
    """NMEA 0183: RMC + GGA per fix (``quality``: GGA fix quality, default 4 = RTK fixed), GSA every fifth."""
    q = np.full(len(t), 4) if quality is None else quality
    lines = []
    for k, (s, a, b, c) in enumerate(zip(t, lat, lon, h)):
        lines.append(rmc(s, a, b))
        lines.append(gga(s, a, b, c, int(q[k])))
        if k % 5 == 0:
            lines.append(_nmea("GPGSA,A,3,01,02,03,04,05,06,,,,,,,1.5,0.8,1.2"))
    path.write_text("\r\n".join(lines) + "\r\n")
    return path


def write_pos(
    path: Path,
    t_utc: ArrayLike,
    lat: ArrayLike,
    lon: ArrayLike,
    h: ArrayLike,
    q: Sequence[int] | None = None,
    week_tow: bool = False,
    system: str = "GPST",
) -> Path:
    """An RTKLIB ``.pos`` solution (``system`` GPST or UTC time; calendar or GPS week/seconds; ``q`` fix quality)."""
    q = np.ones(len(t_utc), int) if q is None else q
    head = [
        "% program   : RTKPOST ver.2.4.3 b34",
        "% pos mode  : Kinematic",
        "% (lat/lon/height=WGS84/ellipsoidal,Q=1:fix,2:float,3:sbas,4:dgps,5:single,6:ppp,ns=# of satellites)",
        f"%  {system:<22}latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   sde(m)   sdu(m)"
        "  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio",
    ]
    rows = []
    for s, a, b, c, qq in zip(t_utc, lat, lon, h, q):
        g = s + GPS_MINUS_UTC if system == "GPST" else s
        if week_tow:
            x = g - 315_964_800.0
            week = int(x // 604_800)
            ts = f"{week:4d} {x - week * 604_800:11.3f}"
        else:
            d = dt.datetime.fromtimestamp(round(g, 3), dt.UTC)
            ts = f"{d:%Y/%m/%d %H:%M:%S}.{d.microsecond // 1000:03d}"
        rows.append(
            f"{ts} {a:14.9f} {b:14.9f} {c:10.4f} {int(qq):3d}  12   0.0050   0.0040   0.0110"
            "  -0.0010   0.0010  -0.0030   1.00  999.9"
        )
    path.write_text("\n".join(head + rows) + "\n")
    return path


def write_csv(path: Path, t: ArrayLike, lat: ArrayLike, lon: ArrayLike, h: ArrayLike, iso: bool = False) -> Path:
    """A ``time,lat,lon,height`` CSV (POSIX seconds, or ISO 8601 UTC with ``iso``)."""
    rows = ["time,lat,lon,height"]
    for s, a, b, c in zip(t, lat, lon, h):
        rows.append(f"{_iso(s) if iso else repr(float(s))},{a:.10f},{b:.10f},{c:.4f}")
    path.write_text("\n".join(rows) + "\n")
    return path


WRITERS = {
    "gpx": (write_gpx, ".gpx"),
    "nmea": (write_nmea, ".nmea"),
    "rtklib": (write_pos, ".pos"),
    "csv": (write_csv, ".csv"),
}
"""Format name → (writer, file suffix)."""
