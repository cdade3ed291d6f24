"""The lock-step closed loop: the agent's commands drive the ownship's dynamics; targets sail their scenario paths;
the ownship's sensors are simulated every step from where the ownship really is.

Each step of ``dt`` seconds at time t: every sensor frame completed by t (a lidar sweep started at t_k is complete at
t_k + its period; a radar rotation likewise) is captured with the ownship's own past poses and handed to
``agent.step(t, frames, navigation)``; the loop waits for its command (so a slow agent slows the simulation and no
step is skipped), turns it into thruster commands (a set-point through :class:`seatwin.dynamics.Autopilot`, a force
through the allocation) and integrates the ownship one RK4 step. The sensors are those of the one simulation loop
(:func:`seatwin.sim.run.scenario_sensors`, their draws keyed by the seed and frame), posed in the one scene whose
ownship trajectory grows as the ownship sails, so a run is a pure function of (scenario, agent, settings, seed).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.agents.interface import (
    Agent,
    ForceCommand,
    Mission,
    Navigation,
    SensorFrame,
    SetPoint,
    ThrusterCommand,
    TrackEstimate,
    TruthTarget,
)
from seatwin.dynamics import (
    MILLIAMPERE,
    MILLIAMPERE_THRUSTERS,
    Autopilot,
    Model,
    ThrusterState,
    VesselState,
    step_force,
    step_thrusters,
)
from seatwin.errors import InputError, ParameterError
from seatwin.perception.frames import Mount
from seatwin.scenario import Scenario
from seatwin.sim.settings import SimulationSettings

TRACK_ASSOCIATION_M = 10.0
"""A confirmed track within this of a target counts as tracking it (the evaluation's association distance)."""


class GrowingTrack:
    """The ownship's trajectory as it is sailed: samples appended each step, read as a scene's :class:`Track`."""

    def __init__(self, capacity: int, source: str = "closed loop"):
        self._t = np.empty(capacity)
        self._n = np.empty(capacity)
        self._e = np.empty(capacity)
        self._h = np.empty(capacity)
        self.size = 0
        self.source = source

    def append(self, t: float, north: float, east: float, heading_unwrapped: float) -> None:
        if self.size == self._t.size:
            for name in ("_t", "_n", "_e", "_h"):
                setattr(self, name, np.concatenate([getattr(self, name), np.empty(self._t.size)]))
        k = self.size
        self._t[k], self._n[k], self._e[k], self._h[k] = t, north, east, heading_unwrapped
        self.size += 1

    @property
    def time(self) -> NDArray[np.float64]:
        return self._t[: self.size]

    @property
    def north(self) -> NDArray[np.float64]:
        return self._n[: self.size]

    @property
    def east(self) -> NDArray[np.float64]:
        return self._e[: self.size]

    @property
    def heading(self) -> NDArray[np.float64]:
        return self._h[: self.size]

    @property
    def start(self) -> float:
        return float(self._t[0])

    @property
    def end(self) -> float:
        return float(self._t[self.size - 1])

    def state_at(self, t: ArrayLike) -> Any:
        tt = np.asarray(t, dtype=float)
        if tt.size and (float(tt.min()) < self.start - 1e-6 or float(tt.max()) > self.end + 1e-6):
            raise InputError(
                self.source, f"time {float(tt.max())!r} is beyond the ownship's sailed span [{self.start!r}, {self.end!r}]"
            )
        return None


@dataclass
class RunRecord:
    """What a closed-loop run did, step by step (arrays of one row per step, the initial state first)."""

    scenario: str
    agent: str
    seed: int
    mission: Mission
    time: NDArray[np.float64]
    own: NDArray[np.float64]
    """(T, 6): north, east, heading, u, v, r."""
    command: NDArray[np.float64]
    """(T, 3): the command's numbers (speed, heading) / (X, Y, N) / first azimuth and thrusts; NaN on the last row."""
    targets: dict[str, NDArray[np.float64]]
    """Per target (T, 3): north, east, heading."""
    tracked: dict[str, NDArray[np.bool_]]
    """Per target (T,): a confirmed track of the agent within :data:`TRACK_ASSOCIATION_M` of it."""
    n_tracks: NDArray[np.int64]
    frames: dict[str, int] = field(default_factory=dict)
    """Sensor frames handed to the agent, by sensor."""
    sizes: dict[str, tuple[float, float]] = field(default_factory=dict)
    """(length, beam) of every vessel, the ownship's under its name."""
    ownship: str = "ownship"
    harbour: str = "none"


def mission_from(scenario: Scenario, harbour: str) -> Mission:
    """The ownship's start, goal (its scripted path's end) and cruise speed (its speed at the start)."""
    own = scenario.ownship
    if own is None:
        raise InputError(scenario.source, "the scenario has no ownship for the agent to sail")
    tr = own.trajectory
    speed = float(tr.state_at(scenario.start).speed)
    d = own.dimensions
    return Mission(
        float(tr.north[0]),
        float(tr.east[0]),
        float(tr.north[-1]),
        float(tr.east[-1]),
        speed,
        harbour,
        *((float(d.length), float(d.beam)) if d is not None else ()),
    )


def _navigation(s: VesselState) -> Navigation:
    return Navigation(s.time, s.north, s.east, s.heading, s.u, s.v, s.r)


def _interp_nav(states: list[VesselState], dt: float, t: float) -> Navigation:
    """The ownship's navigation at ``t`` (within the sailed span), linear between steps."""
    t0 = states[0].time
    k = min(max(int(math.floor((t - t0) / dt + 1e-9)), 0), len(states) - 1)
    a = states[k]
    if k + 1 >= len(states) or abs(t - a.time) < 1e-9:
        return _navigation(a)
    b = states[k + 1]
    w = (t - a.time) / (b.time - a.time)
    dh = math.remainder(b.heading - a.heading, 2 * math.pi)
    lerp = lambda x, y: x + w * (y - x)  # noqa: E731
    return Navigation(
        t, lerp(a.north, b.north), lerp(a.east, b.east), a.heading + w * dh, lerp(a.u, b.u), lerp(a.v, b.v), lerp(a.r, b.r)
    )


def _sensors(scenario: Scenario, names: tuple[str, ...], settings: SimulationSettings) -> tuple[list[Any], Any]:
    """The ownship's simulated sensors of ``names`` (and their shared scene), or none."""
    wanted = tuple(n for n in names if n in ("lidar", "radar"))
    unknown = [n for n in names if n not in ("lidar", "radar", "truth")]
    if unknown:
        raise ParameterError("sensors", f"the closed loop simulates 'lidar', 'radar' and 'truth' frames, not {unknown}")
    if not wanted:
        return [], None
    from seatwin.sim.run import scenario_sensors

    sensors = [s for s in scenario_sensors(scenario, settings.model_copy(update={"sensors": wanted})) if s.name in wanted]
    scene = sensors[0].lidar.scene if sensors[0].name == "lidar" else sensors[0].scene
    return sensors, scene


def _mount(sensor: Any) -> Mount | None:
    if sensor.name == "lidar":
        m = sensor.lidar.mount
        return Mount(tuple(float(v) for v in m.translation), m.rotation())
    return None


def run_closed_loop(
    scenario: Scenario,
    agent: Agent,
    settings: SimulationSettings | None = None,
    *,
    dt: float = 0.1,
    duration: float | None = None,
    autopilot: Autopilot | None = None,
) -> RunRecord:
    """Sail ``scenario``'s ownship with ``agent`` in lock-step (module docstring); ``settings`` choose the sensor
    models and the seed as for ``seatwin simulate`` (``sensors`` is taken from the agent)."""
    if not (dt > 0 and math.isfinite(dt)):
        raise ParameterError("dt", f"expected a step > 0 s, got {dt}")
    settings = settings or SimulationSettings()
    if settings.seed is not None:
        scenario = dataclasses.replace(scenario, seed=int(settings.seed))
    from seatwin.sim.run import run_harbour

    harbour = run_harbour(scenario, settings)
    own = scenario.ownship
    mission = mission_from(scenario, harbour)
    assert own is not None
    t0 = scenario.start
    span = scenario.end - t0 if duration is None else min(float(duration), scenario.end - t0)
    n_steps = int(math.floor(span / dt + 1e-9))
    sensors, scene = _sensors(scenario, tuple(agent.sensors), settings)
    start = own.trajectory.state_at(t0)
    heading0 = float(start.heading)
    u0 = float(start.speed)
    state = VesselState(
        t0, float(start.north), float(start.east), heading0, u0, 0.0, 0.0, ThrusterState.idle(len(MILLIAMPERE_THRUSTERS.x))
    )
    model, thrusters, pilot = Model(MILLIAMPERE), MILLIAMPERE_THRUSTERS, autopilot or Autopilot()
    # Start at cruise: thrust balancing the resistance at the start speed.
    thrust0 = MILLIAMPERE.surge_damping(u0) / len(thrusters.x)
    state = dataclasses.replace(state, thrusters=ThrusterState((0.0,) * len(thrusters.x), (thrust0,) * len(thrusters.x)))
    track = GrowingTrack(n_steps + 2, f"{scenario.source}: {own.name} (closed loop)")
    track.append(t0, state.north, state.east, state.heading)
    if scene is not None:
        scene.update_trajectory(own.name, track)
    next_frame = {s.name: 0 for s in sensors}
    frame_times = {s.name: s.frame_times(t0, t0 + span + 1.0) for s in sensors}
    periods = {s.name: 1.0 / float(s.rate_hz) for s in sensors}
    targets = scenario.targets
    target_states = {v.name: v.trajectory.state_at(t0 + dt * np.arange(n_steps + 1)) for v in targets}
    agent.reset(mission)
    states = [state]
    commands = np.full((n_steps + 1, 3), np.nan)
    tracked = {v.name: np.zeros(n_steps + 1, dtype=bool) for v in targets}
    n_tracks = np.zeros(n_steps + 1, dtype=np.int64)
    counts = {s.name: 0 for s in sensors} | ({"truth": 0} if "truth" in agent.sensors else {})
    heading_unwrapped = state.heading
    for k in range(n_steps + 1):
        t = t0 + k * dt
        frames: list[SensorFrame] = []
        for s in sensors:
            times = frame_times[s.name]
            while next_frame[s.name] < times.size and times[next_frame[s.name]] + periods[s.name] <= t + 1e-9:
                i = next_frame[s.name]
                tk = float(times[i])
                frames.append(SensorFrame(s.name, tk, s.capture(tk, i), _interp_nav(states, dt, tk), _mount(s)))
                next_frame[s.name] += 1
                counts[s.name] += 1
        frames.sort(key=lambda f: f.time)
        if "truth" in agent.sensors:
            truth = tuple(
                TruthTarget(
                    v.name,
                    float(target_states[v.name].north[k]),
                    float(target_states[v.name].east[k]),
                    float(target_states[v.name].v_north[k]),
                    float(target_states[v.name].v_east[k]),
                    *((v.dimensions.length, v.dimensions.beam) if v.dimensions is not None else (5.0, 2.0)),
                )
                for v in targets
            )
            frames.append(SensorFrame("truth", t, truth, _navigation(state)))
            counts["truth"] += 1
        command = agent.step(t, frames, _navigation(state))
        est: list[TrackEstimate] = agent.tracks()
        n_tracks[k] = len(est)
        for v in targets:
            tn, te = target_states[v.name].north[k], target_states[v.name].east[k]
            tracked[v.name][k] = any(math.hypot(e.north - tn, e.east - te) <= TRACK_ASSOCIATION_M for e in est)
        if k == n_steps:
            break
        if isinstance(command, SetPoint):
            nums = (command.speed, command.heading, 0.0)
            tau = pilot.force(MILLIAMPERE, state, command.speed, command.heading)
            state = step_force(model, thrusters, state, tau, dt, pilot.cone(command.speed))
        elif isinstance(command, ForceCommand):
            nums = (command.X, command.Y, command.N)
            state = step_force(model, thrusters, state, (command.X, command.Y, command.N), dt)
        elif isinstance(command, ThrusterCommand):
            nums = (command.angles[0], *command.thrusts[:2])
            state = step_thrusters(model, thrusters, state, (tuple(command.angles), tuple(command.thrusts)), dt)
        else:
            raise ParameterError("agent", f"agent {agent.name!r} answered {type(command).__name__}, not a command")
        if not all(math.isfinite(x) for x in nums):
            raise ParameterError("agent", f"agent {agent.name!r} answered a non-finite command {command} at t = {t}")
        commands[k] = nums
        state = dataclasses.replace(state, time=t0 + (k + 1) * dt)  # no drift of the clock over thousands of steps
        heading_unwrapped += math.remainder(state.heading - states[-1].heading, 2 * math.pi)
        states.append(state)
        track.append(state.time, state.north, state.east, heading_unwrapped)
        if scene is not None:
            scene.update_trajectory(own.name, track)
    own_arr = np.array([[s.north, s.east, s.heading, s.u, s.v, s.r] for s in states])
    time = np.array([s.time for s in states])
    tgt = {
        v.name: np.column_stack([target_states[v.name].north, target_states[v.name].east, target_states[v.name].heading])
        for v in targets
    }
    sizes = {
        v.name: ((float(v.dimensions.length), float(v.dimensions.beam)) if v.dimensions is not None else (5.0, 2.0))
        for v in scenario.vessels
    }
    return RunRecord(
        scenario.name,
        agent.name,
        int(scenario.seed),
        mission,
        time,
        own_arr,
        commands,
        tgt,
        tracked,
        n_tracks,
        counts,
        sizes,
        own.name,
        harbour,
    )
