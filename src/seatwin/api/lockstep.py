"""Lock-step simulation: vessel poses arrive step by step (Gemini's ``DoStep``), the one loop follows.

:class:`LockstepSimulation` is what ``seatwin serve`` runs behind its gRPC ``Simulation`` service,
usable without gRPC. Each :meth:`~LockstepSimulation.step` appends every vessel's pose to its
samples (:class:`~seatwin.api.live.LiveTracks`: a few float operations a step, written to its arrays
once per frame) and
advances the one loop (:class:`seatwin.sim.loop.Stepper`) over every frame whose inputs are now known,
each sensor on its own horizon:

* a lidar sweep or radar rotation at ``t`` runs once ``t + span`` has arrived (``span``: the sweep,
  0.1 s at 10 Hz; the rotation) — it sees its vessels interpolated between the steps around each
  firing, exactly as ``seatwin simulate`` does; a camera frame once ``t`` has arrived;
* a ground-truth frame once ``t`` lies before the second-to-last step, so its velocities (central
  differences at the samples) are those of the whole trajectory.

The scene is re-posed (a view of the recent samples, no copy) only when a sensor that looks at it
has a frame to run. A run driven with a scenario's own samples records what ``seatwin simulate``
records for the same window, frame for frame (the frames lag the steps by at most their ``span`` +
one step); a radar rotation that would end after the last step is not recorded.

The first frame's velocities: ``simulate`` takes central differences at the window's start (the
scenario goes on before it); a server has no pose before its first step, so there they are one-sided,
as ``simulate`` records them for the received poses alone (the run's ``scenario.yaml``). A client that
wants ``simulate``'s values sends a step before the start (``time`` < 0): such steps only extend the
trajectories — the frames start at the start time (or the first step after it).
:meth:`~LockstepSimulation.close` runs the frames still due and finishes the bag.
"""

from __future__ import annotations

import datetime as dt
import math
import threading
import time as _time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, field_validator

from seatwin.api.live import LiveGroundTruth, LiveTracks
from seatwin.api.motion import ForceDriven, LinearManoeuvring3DOF, ScenarioReplay, VesselDynamics, VesselMotion, body_velocity
from seatwin.defaults import DEFAULT_SENSORS
from seatwin.errors import InputError, ParameterError
from seatwin.layout.harbours import check_harbour_spec
from seatwin.recording.manifest import MANIFEST_NAME
from seatwin.scenario import Role, Scenario, Trajectory, Vessel
from seatwin.scenario.defaults import OWNSHIP_NAME, RAVNKLOA, TARGETS_BY_COLUMN, model_of_name
from seatwin.sim.loop import NOT_RENDERED, SimulationResult, StepInterrupted, Stepper
from seatwin.sim.sensors import GroundTruthSensor, LidarSensor, SimSensor
from seatwin.sim.settings import BagOptions

DEFAULT_VESSELS: tuple[str, ...] = (TARGETS_BY_COLUMN[1][0], TARGETS_BY_COLUMN[2][0], OWNSHIP_NAME)
"""The Gemini CSV's V1, V2, V3 order: Havfruen, Finn, milliAmpere (the ownship)."""

MAX_TIME_S = 1e6
"""The largest ``StepRequest.time`` taken: a float32 resolves 0.06 s there (a POSIX time sent by
mistake, 1.6e9, would resolve 128 s)."""

MIN_MAX_STEP_S = 1.0
"""Without ``max_step_s``, a step may advance max(10 × its ``stepSize``, this) seconds."""

TIME_QUANTUM_S = 1e-3
"""``StepRequest.time`` (a float32 of seconds since the start) is rounded to this: float32 resolves
8 µs at 60 s and 0.25 ms at an hour, so a step sent as ``k * 0.1`` lands exactly on ``k * 0.1``."""


