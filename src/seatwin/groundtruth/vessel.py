"""One vessel's 3-DOF ground truth from its one or two GNSS antennas on the common clock.

Two antennas (bow, stern): position = their midpoint, heading by eq. 3.6, and ε_gnss
(eq. 3.7) against the hand-measured baseline as a per-sample quality signal; samples with
ε_gnss above the threshold are *flagged*, never dropped. One antenna: heading = course over
ground from the velocity, flagged where the speed is too low for a course to mean anything
(the heading there is interpolated between the nearest usable courses).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.geo import GeodeticOrigin, llh_to_ned_flat, unwrap, wrap_to_pi
from seatwin.geo.flat_earth import Meridian
from seatwin.groundtruth.equations import (
    antenna_distance,
    antenna_midpoint,
    course_over_ground,
    gnss_baseline_error,
    heading_from_antennas,
    velocity_central,
)
from seatwin.groundtruth.resample import ResampledLog
from seatwin.scenario.model import Trajectory

KNOWN_BASELINES_M: dict[str, float] = {"finn": 2.93, "havfruen": 2.01}
"""Hand-measured bow–stern antenna distances |Q_r| of the thesis vessels (§3.3.2)."""
DEFAULT_EPS_THRESHOLD_M = 0.5
DEFAULT_SMOOTH_S = 1.0
DEFAULT_MIN_COG_SPEED = 0.5

FLAG_EPS = 1
"""ε_gnss above the threshold (two antennas)."""
FLAG_GAP = 2
"""Interpolated across a gap in an antenna's fixes longer than ``max_gap``."""
FLAG_LOW_SPEED = 4
"""Course over ground at a speed below ``min_cog_speed`` (one antenna): heading interpolated."""
FLAG_NAMES = {FLAG_EPS: "eps_gnss", FLAG_GAP: "gap", FLAG_LOW_SPEED: "low_speed_cog"}

HEADING_ANTENNAS = "antennas (eq. 3.6)"
HEADING_COG = "course over ground"


@dataclass(frozen=True)
class VesselSpec:
    """A vessel and its antenna log files: bow then stern (two antennas) or one file.

    ``baseline_m`` is the hand-measured bow–stern distance |Q_r| (None: a known thesis vessel's,
    else the median measured distance). The command line's ``NAME=BOW,STERN[,BASELINE_M]`` is
    parsed by :func:`seatwin.cli.parsing.parse_vessel`.
    """

    name: str
    files: tuple[Path, ...]
    baseline_m: float | None = None

    def __post_init__(self) -> None:
        if not self.name or not 1 <= len(self.files) <= 2:
            raise ParameterError(
                "vessels", f"a vessel needs a name and one or two antenna files, got {self.name!r} with {len(self.files)}"
            )
        if self.baseline_m is not None and not (np.isfinite(self.baseline_m) and self.baseline_m > 0):
            raise ParameterError(
                "vessels", f"vessel {self.name!r}: baseline must be a positive number of metres, got {self.baseline_m!r}"
            )


@dataclass
class VesselGroundTruth:
    """The ground truth of one vessel on the common clock, with its per-sample quality."""

    name: str
    time: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    heading: NDArray[np.float64]
    v_north: NDArray[np.float64]
    v_east: NDArray[np.float64]
    heading_source: str
    flags: NDArray[np.uint8]
    antennas: list[ResampledLog]
    eps_gnss: NDArray[np.float64] | None = None
    rel_north: NDArray[np.float64] | None = None
    """Bow − stern north [m] (two antennas)."""
    rel_east: NDArray[np.float64] | None = None
    baseline_m: float | None = None
    baseline_source: str | None = None
    eps_threshold_m: float | None = None
    settings: dict[str, float] = field(default_factory=dict)

    def trajectory(self) -> Trajectory:
        return Trajectory(self.time, self.north, self.east, self.heading, source=self.name)


def _ned(r: ResampledLog, origin: GeodeticOrigin, meridian: Meridian) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    h = np.zeros_like(r.lat) if r.height is None else r.height
    n, e, _ = llh_to_ned_flat(r.lat, r.lon, h, origin, meridian)
    return n, e


def _window(smooth_s: float, rate_hz: float) -> int:
    n = int(round(smooth_s * rate_hz))
    return max(1, n if n % 2 else n + 1)


def _fill_low_speed(time: NDArray[np.float64], cog: NDArray[np.float64], ok: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Heading where ``ok``: the course; elsewhere interpolated (unwrapped) between usable courses."""
    good = unwrap(cog[ok])
    return np.asarray(wrap_to_pi(np.interp(time, time[ok], good)), float)


def build_vessel(
    spec: VesselSpec,
    antennas: list[ResampledLog],
    origin: GeodeticOrigin,
    *,
    meridian: Meridian = "correct",
    eps_threshold_m: float = DEFAULT_EPS_THRESHOLD_M,
    smooth_s: float = DEFAULT_SMOOTH_S,
    min_cog_speed: float = DEFAULT_MIN_COG_SPEED,
) -> VesselGroundTruth:
    """Ground truth of ``spec`` from its resampled antennas (bow first)."""
    time = antennas[0].time
    rate = 1.0 / float(np.median(np.diff(time)))
    window = _window(smooth_s, rate)
    flags = np.zeros(len(time), dtype=np.uint8)
    for a in antennas:
        flags[a.gap] |= FLAG_GAP
    settings = {"smooth_s": smooth_s, "velocity_window_samples": window}
    if len(antennas) == 2:
        nb, eb = _ned(antennas[0], origin, meridian)
        ns, es = _ned(antennas[1], origin, meridian)
        north, east = antenna_midpoint(nb, eb, ns, es)
        heading = np.asarray(heading_from_antennas(nb, eb, ns, es), float)
        if spec.baseline_m is not None:
            baseline, source = spec.baseline_m, "given"
        elif spec.name.lower() in KNOWN_BASELINES_M:
            baseline, source = KNOWN_BASELINES_M[spec.name.lower()], "thesis hand measurement"
        else:
            baseline = float(np.median(antenna_distance(nb, eb, ns, es)))
            source = "median of measured distances (no baseline given)"
        eps = gnss_baseline_error(nb, eb, ns, es, baseline)
        flags[eps > eps_threshold_m] |= FLAG_EPS
        v_n, v_e = velocity_central(time, north, east, window)
        return VesselGroundTruth(
            spec.name, time, north, east, heading, v_n, v_e, HEADING_ANTENNAS, flags, antennas,
            eps_gnss=eps, rel_north=nb - ns, rel_east=eb - es, baseline_m=baseline, baseline_source=source,
            eps_threshold_m=eps_threshold_m, settings=settings,
        )  # fmt: skip
    north, east = _ned(antennas[0], origin, meridian)
    v_n, v_e = velocity_central(time, north, east, window)
    ok = np.hypot(v_n, v_e) >= min_cog_speed
    if not ok.any():
        raise InputError(
            spec.files[0],
            f"vessel {spec.name!r} has one antenna and never moves faster than {min_cog_speed} m/s: "
            "no course over ground to take the heading from; give bow and stern antennas",
        )
    flags[~ok] |= FLAG_LOW_SPEED
    heading = _fill_low_speed(time, course_over_ground(v_n, v_e), ok)
    settings["min_cog_speed"] = min_cog_speed
    return VesselGroundTruth(spec.name, time, north, east, heading, v_n, v_e, HEADING_COG, flags, antennas, settings=settings)
