"""Put every antenna on one common clock: a grid of multiples of 1/rate over the overlap.

Positions are interpolated linearly (the thesis interpolates the GNSS data to 10 Hz so
bow and stern fixes are synchronous); the fix quality is taken from the nearest fix. Grid
samples that fall between two fixes further apart than ``max_gap`` seconds are marked, not
dropped.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.geo.angles import wrap_to_180
from seatwin.groundtruth.log import AntennaLog

DEFAULT_RATE_HZ = 10.0
DEFAULT_MAX_GAP_S = 5.0


@dataclass(frozen=True)
class ResampledLog:
    """One antenna on the common clock."""

    log: AntennaLog
    time: NDArray[np.float64]
    lat: NDArray[np.float64]
    lon: NDArray[np.float64]
    height: NDArray[np.float64] | None
    quality: NDArray[np.int64] | None
    gap: NDArray[np.bool_]
    """True where the sample is interpolated across a gap between fixes longer than ``max_gap``."""


def check_rate(rate_hz: float) -> None:
    """A :class:`ParameterError` naming ``rate_hz`` unless it is a positive number of Hz."""
    if not np.isfinite(rate_hz) or rate_hz <= 0:
        raise ParameterError("rate_hz", f"the rate must be a positive number of Hz, got {rate_hz!r}")


def common_clock(logs: Sequence[AntennaLog], rate_hz: float = DEFAULT_RATE_HZ) -> NDArray[np.float64]:
    """Times k / rate (integer k) within the interval every log covers; an :class:`InputError` if none."""
    check_rate(rate_hz)
    if not logs:
        raise InputError(None, "no antenna logs to resample")
    start = max(log.start for log in logs)
    end = min(log.end for log in logs)
    names = ", ".join(f"{log.source} [{log.start:.3f}, {log.end:.3f}]" for log in logs)
    if end <= start:
        raise InputError(None, f"the antenna logs have no common time interval: {names}")
    k0 = int(np.ceil(start * rate_hz - 1e-6))
    k1 = int(np.floor(end * rate_hz + 1e-6))
    if k1 - k0 + 1 < 2:
        raise InputError(
            None, f"the common interval [{start:.3f}, {end:.3f}] s holds fewer than 2 samples at {rate_hz} Hz: {names}"
        )
    return np.arange(k0, k1 + 1, dtype=np.float64) / rate_hz


def resample_log(log: AntennaLog, time: NDArray[np.float64], max_gap: float = DEFAULT_MAX_GAP_S) -> ResampledLog:
    """Interpolate ``log`` at ``time`` (which must lie within the log's span)."""
    t = np.clip(time, log.start, log.end)
    lon = np.unwrap(log.lon, period=360.0)
    right = np.clip(np.searchsorted(log.time, t, side="right"), 1, len(log) - 1)
    left = right - 1
    spacing = log.time[right] - log.time[left]
    on_fix = (t == log.time[left]) | (t == log.time[right])
    gap = (spacing > max_gap) & ~on_fix
    quality = None
    if log.quality is not None:
        nearest = np.where(t - log.time[left] <= log.time[right] - t, left, right)
        quality = log.quality[nearest]
    lon_i = np.interp(t, log.time, lon)
    return ResampledLog(
        log=log,
        time=np.asarray(time, float),
        lat=np.interp(t, log.time, log.lat),
        lon=np.asarray(wrap_to_180(lon_i), float),
        height=None if log.height is None else np.interp(t, log.time, log.height),
        quality=quality,
        gap=gap,
    )
