"""The vessels' received samples, growing step by step: what ``seatwin serve``'s ground truth and scene read.

:class:`LiveTracks` appends each step's poses to preallocated arrays and keeps per sample what a
:class:`~seatwin.scenario.Trajectory` of the same samples derives — the heading unwrapped as
``numpy.unwrap`` does and the velocities of ``numpy.gradient`` (central differences for uneven
steps, one-sided at the ends) — updated incrementally, so a step costs O(vessels), not O(samples).
:meth:`LiveTracks.state` interpolates with ``numpy.interp``'s arithmetic: the values of
:meth:`Trajectory.state_at` on the received samples (the same bits, except where a trajectory's
steps are all exactly equal and ``numpy.gradient`` takes its even-step formula: ~1e-16 apart).
:class:`LiveGroundTruth` records from it; :meth:`LiveTracks.window` gives the scene a view of the
recent samples (no copy).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo import TWO_PI, GeodeticOrigin, wrap_to_pi
from seatwin.geo.geodetic import ned_to_llh_wgs84
from seatwin.recording import VesselPose
from seatwin.scenario import Role, Scenario, Trajectory
from seatwin.sim.sensors import GroundTruthSensor, Periodic

_NORTH, _EAST, _HEADING, _VN, _VE, _YAW_RATE = range(6)


class LiveTracks:
    """Samples of ``n_vessels`` vessels at common times: north, east [m], heading [rad], appended in time order."""

    def __init__(self, n_vessels: int, capacity: int = 1024):
        self.n = 0
        self._t = np.empty(capacity)
        self._raw = np.empty((n_vessels, capacity))
        """Headings as received [rad]."""
        self._wrapped = np.empty((n_vessels, capacity))
        self._s = np.empty((n_vessels, 6, capacity))
        """North, east, unwrapped heading, and their rates (v_north, v_east, yaw rate) at each sample."""
        self._unwrap = np.zeros(n_vessels)
        """``numpy.unwrap``'s running correction (the cumulative sum of its 2π steps)."""

    @property
    def times(self) -> NDArray[np.float64]:
        return self._t[: self.n]

    def sample_time(self, k: int) -> float:
        """Time of sample ``k`` (negative: counted from the last)."""
        return float(self._t[k if k >= 0 else self.n + k])

    def _grow(self) -> None:
        cap = 2 * len(self._t)
        for name in ("_t", "_raw", "_wrapped", "_s"):
            old = getattr(self, name)
            new = np.empty((*old.shape[:-1], cap))
            new[..., : self.n] = old[..., : self.n]
            setattr(self, name, new)  # views handed out earlier keep the old buffer, whose samples never change

    def append(self, t: float, north: NDArray[np.float64], east: NDArray[np.float64], heading: NDArray[np.float64]) -> None:
        """Add every vessel's sample at ``t`` (later than the last); headings in radians."""
        k = self.n
        if k == len(self._t):
            self._grow()
        s, tt = self._s, self._t
        tt[k] = t
        s[:, _NORTH, k] = north
        s[:, _EAST, k] = east
        self._raw[:, k] = heading
        w = self._wrapped[:, k] = wrap_to_pi(heading)
        if k:  # numpy.unwrap, one step: p[k] + cumsum of the corrections
            dd = w - self._wrapped[:, k - 1]
            ddmod = np.mod(dd + np.pi, TWO_PI) - np.pi
            ddmod[(ddmod == -np.pi) & (dd > 0)] = np.pi
            correction = ddmod - dd
            correction[np.abs(dd) < np.pi] = 0
            self._unwrap = correction if k == 1 else self._unwrap + correction
            s[:, _HEADING, k] = w + self._unwrap
            # numpy.gradient: one-sided at the new end (and at the start), central at the sample before
            f = s[:, :3]
            dx = tt[k] - tt[k - 1]
            s[:, 3:, k] = (f[:, :, k] - f[:, :, k - 1]) / dx
            if k == 1:
                s[:, 3:, 0] = s[:, 3:, 1]
            else:
                dx1, dx2 = tt[k - 1] - tt[k - 2], dx
                a = -(dx2) / (dx1 * (dx1 + dx2))
                b = (dx2 - dx1) / (dx1 * dx2)
                c = dx1 / (dx2 * (dx1 + dx2))
                s[:, 3:, k - 1] = a * f[:, :, k - 2] + b * f[:, :, k - 1] + c * f[:, :, k]
        else:
            s[:, _HEADING, 0] = w
        self.n = k + 1

    def last(self, vessel: int) -> tuple[float, float, float, float, float, float]:
        """Vessel ``vessel`` at the last sample: north, east, heading (unwrapped), v_north, v_east, yaw rate
        (one-sided differences; zero velocities with a single sample)."""
        k = self.n - 1
        n, e, h = self._s[vessel, :3, k].tolist()
        return (n, e, h, *(self._s[vessel, 3:, k].tolist() if k else (0.0, 0.0, 0.0)))

    def state(self, t: ArrayLike) -> NDArray[np.float64]:
        """(vessels, 6, len(t)): north, east, heading (wrapped to [−π, π)), v_north, v_east, yaw rate at times
        ``t`` within the samples (needs two), interpolated as ``Trajectory.state_at``."""
        tt = np.asarray(t, dtype=np.float64).reshape(-1)
        n, times, s = self.n, self._t[: self.n], self._s
        j = np.clip(np.searchsorted(times, tt, side="right") - 1, 0, n - 2)
        x0 = times[j]
        y0, y1 = s[:, :, j], s[:, :, j + 1]
        out = (y1 - y0) / (times[j + 1] - x0) * (tt - x0) + y0
        out = np.where(tt == x0, y0, out)  # numpy.interp: a sample's own value, and the last at the end
        out = np.where(tt >= times[-1], s[:, :, n - 1 : n], out)
        out[:, _HEADING] = wrap_to_pi(out[:, _HEADING])
        return out

    def window(self, vessel: int, first: int) -> _Window:
        """Vessel ``vessel``'s samples from ``first`` on, as a track the scene can pose (views, no copy)."""
        n = self.n
        s = self._s[vessel]
        return _Window(self._t[first:n], s[_NORTH, first:n], s[_EAST, first:n], self._wrapped[vessel, first:n])

    def trajectory(self, vessel: int, source: str = "seatwin serve") -> Trajectory:
        """Vessel ``vessel``'s samples so far as a :class:`Trajectory` (needs two)."""
        n, s = self.n, self._s
        return Trajectory(
            self._t[:n].copy(), s[vessel, _NORTH, :n].copy(), s[vessel, _EAST, :n].copy(), self._raw[vessel, :n].copy(), source
        )


