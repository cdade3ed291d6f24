"""Synthetic antenna logs for the ground-truth tests: a known turning vessel near Ravnkloa,
its bow and stern antennas, noise, and writers for every supported file format."""

from __future__ import annotations

import calendar
from dataclasses import dataclass

import numpy as np

from seatwin.geo import GeodeticOrigin, ned_to_llh_exact
from seatwin.rng import frame_rng

ORIGIN = GeodeticOrigin(63.4346, 10.3977, 0.0)
T0 = float(calendar.timegm((2020, 9, 15, 10, 0, 0)))
BASELINE = 2.93
DURATION = 80.0


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


# ---------------------------------------------------------------- writers (the library's)

from seatwin.groundtruth.log_writers import (  # noqa: E402
    GPS_MINUS_UTC,
    WRITERS,
    gga,
    rmc,
    write_csv,
    write_gpx,
    write_nmea,
    write_pos,
)

__all__ = ["GPS_MINUS_UTC", "WRITERS", "gga", "rmc", "write_csv", "write_gpx", "write_nmea", "write_pos"]
