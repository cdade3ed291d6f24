"""Lock-step simulation: vessel poses arrive step by step (Gemini's ``DoStep``), the one loop follows.

:class:`LockstepSimulation` is what ``seatwin serve`` runs behind its gRPC ``Simulation`` service,
usable without gRPC. Each :meth:`~LockstepSimulation.step` appends every vessel's pose to its
trajectory (a scenario that grows), re-poses the scene, and advances the one loop
(:class:`seatwin.sim.loop.Stepper`) over every frame whose inputs are now known:

* a frame at ``t`` runs once ``t + span`` has arrived, ``span`` being the longest sensor frame
  (a lidar sweep, 0.1 s at 10 Hz; a radar rotation) — a sweep sees its vessels interpolated between
  the steps around each firing, exactly as ``seatwin simulate`` does;
* and once ``t`` lies before the second-to-last step, so the ground truth's velocities (central
  differences at the samples) are those of the whole trajectory.

Hence a run driven with a scenario's own samples records what ``seatwin simulate`` records for
the same window, frame for frame (the frames lag the steps by at most ``span`` + one step).
:meth:`~LockstepSimulation.close` runs the frames still due and finishes the bag.
"""

from __future__ import annotations

import datetime as dt
import math
import time as _time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from pydantic import Field

from seatwin.errors import InputError, ParameterError
from seatwin.geo import unwrap, wrap_to_pi
from seatwin.recording import VesselPose
from seatwin.recording.manifest import MANIFEST_NAME
from seatwin.scenario import Role, Scenario, Trajectory, Vessel
from seatwin.scenario.defaults import NOMINAL_DIMENSIONS, OWNSHIP_NAME, RAVNKLOA, TARGETS_BY_COLUMN
from seatwin.settings import Settings
from seatwin.sim.loop import SimulationResult, Stepper
from seatwin.sim.poses import PoseTable, poses_from_scenario
from seatwin.sim.sensors import GroundTruthSensor, SimSensor

DEFAULT_VESSELS: tuple[str, ...] = (TARGETS_BY_COLUMN[1][0], TARGETS_BY_COLUMN[2][0], OWNSHIP_NAME)
"""The Gemini CSV's V1, V2, V3 order: Havfruen, Finn, milliAmpere (the ownship)."""

TIME_QUANTUM_S = 1e-3
"""``StepRequest.time`` (a float32 of seconds since the start) is rounded to this: float32 resolves
8 µs at 60 s and 0.25 ms at an hour, so a step sent as ``k * 0.1`` lands exactly on ``k * 0.1``."""


class LockstepSettings(Settings):
    """What ``seatwin serve`` simulates: the vessels posed by each step and the ownship's sensors."""

    vessels: tuple[str, ...] = Field(
        DEFAULT_VESSELS, min_length=1, description="Vessel names in the order of StepRequest.VesselPoses."
    )
    ownship: str | None = Field(OWNSHIP_NAME, description="The vessel carrying the sensors (one of vessels; None: no sensors).")
    sensors: tuple[Literal["lidar", "radar"], ...] = Field(
        ("lidar",), description="Ownship sensors (empty: ground truth only); ground truth is always recorded."
    )
    seed: int = Field(0, description="Seed of every random draw.")
    lidar_mode: Literal["raycast", "depthbuffer", "depthbuffer-legacy"] = Field("raycast", description="Lidar range model.")
    lidar_preset: Literal["vlp16", "vlp16-thesis"] = Field("vlp16", description="Lidar preset.")
    fmt: Literal["mcap", "sqlite3", "ros1"] = Field("mcap", description="Bag format.")
    radar_spokes: bool = Field(False, description="Keep each radar rotation's raw spokes (for streaming).")
    ground_truth_rate_hz: float = Field(10.0, gt=0, description="Rate of the ground-truth topics [Hz].")


def parse_start_time(text: str) -> float:
    """``SetStartTimeRequest.time`` as POSIX seconds: a number (Gemini's convention) or an ISO 8601 time (UTC if naive)."""
    s = str(text).strip()
    try:
        t = float(s)
    except ValueError:
        try:
            d = dt.datetime.fromisoformat(s.replace("Z", "+00:00"))
        except ValueError:
            raise ParameterError("time", f"expected POSIX seconds or an ISO 8601 time, got {text!r}") from None
        t = (d if d.tzinfo else d.replace(tzinfo=dt.UTC)).timestamp()
    if not math.isfinite(t):
        raise ParameterError("time", f"expected a finite start time, got {text!r}")
    return t


def _model_of(name: str) -> tuple[str, Any]:
    key = name.lower()
    return (key, NOMINAL_DIMENSIONS[key]) if key in NOMINAL_DIMENSIONS else ("generic", None)


