"""The agent under test: what it is told each step and what it answers — one interface for every transport.

Each simulation step (lock-step: the simulation waits for the answer, so a slow agent slows it and never misses a
step) the loop calls ``agent.step(time, frames, navigation)``:

* ``frames`` — every sensor frame completed since the previous call, in time order (:class:`SensorFrame`: a lidar
  sweep, a radar rotation, or — for a perfect-perception agent that asks for ``truth`` — the targets' true states),
  each with the ownship's navigation at its stamp (what tf gives a ROS consumer);
* ``navigation`` — the ownship's own state now (:class:`Navigation`).

It answers a :data:`Command`: generalised forces (:class:`ForceCommand`), thruster azimuths and thrusts
(:class:`ThrusterCommand`), or a speed/heading set-point (:class:`SetPoint`) that the loop's autopilot
(:class:`seatwin.dynamics.Autopilot`) turns into forces.

The out-of-process transport (gRPC: :mod:`seatwin.api.agent_link`, Gemini's ``ForceControl`` beside seatwin's
``AgentLink``) is a translation of these types: ``ForceCommand`` ↔ ``ApplyForce``, ``SetPoint`` ↔ ``SetVelocity``,
``ThrusterCommand`` ↔ ``ApplyThrust``, ``Navigation`` ↔ ``State`` (and Gemini's ``NavigationRequest``), frames ↔
``Frame`` (lidar as Gemini's ``LidarStreamingRequest``). :class:`~seatwin.api.agent_link.RemoteAgent` has this same
:class:`Agent` shape and forwards each ``step`` over the wire; :func:`seatwin.api.agent_host.host_agent` is the other
side.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from seatwin.perception.frames import Mount


@dataclass(frozen=True)
class Navigation:
    """The ownship's navigation solution: pose (NED, heading clockwise from north) and body velocities."""

    time: float
    north: float
    east: float
    heading: float
    u: float
    """Surge [m/s]."""
    v: float
    """Sway [m/s] (starboard positive)."""
    r: float
    """Yaw rate [rad/s] (clockwise positive)."""

    @property
    def v_north(self) -> float:
        return self.u * math.cos(self.heading) - self.v * math.sin(self.heading)

    @property
    def v_east(self) -> float:
        return self.u * math.sin(self.heading) + self.v * math.cos(self.heading)

    @property
    def speed(self) -> float:
        return math.hypot(self.u, self.v)

    @property
    def course(self) -> float:
        return math.atan2(self.v_east, self.v_north) if self.speed > 1e-6 else self.heading


@dataclass(frozen=True)
class TruthTarget:
    """A target's true state (what a perfect perception reports)."""

    name: str
    north: float
    east: float
    v_north: float
    v_east: float
    length: float
    beam: float


@dataclass(frozen=True)
class SensorFrame:
    """One completed sensor frame: ``sensor`` ``lidar`` (``data`` a :class:`seatwin.sensors.lidar.LidarSweep` in the
    sensor frame), ``radar`` (a :class:`seatwin.sensors.radar.model.RadarScan`) or ``truth`` (a tuple of
    :class:`TruthTarget`), stamped ``time`` (a sweep's start), with the ownship's navigation then and the mount."""

    sensor: str
    time: float
    data: Any
    navigation: Navigation
    mount: Mount | None = None


@dataclass(frozen=True)
class ForceCommand:
    """Generalised force τ = (X [N], Y [N], N [N·m]) in the body frame."""

    X: float
    Y: float
    N: float


@dataclass(frozen=True)
class ThrusterCommand:
    """Azimuths [rad] and thrusts [N], one per thruster."""

    angles: tuple[float, ...]
    thrusts: tuple[float, ...]


@dataclass(frozen=True)
class SetPoint:
    """Surge speed [m/s] and heading [rad] for the autopilot."""

    speed: float
    heading: float


Command = ForceCommand | ThrusterCommand | SetPoint


@dataclass(frozen=True)
class Mission:
    """What an agent is told before a run: where it starts and must go, at what speed, in which harbour."""

    start_north: float
    start_east: float
    goal_north: float
    goal_east: float
    cruise_speed: float
    harbour: str
    """The harbour's name or raster path (an agent may use it as its chart)."""
    length: float = 5.0
    beam: float = 2.8


@dataclass(frozen=True)
class TrackEstimate:
    """A confirmed track the agent believes in (reported for the verdicts: when each target was first tracked)."""

    id: int
    north: float
    east: float
    v_north: float
    v_east: float


class Agent(Protocol):
    """The autonomy under test (module docstring)."""

    name: str
    sensors: tuple[str, ...]
    """The frames it wants: ``lidar``, ``radar``, ``truth``."""

    def reset(self, mission: Mission) -> None: ...

    def step(self, time: float, frames: Sequence[SensorFrame], navigation: Navigation) -> Command: ...

    def tracks(self) -> list[TrackEstimate]:
        """Its confirmed tracks now (empty if it does not say)."""
        ...