class LockstepSettings(BagOptions):
    """What ``seatwin serve`` simulates: the vessels posed by each step and the ownship's sensors."""

    vessels: tuple[str, ...] = Field(
        DEFAULT_VESSELS, min_length=1, description="Vessel names in the order of StepRequest.VesselPoses."
    )
    ownship: str | None = Field(OWNSHIP_NAME, description="The vessel carrying the sensors (one of vessels; None: no sensors).")
    sensors: tuple[Literal["lidar", "radar", "camera"], ...] = Field(
        DEFAULT_SENSORS, description="Ownship sensors (empty: ground truth only); ground truth is always recorded."
    )
    seed: int = Field(0, description="Seed of every random draw.")
    lidar_mode: Literal["raycast", "depthbuffer", "depthbuffer-legacy", "depthbuffer-plane"] = Field(
        "raycast", description="Lidar range model."
    )
    lidar_preset: Literal["vlp16", "vlp16-thesis"] = Field("vlp16", description="Lidar preset.")
    fmt: Literal["mcap", "sqlite3", "ros1"] = Field("mcap", description="Bag format.")
    radar_spokes: bool = Field(False, description="Keep each radar rotation's raw spokes (for streaming).")
    ground_truth_rate_hz: float = Field(10.0, gt=0, description="Rate of the ground-truth topics [Hz].")
    max_step_s: float | None = Field(
        None,
        gt=0,
        le=3600,
        description="The most seconds one step may advance past the last (None: max(10 × the request's stepSize, 1 s)).",
    )
    harbour: str = Field(
        "default",
        description="Harbour the steps' poses are in: 'default', 'ravnkloa' (the Gemini scenarios' frame), "
        "'none' or a land raster (.bin/.yaml).",
    )

    @field_validator("harbour")
    @classmethod
    def _harbour(cls, v: str) -> str:
        return check_harbour_spec(v)


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


class _Due:
    """A sensor as the stepper sees it in lock-step: its frames only up to ``limit`` (set each step);
    ``before_capture(t)`` runs first (the scene's re-posing); a sensor whose served name is in ``off``
    (``SensorManagement.StopRendering``) makes no frame — a rig camera's image is left out of the rig's
    frame, the rig makes none once all its cameras are off. Everything else is the sensor's own."""

    def __init__(
        self, sensor: SimSensor, span_s: float, before_capture: Callable[[float], None] | None = None, off: set[str] | None = None
    ):
        self.sensor, self.span_s, self.before_capture = sensor, span_s, before_capture
        self.off = off if off is not None else set()
        self.limit = -math.inf
        self.ground_truth = isinstance(sensor, GroundTruthSensor)
        """A ground-truth frame waits for the step after it (its velocities are central differences)."""
        self._tail = getattr(sensor, "frame_times_from", None)
        mounts = getattr(sensor, "mounts", None)
        self.cameras = [f"camera/{m.name}" for m in mounts] if mounts is not None else None
        """A camera rig's served names (``camera/<name>``, as its images are streamed), else None."""

    def __getattr__(self, name: str) -> Any:
        return getattr(self.sensor, name)

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        return self.sensor.frame_times(t0, min(t1, self.limit))

    def frame_times_from(self, t0: float, t1: float, first: int) -> NDArray[np.float64]:
        t1 = min(t1, self.limit)
        return self._tail(t0, t1, first) if self._tail is not None else self.sensor.frame_times(t0, t1)[first:]

    def capture(self, t: float, frame: int) -> Any:
        off = self.off
        if off and (all(c in off for c in self.cameras) if self.cameras is not None else self.sensor.name in off):
            return NOT_RENDERED
        if self.before_capture is not None:
            self.before_capture(t)
        data = self.sensor.capture(t, frame)
        if off and self.cameras is not None:
            data = [img for img in data if f"camera/{img.name}" not in off]
        return data

    def record(self, writer: Any, t: float, data: Any) -> None:
        if self.cameras is not None and len(data) != len(self.cameras):  # some cameras of the rig are off
            names = {img.name for img in data}
            rig = _Subrig(self.sensor, [m for m in self.sensor.mounts if m.name in names])  # type: ignore[attr-defined]
            type(self.sensor).record(rig, writer, t, data)  # type: ignore[arg-type]
        else:
            self.sensor.record(writer, t, data)


