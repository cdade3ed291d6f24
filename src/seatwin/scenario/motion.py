"""Smooth planar motion for generated scenarios: a path of lines and arcs, and a speed profile.

A :class:`Path` is a chain of straight lines and circular arcs from a start pose, so its
heading is continuous and always the direction of travel. A :class:`SpeedProfile` holds
speeds at knot times and blends between them with half-cosine ramps (continuous
acceleration at the knots' ends, peak acceleration π·Δv/(2·T)). :func:`follow` moves a vessel
along a path with a profile and samples it into a :class:`~seatwin.scenario.model.Trajectory`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo import wrap_to_pi
from seatwin.scenario.model import Trajectory


@dataclass(frozen=True)
class _Segment:
    s0: float
    length: float
    north: float
    east: float
    heading: float
    curvature: float
    """1/radius, positive turning clockwise (to starboard); 0 for a line."""


@dataclass
class Path:
    """Lines and arcs from a start pose (north, east [m], heading [rad] clockwise from north)."""

    north: float
    east: float
    heading: float
    _segments: list[_Segment] = field(default_factory=list, repr=False)

    @property
    def length(self) -> float:
        return sum(seg.length for seg in self._segments)

    def _end(self) -> tuple[float, float, float]:
        if not self._segments:
            return self.north, self.east, self.heading
        seg = self._segments[-1]
        n, e, h = _segment_pose(seg, np.array([seg.length]))
        return float(n[0]), float(e[0]), float(h[0])

    def _add(self, length: float, curvature: float) -> Path:
        if length < 0:
            raise ValueError(f"segment length must be non-negative, got {length}")
        if length > 0:
            n, e, h = self._end()
            self._segments.append(_Segment(self.length, float(length), n, e, h, float(curvature)))
        return self

    def line(self, length: float) -> Path:
        """Go straight for ``length`` metres."""
        return self._add(length, 0.0)

    def arc(self, radius: float, angle_deg: float) -> Path:
        """Turn by ``angle_deg`` (positive to starboard, i.e. clockwise) on a circle of ``radius`` m."""
        if radius <= 0:
            raise ValueError(f"turn radius must be positive, got {radius}")
        return self._add(radius * abs(np.radians(angle_deg)), np.sign(angle_deg) / radius)

    def turn_to(self, heading_deg: float, radius: float) -> Path:
        """Turn the shorter way onto compass heading ``heading_deg``."""
        delta = float(np.degrees(wrap_to_pi(np.radians(heading_deg) - self._end()[2])))
        return self.arc(radius, delta)

    def jog(self, offset: float, radius: float, angle_deg: float = 30.0) -> Path:
        """Shift sideways by ``offset`` m (positive to starboard) and resume the same heading.

        An S-bend: turn ``angle_deg`` on ``radius``, go straight, turn back.
        """
        theta = np.radians(angle_deg)
        bends = 2.0 * radius * (1.0 - np.cos(theta))
        if abs(offset) < bends:
            raise ValueError(f"offset {offset} m is smaller than the two bends alone ({bends:.1f} m)")
        sign = np.sign(offset)
        return self.arc(radius, sign * angle_deg).line((abs(offset) - bends) / np.sin(theta)).arc(radius, -sign * angle_deg)

    def end_pose(self) -> tuple[float, float, float]:
        """(north, east, heading in [−π, π)) at the end of the path."""
        n, e, h = self._end()
        return n, e, float(wrap_to_pi(h))

    def at(self, s: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """North, east, heading at arc length(s) ``s`` (clamped to the path; beyond its end it stops)."""
        ss = np.atleast_1d(np.asarray(s, dtype=float))
        if not self._segments:
            return (np.full_like(ss, self.north), np.full_like(ss, self.east), np.full_like(ss, self.heading))
        ss = np.clip(ss, 0.0, self.length)
        starts = np.array([seg.s0 for seg in self._segments])
        index = np.clip(np.searchsorted(starts, ss, side="right") - 1, 0, len(self._segments) - 1)
        north, east, heading = np.empty_like(ss), np.empty_like(ss), np.empty_like(ss)
        for i, seg in enumerate(self._segments):
            m = index == i
            if m.any():
                north[m], east[m], heading[m] = _segment_pose(seg, ss[m] - seg.s0)
        return north, east, np.asarray(wrap_to_pi(heading), float)


def _segment_pose(seg: _Segment, ds: NDArray[np.float64]) -> tuple[NDArray, NDArray, NDArray]:
    k, h0 = seg.curvature, seg.heading
    if k == 0.0:
        return seg.north + ds * np.cos(h0), seg.east + ds * np.sin(h0), np.full_like(ds, h0)
    h = h0 + k * ds
    return seg.north + (np.sin(h) - np.sin(h0)) / k, seg.east - (np.cos(h) - np.cos(h0)) / k, h


@dataclass(frozen=True)
class SpeedProfile:
    """Speed [m/s] at knot times [s from start]; half-cosine ramps between consecutive knots.

    Before the first knot the speed is the first knot's, after the last the last knot's. Two
    knots with the same speed hold it; a knot pair with different speeds is a ramp.
    """

    knots: tuple[tuple[float, float], ...]

    def __post_init__(self) -> None:
        t = [k[0] for k in self.knots]
        if not self.knots or any(b <= a for a, b in zip(t, t[1:])):
            raise ValueError(f"knot times must increase strictly, got {t}")
        if any(k[1] < 0 for k in self.knots):
            raise ValueError("speeds must be non-negative")

    @classmethod
    def constant(cls, speed: float) -> SpeedProfile:
        return cls(((0.0, speed),))

    def speed(self, t: ArrayLike) -> NDArray[np.float64]:
        tt = np.asarray(t, dtype=float)
        v = np.full_like(tt, self.knots[0][1])
        for (t0, v0), (t1, v1) in zip(self.knots, self.knots[1:]):
            u = np.clip((tt - t0) / (t1 - t0), 0.0, 1.0)
            v = np.where(tt >= t0, v0 + (v1 - v0) * 0.5 * (1.0 - np.cos(np.pi * u)), v)
        return v

    def distance(self, t: ArrayLike) -> NDArray[np.float64]:
        """Distance travelled since time 0 (closed-form integral of :meth:`speed`)."""
        tt = np.asarray(t, dtype=float)
        t_first, v_first = self.knots[0]
        # Before the first knot (and from 0 to it) the speed is v_first.
        d = v_first * (np.minimum(tt, t_first) - 0.0)
        for (t0, v0), (t1, v1) in zip(self.knots, self.knots[1:]):
            T = t1 - t0
            tau = np.clip(tt - t0, 0.0, T)
            d = d + v0 * tau + 0.5 * (v1 - v0) * (tau - T / np.pi * np.sin(np.pi * tau / T))
        t_last, v_last = self.knots[-1]
        return d + v_last * np.clip(tt - t_last, 0.0, None)


def follow(
    path: Path,
    profile: SpeedProfile,
    start: float,
    duration: float,
    rate_hz: float = 10.0,
    offset: float = 0.0,
    source: str = "<generated>",
) -> Trajectory:
    """Sample a vessel moving along ``path`` with ``profile`` from POSIX ``start`` for ``duration`` s.

    ``offset`` is how far along the path the vessel is at the start (a vessel following another
    on the same path). Raises ``ValueError`` when the path is shorter than the distance covered.
    """
    rel = np.arange(int(round(duration * rate_hz)) + 1) / rate_hz
    s = offset + profile.distance(rel)
    if s[-1] > path.length + 1e-6:
        raise ValueError(f"{source}: path is {path.length:.1f} m but the speed profile covers {s[-1]:.1f} m")
    north, east, heading = path.at(s)
    return Trajectory(start + rel, north, east, heading, source=source)
