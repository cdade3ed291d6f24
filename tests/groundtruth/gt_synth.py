"""Synthetic antenna logs for the ground-truth tests: a known turning vessel near Ravnkloa,
its bow and stern antennas, noise, and writers for every supported file format."""

from __future__ import annotations

import calendar
import datetime as dt
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from seatwin.geo import GeodeticOrigin, ned_to_llh_exact
from seatwin.groundtruth.read_nmea import nmea_checksum
from seatwin.rng import frame_rng

ORIGIN = GeodeticOrigin(63.4346, 10.3977, 0.0)
T0 = float(calendar.timegm((2020, 9, 15, 10, 0, 0)))
BASELINE = 2.93
DURATION = 80.0
GPS_MINUS_UTC = 18.0


@dataclass(frozen=True)
class Truth:
    """The true trajectory, sampled densely (1 ms) and interpolated."""

    time: np.ndarray
    north: np.ndarray
    east: np.ndarray
    heading: np.ndarray  # unwrapped, rad

    def at(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return (np.interp(t, self.time, self.north), np.interp(t, self.time, self.east), np.interp(t, self.time, self.heading))


def turning_vessel(t0: float = T0, duration: float = DURATION, speed: float = 3.0) -> Truth:
    """Straight at 30°, a 3°/s starboard turn from 20 s to 50 s (to 120°), then straight again."""
    dt_ = 1e-3
    tau = np.arange(0.0, duration + dt_ / 2, dt_)
    rate = np.radians(3.0)
    heading = np.radians(30.0) + rate * np.clip(tau - 20.0, 0.0, 30.0)
    vn, ve = speed * np.cos(heading), speed * np.sin(heading)
    north = -100.0 + np.concatenate([[0.0], np.cumsum(0.5 * (vn[1:] + vn[:-1]) * dt_)])
    east = 50.0 + np.concatenate([[0.0], np.cumsum(0.5 * (ve[1:] + ve[:-1]) * dt_)])
    return Truth(t0 + tau, north, east, heading)


def antenna_llh(
    truth: Truth, t: np.ndarray, along: float, sigma: float, seed: int, stream: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """LLH of an antenna ``along`` metres forward of the reference point, with N/E noise ``sigma``."""
    n, e, psi = truth.at(t)
    rng = frame_rng(seed, stream, 0)
    n = n + along * np.cos(psi) + sigma * rng.standard_normal(len(t))
    e = e + along * np.sin(psi) + sigma * rng.standard_normal(len(t))
    lat, lon, h = ned_to_llh_exact(n, e, np.full(len(t), -40.0), ORIGIN)
    return lat, lon, h


def sample_times(t0: float, duration: float, rate_hz: float, offset: float = 0.0) -> np.ndarray:
    return t0 + offset + np.arange(0.0, duration - offset + 1e-9, 1.0 / rate_hz)


# ---------------------------------------------------------------- writers


def _iso(t: float) -> str:
    return dt.datetime.fromtimestamp(t, dt.UTC).strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"


def write_gpx(path: Path, t, lat, lon, h) -> Path:
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
    tod = dt.datetime.fromtimestamp(round(t, 2), dt.UTC)
    hms = f"{tod:%H%M%S}.{tod.microsecond // 10000:02d}"
    la, ns = _ddmm(lat, 2, "N", "S")
    lo, ew = _ddmm(lon, 3, "E", "W")
    sep = 39.0
    return _nmea(f"{talker}GGA,{hms},{la},{ns},{lo},{ew},{quality},12,0.8,{h - sep:.3f},M,{sep:.3f},M,1.0,0001")


def rmc(t: float, lat: float, lon: float) -> str:
    tod = dt.datetime.fromtimestamp(round(t, 2), dt.UTC)
    hms = f"{tod:%H%M%S}.{tod.microsecond // 10000:02d}"
    la, ns = _ddmm(lat, 2, "N", "S")
    lo, ew = _ddmm(lon, 3, "E", "W")
    return _nmea(f"GPRMC,{hms},A,{la},{ns},{lo},{ew},5.8,30.0,{tod:%d%m%y},,,R")


def write_nmea(path: Path, t, lat, lon, h, quality=None) -> Path:
    q = np.full(len(t), 4) if quality is None else quality
    lines = []
    for k, (s, a, b, c) in enumerate(zip(t, lat, lon, h)):
        lines.append(rmc(s, a, b))
        lines.append(gga(s, a, b, c, int(q[k])))
        if k % 5 == 0:
            lines.append(_nmea("GPGSA,A,3,01,02,03,04,05,06,,,,,,,1.5,0.8,1.2"))
    path.write_text("\r\n".join(lines) + "\r\n")
    return path


def write_pos(path: Path, t_utc, lat, lon, h, q=None, week_tow: bool = False, system: str = "GPST") -> Path:
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


def write_csv(path: Path, t, lat, lon, h, iso: bool = False) -> Path:
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