class _LiveTrajectory(Trajectory):
    """Received samples, already checked (finite, times increasing): a :class:`Trajectory` with the
    same interpolation and ``numpy.gradient`` velocities, built without re-checking (once a step)."""

    def __post_init__(self) -> None:
        self.heading = np.asarray(wrap_to_pi(self.heading), dtype=float)
        self._heading_unwrapped = unwrap(self.heading)
        self._v_north, self._v_east, self._yaw_rate = np.gradient(
            np.stack([self.north, self.east, self._heading_unwrapped]), self.time, axis=1
        )


class _LiveGroundTruth(GroundTruthSensor):
    """Ground truth whose pose table covers only the frames not yet run (the trajectories keep
    only their recent samples live; :class:`GroundTruthSensor` tables every frame from the start)."""

    def __init__(self, scenario: Scenario, rate_hz: float):
        super().__init__(scenario, rate_hz)
        self._offset = 0

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        times = super(GroundTruthSensor, self).frame_times(t0, t1)  # Periodic's
        new = times[self._offset :]
        self._table = PoseTable.from_scenario(self.scenario, new) if len(new) else None
        self._start_index, self._offset = self._offset, len(times)
        return times

    def capture(self, t: float, frame: int) -> list[VesselPose]:
        table, k = self._table, frame - getattr(self, "_start_index", 0)
        if table is not None and 0 <= k < len(table.times) and table.times[k] == t:
            return table.poses(k)
        return poses_from_scenario(self.scenario, t)


