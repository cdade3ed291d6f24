"""The common antenna log every reader returns, and its validation.

An :class:`AntennaLog` is one GNSS antenna's fixes: POSIX UTC time [s], WGS-84 latitude and
longitude [deg], ellipsoidal height [m] (``None`` when the file has none), and optionally the
receiver's fix-quality code per fix, interpreted through ``quality_scheme``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError
from seatwin.geo import GeodeticOrigin, llh_to_ned_flat
from seatwin.scenario.plausibility import MAX_SPEED, first_teleport

HEIGHT_RANGE_M = (-11_000.0, 100_000.0)
"""Heights a GNSS fix can have [m] (the deepest sea to near space); beyond is a corrupt number."""

QUALITY_NAMES: dict[str, dict[int, str]] = {
    # NMEA 0183 GGA field 6.
    "nmea-gga": {
        0: "invalid",
        1: "gps",
        2: "dgps",
        3: "pps",
        4: "rtk_fixed",
        5: "rtk_float",
        6: "estimated",
        7: "manual",
        8: "simulation",
    },
    # RTKLIB .pos column Q.
    "rtklib": {1: "fix", 2: "float", 3: "sbas", 4: "dgps", 5: "single", 6: "ppp"},
    # A generic CSV's ``quality`` column: codes kept as they are.
    "csv": {},
}


def quality_name(scheme: str | None, code: int) -> str:
    """A readable name for a fix-quality ``code`` in ``scheme`` (``"code N"`` when unknown)."""
    return QUALITY_NAMES.get(scheme or "", {}).get(int(code), f"code {int(code)}")


@dataclass
class AntennaLog:
    """One antenna's GNSS fixes, as read from one file (see the module docstring)."""

    time: NDArray[np.float64]
    lat: NDArray[np.float64]
    lon: NDArray[np.float64]
    height: NDArray[np.float64] | None
    source: str
    format: str
    quality: NDArray[np.int64] | None = None
    quality_scheme: str | None = None
    lines: NDArray[np.int64] | None = None
    """Line number (1-based) in ``source`` of each fix, for error messages."""
    skipped: dict[str, int] = field(default_factory=dict)
    """Records read but not used as fixes, by reason (e.g. ``{"no fix (GGA quality 0)": 3}``)."""

    def __post_init__(self) -> None:
        self.time = np.asarray(self.time, dtype=float)
        self.lat = np.asarray(self.lat, dtype=float)
        self.lon = np.asarray(self.lon, dtype=float)
        if self.height is not None:
            self.height = np.asarray(self.height, dtype=float)
        if self.quality is not None:
            self.quality = np.asarray(self.quality, dtype=np.int64)
        if self.lines is not None:
            self.lines = np.asarray(self.lines, dtype=np.int64)
        validate_log(self)

    def __len__(self) -> int:
        return len(self.time)

    @property
    def start(self) -> float:
        return float(self.time[0])

    @property
    def end(self) -> float:
        return float(self.time[-1])

    def quality_counts(self) -> dict[str, int] | None:
        """Number of fixes per fix-quality name, or ``None`` when the file carries no quality."""
        if self.quality is None:
            return None
        codes, counts = np.unique(self.quality, return_counts=True)
        return {quality_name(self.quality_scheme, c): int(n) for c, n in zip(codes, counts)}


def _where(log: AntennaLog, i: int) -> str:
    if log.lines is not None and 0 <= i < len(log.lines):
        return f"line {int(log.lines[i])}"
    return f"fix {i + 1}"


def validate_log(log: AntennaLog) -> None:
    """Raise :class:`InputError` unless ``log`` has ≥ 2 finite, in-range fixes at strictly increasing times."""
    n = log.time.shape
    arrays = {"time": log.time, "latitude": log.lat, "longitude": log.lon}
    if log.height is not None:
        arrays["height"] = log.height
    for name, a in arrays.items():
        if a.ndim != 1 or a.shape != n:
            raise InputError(log.source, f"{name} must be a 1-D array as long as time")
    for extra, name in ((log.quality, "quality"), (log.lines, "lines")):
        if extra is not None and extra.shape != n:
            raise InputError(log.source, f"{name} must be as long as time")
    if len(log.time) < 2:
        raise InputError(log.source, f"expected at least 2 fixes, got {len(log.time)}")
    for name, a in arrays.items():
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise InputError(log.source, f"{name} is not a finite number ({a[bad[0]]!r})", where=_where(log, int(bad[0])))
    bad = np.flatnonzero(np.abs(log.lat) > 90.0)
    if bad.size:
        raise InputError(log.source, f"latitude {log.lat[bad[0]]!r} outside [-90, 90] degrees", where=_where(log, int(bad[0])))
    bad = np.flatnonzero((log.lon < -180.0) | (log.lon > 360.0))
    if bad.size:
        raise InputError(log.source, f"longitude {log.lon[bad[0]]!r} outside [-180, 360] degrees", where=_where(log, int(bad[0])))
    if log.height is not None:
        lo, hi = HEIGHT_RANGE_M
        bad = np.flatnonzero((log.height < lo) | (log.height > hi))
        if bad.size:
            raise InputError(
                log.source, f"height {float(log.height[bad[0]])!r} outside [{lo:g}, {hi:g}] m", where=_where(log, int(bad[0]))
            )
    steps = np.diff(log.time)
    bad = np.flatnonzero(steps <= 0)
    if bad.size:
        i = int(bad[0]) + 1
        kind = "duplicated" if steps[i - 1] == 0 else "decreasing (non-monotonic)"
        raise InputError(log.source, f"{kind} time {log.time[i]!r} after {log.time[i - 1]!r}", where=_where(log, i))


def check_log_motion(log: AntennaLog, max_speed: float = MAX_SPEED) -> None:
    """Raise :class:`InputError` at the first fix that implies a teleport: further from the fix before
    than ``max_speed`` [m/s] allows (the same check a scenario CSV gets when it is read,
    :func:`seatwin.scenario.plausibility.first_teleport`).

    A receiver does not put a harbour vessel 100 km away for one fix; such a fix is a corrupt
    line or a mistyped number (``-0`` for a longitude), so it is an error naming the line, never
    dropped and interpolated over: the ground truth is the reference everything else is judged by.
    """
    lon = np.unwrap(log.lon, period=360.0)
    origin = GeodeticOrigin(float(log.lat[0]), float(lon[0]), 0.0)
    north, east, _ = llh_to_ned_flat(log.lat, lon, np.zeros_like(log.lat), origin)
    jump = first_teleport(log.time, north, east, max_speed)
    if jump is None:
        return
    k = jump.index
    others = f"; {jump.count} steps between fixes in the file are that fast" if jump.count > 1 else ""
    raise InputError(
        log.source,
        f"fix at latitude {float(log.lat[k + 1])!r}, longitude {float(log.lon[k + 1])!r} is {jump.step:.4g} m from the fix at "
        f"{_where(log, k)}, {jump.dt:.3g} s before ({jump.speed:.4g} m/s, faster than max_speed {max_speed:g} m/s): "
        f"a teleport (a corrupt line or mistyped number?){others}",
        where=_where(log, k + 1),
    )
