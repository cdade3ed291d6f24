"""The scenario model: vessels with trajectories in a local NED frame, and their state at any time.

A trajectory is sampled (typically at 10 Hz); between samples positions and the unwrapped
heading are interpolated linearly. Velocity and yaw rate come from central differences at
the samples (``numpy.gradient``), also interpolated linearly, so they are continuous.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.geo import GeodeticOrigin, unwrap, wrap_to_pi
from seatwin.mesh_placement import MeshPlacement


class Role(str, Enum):
    OWNSHIP = "ownship"
    TARGET = "target"


@dataclass(frozen=True)
class VesselState:
    """State of one vessel at one or more times (arrays broadcast like ``time``)."""

    time: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    heading: NDArray[np.float64]
    """Radians clockwise from north, in [−π, π)."""
    v_north: NDArray[np.float64]
    v_east: NDArray[np.float64]
    yaw_rate: NDArray[np.float64]
    """rad/s, positive clockwise seen from above (NED z down)."""

    @property
    def speed(self) -> NDArray[np.float64]:
        return np.hypot(self.v_north, self.v_east)


@dataclass
class Trajectory:
    """Samples of one vessel's 3-DOF pose: POSIX time, north and east [m], heading [rad]."""

    time: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    heading: NDArray[np.float64]
    source: str = "<memory>"

    def __post_init__(self) -> None:
        self.time = np.asarray(self.time, dtype=float)
        self.north = np.asarray(self.north, dtype=float)
        self.east = np.asarray(self.east, dtype=float)
        self.heading = np.asarray(wrap_to_pi(self.heading), dtype=float).reshape(self.time.shape)
        n = self.time.shape
        if self.time.ndim != 1 or self.north.shape != n or self.east.shape != n:
            raise InputError(self.source, "time, north, east and heading must be 1-D arrays of equal length")
        if len(self.time) < 2:
            raise InputError(self.source, f"a trajectory needs at least 2 samples, got {len(self.time)}")
        for name in ("time", "north", "east", "heading"):
            bad = np.flatnonzero(~np.isfinite(getattr(self, name)))
            if bad.size:
                raise InputError(self.source, f"{name} is not finite at sample {bad[0]}", where=name)
        steps = np.diff(self.time)
        if (steps <= 0).any():
            i = int(np.flatnonzero(steps <= 0)[0]) + 1
            raise InputError(
                self.source,
                f"times must increase strictly; sample {i} ({self.time[i]!r}) follows {self.time[i - 1]!r}",
                where="time",
            )
        self._heading_unwrapped = unwrap(self.heading)
        self._v_north = np.gradient(self.north, self.time)
        self._v_east = np.gradient(self.east, self.time)
        self._yaw_rate = np.gradient(self._heading_unwrapped, self.time)

    @property
    def start(self) -> float:
        return float(self.time[0])

    @property
    def end(self) -> float:
        return float(self.time[-1])

    @property
    def rate_hz(self) -> float:
        """Sample rate: over the whole span when the steps are even (exact despite the rounding of
        large POSIX times), else from the median step."""
        steps = np.diff(self.time)
        median = float(np.median(steps))
        if np.ptp(steps) <= 1e-3 * median:
            return float((len(self.time) - 1) / (self.time[-1] - self.time[0]))
        return 1.0 / median

    def state_at(self, t: ArrayLike) -> VesselState:
        """Interpolated state at time(s) ``t``; an :class:`InputError` outside the time span."""
        tt = np.asarray(t, dtype=float)
        # Allow a rounding hair beyond the ends (times printed with limited decimals).
        tol = 1e-6
        if tt.size and (np.nanmin(tt) < self.start - tol or np.nanmax(tt) > self.end + tol or np.isnan(tt).any()):
            raise InputError(
                self.source,
                f"time {float(np.nanmin(tt) if np.nanmin(tt) < self.start else np.nanmax(tt))!r} is outside "
                f"the trajectory's span [{self.start!r}, {self.end!r}]",
            )
        tt = np.clip(tt, self.start, self.end)
        interp = lambda y: np.interp(tt, self.time, y)  # noqa: E731
        return VesselState(
            time=tt,
            north=interp(self.north),
            east=interp(self.east),
            heading=np.asarray(wrap_to_pi(interp(self._heading_unwrapped)), float),
            v_north=interp(self._v_north),
            v_east=interp(self._v_east),
            yaw_rate=interp(self._yaw_rate),
        )

    def sliced(self, start: float, end: float) -> Trajectory:
        """The samples within [start, end]."""
        keep = (self.time >= start - 1e-9) & (self.time <= end + 1e-9)
        return Trajectory(self.time[keep], self.north[keep], self.east[keep], self.heading[keep], self.source)


@dataclass
class Dimensions:
    """Overall size of a vessel [m]: length overall, beam, height above the waterline."""

    length: float
    beam: float
    height: float


@dataclass
class Vessel:
    name: str
    role: Role
    trajectory: Trajectory
    model: str = "generic"
    """Name of the 3-D model (``seatwin.world`` builds it) or a mesh file path."""
    dimensions: Dimensions | None = None
    mesh: MeshPlacement | None = None
    """Scale, yaw, offset and axes of a mesh file ``model`` (None: as the file is, z up, in metres)."""


@dataclass
class Scenario:
    """Vessels moving in a local NED frame about a geodetic origin."""

    name: str
    vessels: list[Vessel]
    origin: GeodeticOrigin | None = None
    seed: int = 0
    environment: dict[str, Any] = field(default_factory=lambda: {"harbour": "default", "water": "flat"})
    rig: str | None = "milliampere"
    """Name of the ownship's sensor rig."""
    source: str = "<memory>"
    description: str = ""

    @property
    def files(self) -> list[str]:
        """The files the scenario was read from (its own and its trajectories'), to never write over them."""
        names = [self.source, *(re.sub(r" \([^()]*\)$", "", v.trajectory.source) for v in self.vessels)]  # "f.csv (vessel 1)"
        return list(dict.fromkeys(n for n in names if n and not n.startswith("<")))

    def __post_init__(self) -> None:
        if not self.vessels:
            raise InputError(self.source, "a scenario needs at least one vessel")
        names = [v.name for v in self.vessels]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise InputError(self.source, f"vessel names must be unique, repeated: {sorted(dup)}")
        owners = [v for v in self.vessels if v.role == Role.OWNSHIP]
        if len(owners) > 1:
            raise InputError(self.source, f"at most one ownship, got {[v.name for v in owners]}")

    @property
    def ownship(self) -> Vessel | None:
        return next((v for v in self.vessels if v.role == Role.OWNSHIP), None)

    @property
    def targets(self) -> list[Vessel]:
        return [v for v in self.vessels if v.role == Role.TARGET]

    def vessel(self, name: str) -> Vessel:
        for v in self.vessels:
            if v.name == name:
                return v
        raise InputError(self.source, f"no vessel named {name!r}; vessels are {[v.name for v in self.vessels]}")

    @property
    def start(self) -> float:
        """Start of the interval where every vessel has a trajectory."""
        return max(v.trajectory.start for v in self.vessels)

    @property
    def end(self) -> float:
        return min(v.trajectory.end for v in self.vessels)

    @property
    def duration(self) -> float:
        return self.end - self.start

    def state_at(self, name: str, t: ArrayLike) -> VesselState:
        return self.vessel(name).trajectory.state_at(t)