class LockstepSimulation:
    """A recording driven step by step: :meth:`set_start_time`, :meth:`step` (any number), :meth:`close`."""

    def __init__(
        self,
        run_dir: str | Path,
        settings: LockstepSettings | None = None,
        *,
        on_frame: Callable[[SimSensor, float, int, Any], None] | None = None,
    ):
        from seatwin.recording import RecordingWriter

        self.settings = s = settings or LockstepSettings()
        self.run_dir = Path(run_dir)
        if (self.run_dir / MANIFEST_NAME).exists():
            raise InputError(self.run_dir, "a recording exists here already; choose a new run directory")
        if s.ownship is not None and s.ownship not in s.vessels:
            raise ParameterError("ownship", f"{s.ownship!r} is not one of the vessels {list(s.vessels)}")
        if len(set(s.vessels)) != len(s.vessels):
            raise ParameterError("--vessels", f"vessel names must be unique, got {list(s.vessels)}")
        if s.sensors and s.ownship is None:
            raise ParameterError("sensors", "sensors need an ownship to carry them")
        placeholder = Trajectory(np.array([0.0, 1.0]), np.zeros(2), np.zeros(2), np.zeros(2), source="seatwin serve")
        vessels = []
        for name in s.vessels:
            model, dims = _model_of(name)
            role = Role.OWNSHIP if name == s.ownship else Role.TARGET
            vessels.append(Vessel(name, role, placeholder, model, dims))
        self.scenario = Scenario("served", vessels, origin=RAVNKLOA, seed=s.seed, source="seatwin serve")
        self.sensors = self._sensors()
        self._scenes = {id(sc): sc for sc in (self._scene_of(x) for x in self.sensors) if sc is not None}
        self.span_s = max((1.0 / float(x.rate_hz) for x in self.sensors if not isinstance(x, GroundTruthSensor)), default=0.0)
        self.on_frame = on_frame
        self.run_dir.mkdir(parents=True, exist_ok=True)
        self.writer = RecordingWriter(
            self.run_dir,
            s.fmt,
            sensors={x.name: x.parameters() for x in self.sensors},
            origin=self.scenario.origin,
            seed=s.seed,
            metadata={"scenario": "served", "served_by": "seatwin serve", "settings": s.model_dump(mode="json")},
        )
        self.start: float | None = None
        self.times: list[float] = []
        self._poses: list[NDArray[np.float64]] = []  # per step: (vessels, 3) north, east, heading [rad]
        self.stepper: Stepper | None = None
        self.closed = False
        self._wall0 = _time.perf_counter()

    def _sensors(self) -> list[SimSensor]:
        s = self.settings
        gt = _LiveGroundTruth(self.scenario, s.ground_truth_rate_hz)
        if not s.sensors:
            return [gt]
        from seatwin.sim.run import scenario_sensors
        from seatwin.sim.settings import SimulationSettings

        sim = SimulationSettings(
            sensors=s.sensors,
            seed=s.seed,
            lidar_mode=s.lidar_mode,
            lidar_preset=s.lidar_preset,
            fmt=s.fmt,
            radar_spokes=s.radar_spokes,
            ground_truth_rate_hz=s.ground_truth_rate_hz,
        )
        sensors = scenario_sensors(self.scenario, sim)
        return [gt if isinstance(x, GroundTruthSensor) else x for x in sensors]

    @staticmethod
    def _scene_of(sensor: SimSensor) -> Any:
        lidar = getattr(sensor, "lidar", None)
        return getattr(lidar, "scene", None) if lidar is not None else getattr(sensor, "scene", None)

    # -- the Gemini calls ---------------------------------------------------------------------------

    def set_start_time(self, text: str) -> float:
        """Set the POSIX start time (before the first step); return it."""
        if self.closed:
            raise ParameterError("time", "the simulation is closed")
        if self.times:
            raise ParameterError("time", "the start time cannot change after the first step")
        self.start = parse_start_time(text)
        return self.start

    def step(self, poses: Sequence[Sequence[float]], time: float) -> int:
        """Pose the vessels (north, east [m], heading [° clockwise from north], in ``settings.vessels``
        order) at ``time`` seconds since the start; run the frames now due; return how many ran."""
        if self.closed:
            raise ParameterError("time", "the simulation is closed")
        if self.start is None:
            raise ParameterError("time", "DoStep before SetStartTime: set the start time first")
        p = np.asarray(poses, dtype=np.float64).reshape(-1, 3) if len(poses) else np.zeros((0, 3))
        n = len(self.settings.vessels)
        if len(p) != n:
            raise ParameterError("VesselPoses", f"expected {n} poses ({', '.join(self.settings.vessels)}), got {len(p)}")
        if not np.isfinite(p).all():
            i = int(np.flatnonzero(~np.isfinite(p).all(axis=1))[0])
            raise ParameterError("VesselPoses", f"pose {i} ({self.settings.vessels[i]}) is not finite: {p[i].tolist()}")
        if not math.isfinite(time):
            raise ParameterError("time", f"expected a finite time, got {time!r}")
        rel = round(float(time) / TIME_QUANTUM_S) * TIME_QUANTUM_S
        t = self.start + rel
        if self.times and not t > self.times[-1]:
            raise ParameterError("time", f"time must increase: got {time!r} s after a step at {self.times[-1] - self.start!r} s")
        row = p.copy()
        row[:, 2] = np.deg2rad(row[:, 2])
        self.times.append(t)
        self._poses.append(row)
        if self.stepper is None:
            self.stepper = Stepper(self.sensors, self.writer, t, on_frame=self.on_frame)
        if len(self.times) < 2:
            return 0
        self._repose()
        return self.stepper.advance_to(min(self.times[-2], t - self.span_s))

    def close(self, completed: bool = True, error: str | None = None) -> SimulationResult:
        """Run the frames still due (each with its whole span received), save the received scenario, finish the bag."""
        if not self.closed:
            self.closed = True
            try:
                if completed and self.stepper is not None and len(self.times) >= 2:
                    last = self.times[-1]
                    self.stepper.advance_to(last - self.span_s + (1e-5 if self.span_s > 0 else 0.0))
                    self._save_scenario()
            except BaseException as exc:
                self.writer.close(completed=False, error=f"{type(exc).__name__}: {exc}")
                raise
            self.writer.close(completed=completed, error=error)
        wall = _time.perf_counter() - self._wall0
        st = self.stepper
        sim_s = (st.done_t - st.t0) if st is not None else 0.0
        counts = st.counts if st is not None else {x.name: 0 for x in self.sensors}
        rec = self.writer.timing.get("total_s", self.writer.timing["serialize_s"] + self.writer.timing["write_s"])
        return SimulationResult(self.run_dir, completed, sim_s, wall, dict(counts), rec)

    # -- the growing scenario -------------------------------------------------------------------------

    def _trajectory(self, i: int, first: int, kind: type[Trajectory] = Trajectory) -> Trajectory:
        rows = np.asarray([p[i] for p in self._poses[first:]])
        return kind(np.asarray(self.times[first:]), rows[:, 0], rows[:, 1], rows[:, 2], source="seatwin serve")

    def _repose(self) -> None:
        """Every vessel's live trajectory: the samples from two before the loop's horizon on (every
        frame still to run lies after the horizon; the one before gives central differences there)."""
        times = self.times
        horizon = self.stepper.horizon if self.stepper is not None else times[0]
        first = max(0, min(len(times) - 2, int(np.searchsorted(times, horizon, side="right")) - 3))
        for i, v in enumerate(self.scenario.vessels):
            v.trajectory = self._trajectory(i, first, _LiveTrajectory)
            for scene in self._scenes.values():
                scene.update_trajectory(v.name, v.trajectory)

    def received_scenario(self) -> Scenario:
        """Every pose received so far, as a scenario (needs two steps)."""
        vessels = [
            Vessel(v.name, v.role, self._trajectory(i, 0), v.model, v.dimensions) for i, v in enumerate(self.scenario.vessels)
        ]
        return Scenario("served", vessels, origin=self.scenario.origin, seed=self.scenario.seed, source="seatwin serve")

    def _save_scenario(self) -> None:
        from seatwin.scenario.load import save_scenario
        from seatwin.sim.run import RESOLVED_SCENARIO

        save_scenario(self.received_scenario(), self.run_dir / RESOLVED_SCENARIO)
