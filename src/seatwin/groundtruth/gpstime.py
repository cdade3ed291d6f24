"""GPS time ↔ UTC: the GPS epoch, GPS week/seconds, and the leap-second table.

GPS time (GPST) runs without leap seconds from 1980-01-06 00:00:00 UTC; UTC = GPST − ΔLS,
with ΔLS = 18 s since 2017-01-01. A "GPST calendar" time such as RTKLIB's
``2020/09/15 10:00:18.000`` is handled here as POSIX-like seconds of that calendar reading.
"""

from __future__ import annotations

import calendar

import numpy as np
from numpy.typing import ArrayLike, NDArray

GPS_EPOCH_POSIX = 315_964_800.0
"""1980-01-06 00:00:00 UTC as POSIX seconds."""
SECONDS_PER_WEEK = 604_800.0

# (first UTC day the offset applies, GPS − UTC [s]). Source: IERS Bulletin C; none since 2017.
LEAP_SECONDS: tuple[tuple[tuple[int, int, int], int], ...] = (
    ((1980, 1, 6), 0),
    ((1981, 7, 1), 1),
    ((1982, 7, 1), 2),
    ((1983, 7, 1), 3),
    ((1985, 7, 1), 4),
    ((1988, 1, 1), 5),
    ((1990, 1, 1), 6),
    ((1991, 1, 1), 7),
    ((1992, 7, 1), 8),
    ((1993, 7, 1), 9),
    ((1994, 7, 1), 10),
    ((1996, 1, 1), 11),
    ((1997, 7, 1), 12),
    ((1999, 1, 1), 13),
    ((2006, 1, 1), 14),
    ((2009, 1, 1), 15),
    ((2012, 7, 1), 16),
    ((2015, 7, 1), 17),
    ((2017, 1, 1), 18),
)

_UTC_STARTS = np.array([calendar.timegm((y, m, d, 0, 0, 0)) for (y, m, d), _ in LEAP_SECONDS], dtype=float)
_OFFSETS = np.array([s for _, s in LEAP_SECONDS], dtype=float)
_GPST_STARTS = _UTC_STARTS + _OFFSETS


def gps_minus_utc(gpst_posixlike: ArrayLike) -> NDArray[np.float64]:
    """ΔLS = GPST − UTC [s] in effect at the given GPST calendar time(s) (POSIX-like seconds)."""
    t = np.asarray(gpst_posixlike, dtype=float)
    if np.any(t < _GPST_STARTS[0]):
        raise ValueError("GPS time before the GPS epoch 1980-01-06")
    return _OFFSETS[np.searchsorted(_GPST_STARTS, t, side="right") - 1]


def gpst_to_utc(gpst_posixlike: ArrayLike) -> NDArray[np.float64]:
    """GPST calendar time (POSIX-like seconds) → POSIX UTC seconds."""
    t = np.asarray(gpst_posixlike, dtype=float)
    return t - gps_minus_utc(t)


def gps_week_to_posixlike(week: ArrayLike, seconds_of_week: ArrayLike) -> NDArray[np.float64]:
    """GPS week number (full, not modulo 1024) and seconds of week → GPST calendar seconds."""
    return GPS_EPOCH_POSIX + np.asarray(week, float) * SECONDS_PER_WEEK + np.asarray(seconds_of_week, float)


def gps_week_to_utc(week: ArrayLike, seconds_of_week: ArrayLike) -> NDArray[np.float64]:
    """GPS week and seconds of week → POSIX UTC seconds (leap seconds removed)."""
    return gpst_to_utc(gps_week_to_posixlike(week, seconds_of_week))
