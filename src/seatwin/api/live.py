"""The vessels' received samples, growing step by step: what ``seatwin serve``'s ground truth and scene read.

:class:`LiveTracks` keeps per sample what a :class:`~seatwin.scenario.Trajectory` of the same samples
derives — the heading unwrapped as ``numpy.unwrap`` does and the velocities of ``numpy.gradient``
(central differences for uneven steps, one-sided at the ends) — updated incrementally on Python floats
(the same operations, the same bits), so a step costs O(vessels), not O(samples); the preallocated
arrays receive the steps' samples in one write when something reads them (a frame), not one per step.
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

_NORTH, _EAST, _HEADING, _VN, _VE, _YAW_RATE, _RAW, _WRAPPED = range(8)
_PI = float(np.pi)


class LiveTracks:
    """Samples of ``n_vessels`` vessels at common times: north, east [m], heading [rad], appended in time order.

    A step's sample is derived on Python floats (the same IEEE operations as numpy's, so the same bits)
    and kept in a short Python list; the arrays receive the pending samples at once when something reads
    them (:meth:`state`, :meth:`window`, …: once per frame, not per step), so a step without a frame
    costs a few float operations, however long the run."""

    def __init__(self, n_vessels: int, capacity: int = 1024):
        self.n = 0
        self._t = np.empty(capacity)
        self._s = np.empty((n_vessels, 8, capacity))
        """North, east, unwrapped heading, their rates (v_north, v_east, yaw rate), the heading as received
        and wrapped to [−π, π), at each sample written."""
        self._done = 0
        """Samples in the arrays; those after are in ``_pending`` (per sample, per vessel the 8 values) and ``_tpending``."""
        self._pending: list[list[list[float]]] = []
        self._tpending: list[float] = []
        self._u = [0.0] * n_vessels
        """``numpy.unwrap``'s running correction per vessel (the cumulative sum of its 2π steps)."""
        self._tl = (0.0, 0.0)
        """The last two samples' times."""
        self._f: list[list[float]] = []
        """The last sample's 8 values per vessel; ``_f0`` the one before's."""
        self._f0: list[list[float]] = []

    @property
    def times(self) -> NDArray[np.float64]:
        self._sync()
        return self._t[: self.n]

    def sample_time(self, k: int) -> float:
        """Time of sample ``k`` (negative: counted from the last)."""
        k = k if k >= 0 else self.n + k
        return self._tpending[k - self._done] if k >= self._done else float(self._t[k])

    def _sync(self) -> None:
        """Write the pending samples into the arrays (growing them as needed)."""
        m = len(self._pending)
        if not m:
            return
        k0 = self._done
        while k0 + m > len(self._t):
            self._grow()
        self._t[k0 : k0 + m] = self._tpending
        self._s[:, :, k0 : k0 + m] = np.array(self._pending).transpose(1, 2, 0)
        self._done = k0 + m
        self._pending, self._tpending = [], []

    def _grow(self) -> None:
        cap = 2 * len(self._t)
        for name in ("_t", "_s"):
            old = getattr(self, name)
            new = np.empty((*old.shape[:-1], cap))
            new[..., : self._done] = old[..., : self._done]
            setattr(self, name, new)  # views handed out earlier keep the old buffer, whose samples never change

    def append(self, t: float, north: ArrayLike, east: ArrayLike, heading: ArrayLike) -> None:
        """Add every vessel's sample at ``t`` (later than the last); headings in radians.

        The arithmetic is ``numpy.unwrap``'s and ``numpy.gradient``'s (central differences for uneven
        steps, one-sided at the ends), element by element on Python floats."""
        k = self.n
        t = float(t)
        ns, es, hs = (
            x.astype(np.float64, copy=False).tolist() if isinstance(x, np.ndarray) else [float(v) for v in x]
            for x in (north, east, heading)
        )
        rows = []
        if not k:
            for n, e, h in zip(ns, es, hs, strict=True):
                w = (h + _PI) % TWO_PI - _PI  # wrap_to_pi
                rows.append([n, e, w, 0.0, 0.0, 0.0, h, w])  # velocities: set by the next sample
        else:
            dx = t - self._tl[0]
            for i, (n, e, h) in enumerate(zip(ns, es, hs, strict=True)):
                n1, e1, h1, _, _, _, _, w1 = self._f[i]
                w = (h + _PI) % TWO_PI - _PI
                dd = w - w1  # numpy.unwrap, one step: p[k] + the cumulative sum of its corrections
                ddmod = (dd + _PI) % TWO_PI - _PI
                if ddmod == -_PI and dd > 0:
                    ddmod = _PI
                correction = 0.0 if abs(dd) < _PI else ddmod - dd
                u = self._u[i] = correction if k == 1 else self._u[i] + correction
                hu = w + u
                rows.append([n, e, hu, (n - n1) / dx, (e - e1) / dx, (hu - h1) / dx, h, w])  # one-sided at the new end
            if k == 1:  # numpy.gradient at the first sample: one-sided too
                before = [r[3:6] for r in rows]
            else:  # central at the sample before, now that its successor is in
                dx1, dx2 = self._tl[0] - self._tl[1], dx
                a = -(dx2) / (dx1 * (dx1 + dx2))
                b = (dx2 - dx1) / (dx1 * dx2)
                c = dx1 / (dx2 * (dx1 + dx2))
                before = [
                    [a * f0[j] + b * f1[j] + c * f2[j] for j in range(3)]
                    for f0, f1, f2 in zip(self._f0, self._f, rows, strict=True)
                ]
            if k - 1 >= self._done:
                for r, v in zip(self._pending[k - 1 - self._done], before, strict=True):
                    r[3:6] = v
            else:
                self._s[:, 3:6, k - 1] = before
        self._pending.append(rows)
        self._tpending.append(t)
        self._f0, self._f = self._f, rows
        self._tl, self.n = (t, self._tl[0]), k + 1

    def last(self, vessel: int) -> tuple[float, float, float, float, float, float]:
        """Vessel ``vessel`` at the last sample: north, east, heading (unwrapped), v_north, v_east, yaw rate
        (one-sided differences; zero velocities with a single sample)."""
        n, e, h, vn, ve, r = self._f[vessel][:6]
        return (n, e, h, vn, ve, r) if self.n > 1 else (n, e, h, 0.0, 0.0, 0.0)

    def state(self, t: ArrayLike) -> NDArray[np.float64]:
        """(vessels, 6, len(t)): north, east, heading (wrapped to [−π, π)), v_north, v_east, yaw rate at times
        ``t`` within the samples (needs two), interpolated as ``Trajectory.state_at``."""
        self._sync()
        tt = np.asarray(t, dtype=np.float64).reshape(-1)
        n, times, s = self.n, self._t[: self.n], self._s[:, :6]
        j = np.clip(np.searchsorted(times, tt, side="right") - 1, 0, n - 2)
        x0 = times[j]
        y0, y1 = s[:, :, j], s[:, :, j + 1]
        out = (y1 - y0) / (times[j + 1] - x0) * (tt - x0) + y0
        out = np.where(tt == x0, y0, out)  # numpy.interp: a sample's own value, and the last at the end
        out = np.where(tt >= times[-1], s[:, :, n - 1 : n], out)
        out[:, _HEADING] = wrap_to_pi(out[:, _HEADING])
        return out

    def state_rows(self, t: float) -> list[list[float]]:
        """``state(t)[:, :, 0].tolist()`` for one time: the same arithmetic on Python floats (the same bits)
        without a dozen numpy calls on (vessels, 6, 1) arrays — a ground-truth frame's cost."""
        self._sync()
        n, times, t = self.n, self._t, float(t)
        if t >= float(times[n - 1]):
            rows = self._s[:, :6, n - 1].tolist()
        else:
            j = min(max(int(np.searchsorted(times[:n], t, side="right")) - 1, 0), n - 2)
            x0, x1 = float(times[j]), float(times[j + 1])
            pairs = self._s[:, :6, j : j + 2].tolist()
            if t == x0:
                rows = [[y0 for y0, _ in v] for v in pairs]
            else:
                rows = [[(y1 - y0) / (x1 - x0) * (t - x0) + y0 for y0, y1 in v] for v in pairs]
        for r in rows:
            r[_HEADING] = (r[_HEADING] + _PI) % TWO_PI - _PI  # wrap_to_pi
        return rows

    def window(self, vessel: int, first: int) -> _Window:
        """Vessel ``vessel``'s samples from ``first`` on, as a track the scene can pose (views, no copy)."""
        self._sync()
        n = self.n
        s = self._s[vessel]
        return _Window(self._t[first:n], s[_NORTH, first:n], s[_EAST, first:n], s[_WRAPPED, first:n])

    def trajectory(self, vessel: int, source: str = "seatwin serve") -> Trajectory:
        """Vessel ``vessel``'s samples so far as a :class:`Trajectory` (needs two)."""
        self._sync()
        n, s = self.n, self._s[vessel]
        return Trajectory(self._t[:n].copy(), s[_NORTH, :n].copy(), s[_EAST, :n].copy(), s[_RAW, :n].copy(), source)


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
        rows = self.tracks.state_rows(t)
        out = []
        for name, own, (n, e, h, vn, ve, r) in zip(self._names, self._own, rows):
            llh = None
            if own and self.origin is not None:
                lat, lon, height = ned_to_llh_wgs84(np.array([n]), np.array([e]), np.zeros(1), self.origin)
                llh = (float(lat[0]), float(lon[0]), float(height[0]))
            out.append(VesselPose(name=name, north=n, east=e, heading=h, v_north=vn, v_east=ve, yaw_rate=r, ownship=own, llh=llh))
        return out