class _Window:
    """Recent samples of one vessel (the scene's :class:`~seatwin.world.scene.Track`)."""

    def __init__(self, time: NDArray[np.float64], north: NDArray[np.float64], east: NDArray[np.float64], heading: NDArray[Any]):
        self.time, self.north, self.east, self.heading = time, north, east, heading

    @property
    def start(self) -> float:
        return float(self.time[0])

    @property
    def end(self) -> float:
        return float(self.time[-1])

    def state_at(self, t: ArrayLike) -> Any:
        """The scene calls this only to raise the trajectory's own error for a time outside the samples."""
        return Trajectory(self.time, self.north, self.east, self.heading, source="seatwin serve").state_at(t)


class LiveGroundTruth(GroundTruthSensor):
    """Ground truth of the served vessels, read from :class:`LiveTracks` (the ownship's NavSatFix included)."""

    def __init__(self, scenario: Scenario, tracks: LiveTracks, rate_hz: float, origin: GeodeticOrigin | None):
        super().__init__(scenario, rate_hz)
        self.tracks, self.origin = tracks, origin
        self._names = [v.name for v in scenario.vessels]
        self._own = [v.role == Role.OWNSHIP for v in scenario.vessels]

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        return Periodic.frame_times(self, t0, t1)

    def frame_times_from(self, t0: float, t1: float, first: int) -> NDArray[np.float64]:
        return Periodic.frame_times_from(self, t0, t1, first)

    def capture(self, t: float, frame: int) -> list[VesselPose]:
        rows = self.tracks.state(t)[:, :, 0].tolist()
        out = []
        for name, own, (n, e, h, vn, ve, r) in zip(self._names, self._own, rows):
            llh = None
            if own and self.origin is not None:
                lat, lon, height = ned_to_llh_wgs84(np.array([n]), np.array([e]), np.zeros(1), self.origin)
                llh = (float(lat[0]), float(lon[0]), float(height[0]))
            out.append(VesselPose(name=name, north=n, east=e, heading=h, v_north=vn, v_east=ve, yaw_rate=r, ownship=own, llh=llh))
        return out