class _Subrig:
    """A camera rig with only some of its mounts (what its ``record`` writes when some cameras are off)."""

    def __init__(self, rig: Any, mounts: list[Any]):
        self._rig, self.mounts = rig, mounts

    def __getattr__(self, name: str) -> Any:
        return getattr(self._rig, name)


def _span_of(sensor: SimSensor) -> float:
    """How long a frame looks at the world: a lidar sweep, a radar rotation; 0 for an instant (camera, ground truth)."""
    from seatwin.sim.radar import RadarSensor

    return 1.0 / float(sensor.rate_hz) if isinstance(sensor, LidarSensor | RadarSensor) else 0.0  # type: ignore[attr-defined]


class LockstepSimulation:
    """A recording driven step by step: :meth:`set_start_time`, :meth:`step` (any number), :meth:`close`."""

    def __init__(
        self,
        run_dir: str | Path,
        settings: LockstepSettings | None = None,
        *,
        on_frame: Callable[[SimSensor, float, int, Any], None] | None = None,
        dynamics: VesselDynamics | None = None,
    ):
        from seatwin.recording import RecordingWriter

        self.settings = s = settings or LockstepSettings()
        self.run_dir = Path(run_dir)
        if (self.run_dir / MANIFEST_NAME).exists():
            raise InputError(self.run_dir, "a recording exists here already; choose a new run directory")
        if s.ownship is not None and s.ownship not in s.vessels:
            raise ParameterError("ownship", f"{s.ownship!r} is not one of the vessels {list(s.vessels)}")
        if len(set(s.vessels)) != len(s.vessels):
            raise ParameterError("vessels", f"vessel names must be unique, got {list(s.vessels)}")
        if s.sensors and s.ownship is None:
            raise ParameterError("sensors", "sensors need an ownship to carry them")
        placeholder = Trajectory(np.array([0.0, 1.0]), np.zeros(2), np.zeros(2), np.zeros(2), source="seatwin serve")
        vessels = []
        for name in s.vessels:
            model, dims = model_of_name(name)
            role = Role.OWNSHIP if name == s.ownship else Role.TARGET
            vessels.append(Vessel(name, role, placeholder, model, dims))
        self.scenario = Scenario("served", vessels, origin=RAVNKLOA, seed=s.seed, source="seatwin serve")
        self.tracks = LiveTracks(len(vessels))
        self.dynamics: VesselDynamics = dynamics if dynamics is not None else LinearManoeuvring3DOF()
        """What a force-driven vessel follows (:mod:`seatwin.api.motion`)."""
        self.motions: list[VesselMotion] = [ScenarioReplay() for _ in vessels]
        self._driven: list[int] = []
        """Vessels whose motion is not the steps' poses (force-driven)."""
        self._first_forces: dict[int, tuple[float, float, float]] = {}
        """Forces applied before the first step: the vessel starts at rest at its first pose."""
        self.sensors = self._sensors()
        harbour, water_mask = self._harbour()
        self.scenario.environment["harbour"] = harbour
        self._scenes = {id(sc): sc for sc in (self._scene_of(x) for x in self.sensors) if sc is not None}
        self.rendering_off: set[str] = set()
        """Served sensor names whose rendering is stopped (:meth:`set_rendering`)."""
        self._due = [
            _Due(x, _span_of(x), self._repose if self._scene_of(x) is not None else None, self.rendering_off)
            for x in self.sensors
        ]
        self._scene_due = [d for d in self._due if d.before_capture is not None]
        self._posed_n = 0
        """Samples the scene was last posed with."""
        self._scene_from = -math.inf
        self.on_frame = on_frame
        self.run_dir.mkdir(parents=True, exist_ok=True)
        self.writer = RecordingWriter(
            self.run_dir,
            s.fmt,
            **s.writer_options(),
            sensors={x.name: x.parameters() for x in self.sensors},
            origin=self.scenario.origin,
            seed=s.seed,
            metadata={
                "scenario": "served",
                "served_by": "seatwin serve",
                "settings": s.model_dump(mode="json"),
                "harbour": harbour,
                "tracking": {"map": water_mask},
            },
        )
        self.start: float | None = None
        self.stepper: Stepper | None = None
        self.closed = False
        self.interrupted: str | None = None
        """Why a step stopped before its frames were all run (then no step is taken any more)."""
        self._wall0 = _time.perf_counter()

    def _sensors(self) -> list[SimSensor]:
        s = self.settings
        gt = LiveGroundTruth(self.scenario, self.tracks, s.ground_truth_rate_hz, self.scenario.origin)
        if not s.sensors:
            return [gt]
        from seatwin.sim.run import scenario_sensors
        from seatwin.sim.settings import SimulationSettings

        sim = SimulationSettings(
            sensors=s.sensors,
            harbour=s.harbour,
            seed=s.seed,
            lidar_mode=s.lidar_mode,
            lidar_preset=s.lidar_preset,
            fmt=s.fmt,
            radar_spokes=s.radar_spokes,
            ground_truth_rate_hz=s.ground_truth_rate_hz,
        )
        sensors = scenario_sensors(self.scenario, sim)
        return [gt if isinstance(x, GroundTruthSensor) else x for x in sensors]

    def _harbour(self) -> tuple[str, str]:
        """The harbour (a name or a raster's absolute path) and the water mask ``seatwin track`` should use."""
        from seatwin.sim.run import run_harbour, water_mask_hint
        from seatwin.sim.settings import SimulationSettings

        sim = SimulationSettings(harbour=self.settings.harbour)
        try:
            return run_harbour(self.scenario, sim), water_mask_hint(self.scenario, sim)
        except InputError as exc:
            raise ParameterError("harbour", exc.detail) from None

    @staticmethod
    def _scene_of(sensor: SimSensor) -> Any:
        lidar = getattr(sensor, "lidar", None)
        return getattr(lidar, "scene", None) if lidar is not None else getattr(sensor, "scene", None)

    # -- the Gemini calls ---------------------------------------------------------------------------

    @property
    def times(self) -> NDArray[np.float64]:
        """POSIX times of the steps received so far."""
        return self.tracks.times

    def set_start_time(self, text: str) -> float:
        """Set the POSIX start time (before the first step); return it."""
        if self.closed:
            raise ParameterError("time", "the simulation is closed")
        if self.tracks.n:
            raise ParameterError("time", "the start time cannot change after the first step")
        self.start = parse_start_time(text)
        return self.start

    def max_step(self, step_size: float) -> float:
        """The most seconds a step with ``stepSize`` = ``step_size`` may advance past the last."""
        s = self.settings.max_step_s
        return float(s) if s is not None else max(10.0 * step_size, MIN_MAX_STEP_S)

    def set_rendering(self, name: str, on: bool) -> None:
        """Start or stop the frames of served sensor ``name`` (``lidar``, ``radar``, ``camera/<name>``: see
        :func:`seatwin.api.sensor_services.served_sensors`) from the next frame on."""
        (self.rendering_off.discard if on else self.rendering_off.add)(name)

    def vessel_index(self, name: str) -> int:
        """The index of vessel ``name`` in ``settings.vessels``."""
        try:
            return self.settings.vessels.index(name)
        except ValueError:
            expected = f"expected one of the served vessels {list(self.settings.vessels)}"
            raise ParameterError("vesselId", f"{expected}, got {name!r}") from None

    def apply_force(self, vessel: str, x: float, y: float, n: float) -> None:
        """Gemini's ``ApplyForce``: from now on vessel ``vessel`` is moved by the body-frame force (X, Y [N],
        N [N·m]), held until the next call; the poses the steps send for it are ignored from the next step on.

        Applied before the first step, the vessel starts at rest at the first step's pose; after, from its
        last received pose and velocity."""
        if self.closed or self.interrupted:
            raise ParameterError("time", "the simulation is closed")
        i = self.vessel_index(vessel)
        force = (float(x), float(y), float(n))
        if not all(math.isfinite(f) for f in force):
            raise ParameterError("generalizedForce", f"expected finite forces, got {list(force)}")
        motion = self.motions[i]
        if isinstance(motion, ForceDriven):
            motion.set_force(*force)
        elif not self.tracks.n:
            self._first_forces[i] = force
        else:
            t = self.tracks.sample_time(-1)
            north, east, heading, vn, ve, r = self.tracks.last(i)
            motion = ForceDriven(self.dynamics, t, np.array([north, east, heading]), body_velocity(heading, vn, ve, r))
            motion.set_force(*force)
            self.motions[i] = motion
            self._driven.append(i)

    def step(
        self, poses: Sequence[Sequence[float]], time: float, step_size: float = 0.0, interrupt: threading.Event | None = None
    ) -> int:
        """Pose the vessels (north, east [m], heading [° clockwise from north], in ``settings.vessels``
        order) at ``time`` seconds since the start (< 0: history before the start, no frames); run the
        frames now due; return how many ran.

        Everything is checked before anything changes (a refused step changes nothing): the poses,
        ``time`` (finite, within ±``MAX_TIME_S``, after the last step by at most :meth:`max_step`)
        and ``step_size`` (finite, ≥ 0). ``interrupt`` set stops the frames before the next one
        (:class:`~seatwin.sim.loop.StepInterrupted`); the run then ends at :meth:`close` without more frames."""
        if self.closed or self.interrupted:
            raise ParameterError("time", "the simulation is closed")
        if self.start is None:
            raise ParameterError("time", "DoStep before SetStartTime: set the start time first")
        p = np.array(poses, dtype=np.float64).reshape(-1, 3) if len(poses) else np.zeros((0, 3))
        n = len(self.settings.vessels)
        if len(p) != n:
            raise ParameterError("VesselPoses", f"expected {n} poses ({', '.join(self.settings.vessels)}), got {len(p)}")
        if not np.isfinite(p).all():
            i = int(np.flatnonzero(~np.isfinite(p).all(axis=1))[0])
            raise ParameterError("VesselPoses", f"pose {i} ({self.settings.vessels[i]}) is not finite: {p[i].tolist()}")
        if not math.isfinite(time):
            raise ParameterError("time", f"expected a finite time, got {time!r}")
        if not abs(time) <= MAX_TIME_S:
            raise ParameterError(
                "time", f"expected seconds since the start time (|time| ≤ {MAX_TIME_S:g}), got {time!r}: a POSIX time?"
            )
        if not (math.isfinite(step_size) and step_size >= 0):
            raise ParameterError("stepSize", f"expected a finite step size ≥ 0, got {step_size!r}")
        rel = round(float(time) / TIME_QUANTUM_S) * TIME_QUANTUM_S
        t = self.start + rel
        tracks = self.tracks
        if tracks.n:
            last = tracks.sample_time(-1)
            if not t > last:
                raise ParameterError("time", f"time must increase: got {time!r} s after a step at {last - self.start!r} s")
            limit = self.max_step(step_size)
            if t - last > limit + TIME_QUANTUM_S / 2:
                raise ParameterError(
                    "time",
                    f"a step may advance at most {limit:g} s (max_step; stepSize {step_size:g}): got {time!r} s "
                    f"after a step at {last - self.start!r} s",
                )
        p[:, 2] = np.deg2rad(p[:, 2])
        if self._first_forces:  # after every check: a refused step changes nothing
            for i, force in self._first_forces.items():
                self.motions[i] = ForceDriven(self.dynamics, t, p[i])
                self.motions[i].set_force(*force)  # type: ignore[attr-defined]
                self._driven.append(i)
            self._first_forces = {}
        for i in self._driven:
            p[i] = self.motions[i].pose(t, p[i])
        tracks.append(t, p[:, 0], p[:, 1], p[:, 2])
        for i in self._driven:
            self.motions[i].commit(t)
        if self.stepper is None and rel >= 0:
            hook = self.on_frame
            on_frame = None if hook is None else (lambda d, t, k, data: hook(d.sensor, t, k, data))  # the sensor, not its _Due
            self.stepper = Stepper(self._due, self.writer, max(self.start, tracks.sample_time(0)), on_frame=on_frame)
        if self.stepper is None or tracks.n < 2:
            return 0
        prev = tracks.sample_time(-2)
        limits = [prev if d.ground_truth else t - d.span_s for d in self._due]
        try:
            return self._advance(limits, interrupt)
        except StepInterrupted as exc:
            self.interrupted = f"the step at {rel:g} s was {exc}"
            raise

    def _advance(self, limits: Sequence[float], interrupt: threading.Event | None = None) -> int:
        """Run every sensor's frames before its new limit (the stepper's horizon: the latest limit)."""
        # Every frame of a scene sensor before its previous limit has run: the scene needs the samples from there on.
        self._scene_from = min((d.limit for d in self._scene_due), default=math.inf)
        for d, limit in zip(self._due, limits, strict=True):
            d.limit = limit
        return self.stepper.advance_to(max(limits), interrupt=interrupt)  # type: ignore[union-attr]

    def close(self, completed: bool = True, error: str | None = None) -> SimulationResult:
        """Run the frames still due (each with its whole span received; none after an interrupted step),
        save the received scenario, finish the bag (``completed: false`` with the reason after an interrupted
        step). A frame failing here (an error, not a signal) ends the run there: the bag is finished with
        ``completed: false`` and the error, and the result says incomplete (nothing is raised)."""
        if self.interrupted and error is None:
            completed, error = False, f"interrupted: {self.interrupted}"
        if not self.closed:
            self.closed = True
            try:
                if self.interrupted and self.tracks.n >= 2:
                    self._save_scenario()
                if completed and self.stepper is not None and self.tracks.n >= 2:
                    last = self.tracks.sample_time(-1)
                    self._advance([last - d.span_s + (1e-5 if d.span_s > 0 else 0.0) for d in self._due])
                    self._save_scenario()
            except Exception as exc:  # noqa: BLE001 - the bag is finished with the error, whatever failed
                completed, error = False, f"the frames still due failed: {type(exc).__name__}: {exc}"
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

    def _repose(self, t: float) -> None:
        """Before a scene sensor's frame at ``t``: pose every vessel of the scene along its samples from
        the one before the earliest frame still to run (views of the samples; once per step)."""
        tracks = self.tracks
        if self._posed_n == tracks.n:
            return
        self._posed_n = tracks.n
        earliest = min(t, self._scene_from)
        first = max(0, min(tracks.n - 2, int(np.searchsorted(tracks.times, earliest, side="right")) - 2))
        for i, v in enumerate(self.scenario.vessels):
            track = tracks.window(i, first)
            for scene in self._scenes.values():
                scene.update_trajectory(v.name, track)

    def received_scenario(self) -> Scenario:
        """Every pose received so far, as a scenario (needs two steps)."""
        vessels = [
            Vessel(v.name, v.role, self.tracks.trajectory(i), v.model, v.dimensions) for i, v in enumerate(self.scenario.vessels)
        ]
        return Scenario(
            "served",
            vessels,
            origin=self.scenario.origin,
            seed=self.scenario.seed,
            source="seatwin serve",
            environment=dict(self.scenario.environment),
        )

    def _save_scenario(self) -> None:
        from seatwin.scenario.load import save_scenario
        from seatwin.sim.run import RESOLVED_SCENARIO

        save_scenario(self.received_scenario(), self.run_dir / RESOLVED_SCENARIO)
