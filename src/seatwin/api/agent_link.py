"""The out-of-process agent transport: an agent in another process, driven over gRPC in lock-step.

seatwin serves (``agent_link.proto``'s ``seatwin.agentlink.AgentLink`` and Gemini's
``gemini.forcecontrol.ForceControl`` on one address); the agent is a client. :class:`RemoteAgent` has the
:class:`~seatwin.agents.Agent` shape, so :func:`seatwin.verification.run_closed_loop` drives it like an agent in
process: ``reset(mission)`` queues a ``Mission``; ``step(t, frames, navigation)`` queues a ``Step`` (its own state in
doubles, Gemini's ``NavigationRequest`` of it, the frames: truth targets in doubles, lidar sweeps as Gemini's
``LidarStreamingRequest``, radar plots in doubles) and waits for the agent's one command for that step
(``SetVelocity``, ``ApplyForce`` in doubles, Gemini's ``ApplyForce`` in floats, ``ApplyThrust``). The agent fetches
each queued observation with ``Observe`` (answered as soon as there is one), or sends its command with ``Act``,
answered with the next observation: one call a step. A slow agent slows the loop; an agent
that does not answer within ``timeout_s``, or whose launched process exits, is one
:class:`~seatwin.errors.ParameterError` naming the agent, step and cause. :meth:`RemoteAgent.close` sends
``Finished``, stops the server and ends a launched process.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
import threading
import time
from collections import deque
from collections.abc import Sequence
from concurrent import futures
from types import SimpleNamespace
from typing import Any

import grpc
import numpy as np

from seatwin.agents.interface import (
    Command,
    ForceCommand,
    Mission,
    Navigation,
    SensorFrame,
    SetPoint,
    ThrusterCommand,
    TrackEstimate,
)
from seatwin.api.proto import agent_link_pb2, agent_link_pb2_grpc, force_control_pb2, force_control_pb2_grpc
from seatwin.api.server import bind
from seatwin.api.streaming import lidar_request, navigation_request
from seatwin.errors import ParameterError

SENSORS = ("truth", "lidar", "radar")
"""The frames the transport carries."""

TIMEOUT_S = 30.0
"""How long a step waits for the agent's command."""

STARTUP_TIMEOUT_S = 60.0
"""How long a run's first step waits (the agent's start-up, its reading of the mission)."""

POLL_S = 0.05
"""How often a waiting step looks whether a launched agent process has exited."""

_OK = agent_link_pb2.CommandResponse(success=True)


def _state(nav: Navigation) -> Any:
    return agent_link_pb2.State(time=nav.time, north=nav.north, east=nav.east, heading=nav.heading, u=nav.u, v=nav.v, r=nav.r)


def _gemini_navigation(nav: Navigation, vessel: str) -> Any:
    pose = SimpleNamespace(
        north=nav.north, east=nav.east, down=0.0, heading=nav.heading, v_north=nav.v_north, v_east=nav.v_east, yaw_rate=nav.r
    )
    return navigation_request(nav.time, SimpleNamespace(**vars(pose), name=vessel))


def _frame(frame: SensorFrame) -> Any:
    pb = agent_link_pb2
    out = pb.Frame(sensor=frame.sensor, time=frame.time, navigation=_state(frame.navigation))
    if frame.mount is not None:
        out.mount.extend([*frame.mount.translation, *np.asarray(frame.mount.rotation, dtype=float).reshape(9)])
    if frame.sensor == "truth":
        out.truth.targets.extend(
            pb.Target(name=t.name, north=t.north, east=t.east, v_north=t.v_north, v_east=t.v_east, length=t.length, beam=t.beam)
            for t in frame.data
        )
    elif frame.sensor == "lidar":
        out.lidar.CopyFrom(lidar_request("lidar", frame.time, frame.data))
    elif frame.sensor == "radar":
        r = frame.data
        a = r.antenna
        out.radar.CopyFrom(
            pb.RadarPlots(
                antenna_north=a.north,
                antenna_east=a.east,
                antenna_heading=a.heading,
                antenna_height=a.height,
                range=r.range_m,
                azimuth=r.azimuth,
                north=r.north,
                east=r.east,
                cells=r.n_cells,
                extent=r.extent_m,
                intensity=r.intensity,
            )
        )
    else:
        raise ParameterError("sensors", f"the gRPC agent transport carries {', '.join(SENSORS)} frames, not {frame.sensor!r}")
    return out


def _tracks(tracks: Sequence[Any]) -> list[TrackEstimate]:
    return [TrackEstimate(int(t.id), t.north, t.east, t.v_north, t.v_east) for t in tracks]


class _Link(agent_link_pb2_grpc.AgentLinkServicer, force_control_pb2_grpc.ForceControlServicer):
    """The servicer: the observations queued for the agent, the step awaiting a command, the command."""

    def __init__(self, vessel: str):
        self.vessel = vessel
        self.cond = threading.Condition()
        self.outbox: deque[Any] = deque()
        self.pending: int | None = None
        self.command: tuple[Command, list[TrackEstimate]] | None = None
        self.closed = False

    def Observe(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - the proto's name
        with self.cond:
            while not self.outbox and not self.closed and context.is_active():
                self.cond.wait(0.5)
            if self.outbox:
                return self.outbox.popleft()
        return agent_link_pb2.Observation(finished=agent_link_pb2.Finished(reason="the simulation has ended"))

    def Act(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802
        kind = request.WhichOneof("command")
        if kind is None:
            context.abort(grpc.StatusCode.INVALID_ARGUMENT, "an Action needs a command: velocity, force or thrust")
        {"velocity": self.SetVelocity, "force": self.ApplyForce, "thrust": self.ApplyThrust}[kind](
            getattr(request, kind), context
        )
        return self.Observe(request, context)

    def _answer(self, step: int | None, command: Command, tracks: Sequence[Any], context: grpc.ServicerContext) -> Any:
        values = (
            (command.speed, command.heading)
            if isinstance(command, SetPoint)
            else (command.X, command.Y, command.N)
            if isinstance(command, ForceCommand)
            else (*command.angles, *command.thrusts)
        )
        if not all(math.isfinite(x) for x in values):
            context.abort(grpc.StatusCode.INVALID_ARGUMENT, f"non-finite command {command}")
        with self.cond:
            if self.pending is None:
                context.abort(grpc.StatusCode.FAILED_PRECONDITION, "no step awaits a command: call Observe first")
            if step is not None and step != self.pending:
                context.abort(
                    grpc.StatusCode.FAILED_PRECONDITION, f"the command names step {step}; step {self.pending} awaits one"
                )
            if self.command is not None:
                context.abort(grpc.StatusCode.ALREADY_EXISTS, f"step {self.pending} already has its command")
            self.command = (command, _tracks(tracks))
            self.cond.notify_all()
        return _OK

    def SetVelocity(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802
        return self._answer(request.step, SetPoint(request.speed, request.heading), request.tracks, context)

    def ApplyForce(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - both services' name
        if isinstance(request, force_control_pb2.ForceRequest):  # Gemini's: floats, for the vessel named, no step
            if request.vesselId != self.vessel:
                context.abort(grpc.StatusCode.NOT_FOUND, f"vesselId: expected {self.vessel!r}, got {request.vesselId!r}")
            f = request.generalizedForce
            self._answer(None, ForceCommand(f.x, f.y, f.n), (), context)
            return force_control_pb2.ForceResponse(success=True)
        return self._answer(request.step, ForceCommand(request.x, request.y, request.n), request.tracks, context)

    def ApplyThrust(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802
        if not request.angles or len(request.angles) != len(request.thrusts):
            context.abort(grpc.StatusCode.INVALID_ARGUMENT, "expected as many thrusts as angles (one per thruster), at least one")
        return self._answer(request.step, ThrusterCommand(tuple(request.angles), tuple(request.thrusts)), request.tracks, context)


class RemoteAgent:
    """An agent in another process (module docstring).

    ``address``: where seatwin listens (``HOST:PORT``; port 0 picks a free one). ``command``: the agent's command
    line, launched now, with ``{address}`` replaced by the bound address (also in its environment as
    ``SEATWIN_AGENT_ADDRESS``) and ``{python}`` by this Python interpreter; without it the agent is started by
    someone else and connects to ``address``.
    ``timeout_s``: how long a step waits for its command, ``startup_timeout_s`` a run's first step.
    ``sensors``: the frames it is sent (:data:`SENSORS`); ``vessel``: the ownship's name Gemini's ``ApplyForce``
    must give. Use it as a context manager (or call :meth:`close`)."""

    def __init__(
        self,
        name: str = "grpc",
        sensors: Sequence[str] = ("truth",),
        *,
        address: str = "127.0.0.1:0",
        command: Sequence[str] | None = None,
        timeout_s: float = TIMEOUT_S,
        startup_timeout_s: float = STARTUP_TIMEOUT_S,
        vessel: str = "milliAmpere",
        cwd: str | os.PathLike[str] | None = None,
    ):
        bad = [s for s in sensors if s not in SENSORS]
        if bad or not sensors:
            raise ParameterError("sensors", f"the gRPC agent transport carries some of {', '.join(SENSORS)}, not {list(sensors)}")
        for param, value in (("timeout_s", timeout_s), ("startup_timeout_s", startup_timeout_s)):
            if not (value > 0 and math.isfinite(value)):
                raise ParameterError(param, f"expected a timeout > 0 s, got {value!r}")
        host, sep, port = address.rpartition(":")
        if not sep or not host or not port.isdigit():
            raise ParameterError("address", f"expected HOST:PORT to listen on, got {address!r}")
        self.name, self.sensors, self.timeout_s = name, tuple(sensors), float(timeout_s)
        self.startup_timeout_s = float(startup_timeout_s)
        self._link = _Link(vessel)
        self._server = grpc.server(futures.ThreadPoolExecutor(max_workers=4, thread_name_prefix="seatwin-agent"))
        agent_link_pb2_grpc.add_AgentLinkServicer_to_server(self._link, self._server)
        force_control_pb2_grpc.add_ForceControlServicer_to_server(self._link, self._server)
        self.address = f"{host}:{bind(self._server, host.strip('[]'), int(port))}"
        self._server.start()
        self._tracks: list[TrackEstimate] = []
        self._index = 0
        self._process: subprocess.Popen[bytes] | None = None
        self._log: Any = None
        if command is not None:
            self._launch([str(c).replace("{address}", self.address).replace("{python}", sys.executable) for c in command], cwd)

    def _launch(self, argv: list[str], cwd: str | os.PathLike[str] | None) -> None:
        if not argv:
            self.close()
            raise ParameterError("command", "expected the agent's command line, got an empty one")
        self._log = tempfile.TemporaryFile()  # noqa: SIM115 - open while the process runs; closed in close()
        env = {**os.environ, "SEATWIN_AGENT_ADDRESS": self.address}
        try:
            self._process = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=self._log, stderr=self._log, env=env, cwd=cwd)
        except OSError as exc:
            self.close()
            raise ParameterError("command", f"cannot start the agent {argv[0]!r}: {exc.strerror}") from None

    def _where(self) -> str:
        return f"agent {self.name!r} at {self.address}"

    def _exited(self) -> str | None:
        """Why a launched agent process is gone (its exit code and last output line), or None while it runs."""
        if self._process is None or self._process.poll() is None:
            return None
        self._log.seek(0)
        lines = [ln for ln in self._log.read().decode(errors="replace").splitlines() if ln.strip()]
        last = f": {lines[-1].strip()}" if lines else ""
        return f"its process exited with code {self._process.returncode}{last}"

    def reset(self, mission: Mission) -> None:
        pb = agent_link_pb2
        m = pb.Mission(
            start_north=mission.start_north,
            start_east=mission.start_east,
            goal_north=mission.goal_north,
            goal_east=mission.goal_east,
            cruise_speed=mission.cruise_speed,
            harbour=mission.harbour,
            length=mission.length,
            beam=mission.beam,
            vessel_id=self._link.vessel,
            sensors=list(self.sensors),
        )
        with self._link.cond:
            self._link.outbox.append(pb.Observation(mission=m))
            self._link.cond.notify_all()
        self._index, self._tracks = 0, []

    def step(self, time_s: float, frames: Sequence[SensorFrame], navigation: Navigation) -> Command:
        pb, link, k = agent_link_pb2, self._link, self._index
        obs = pb.Observation(
            step=pb.Step(
                index=k,
                time=time_s,
                own=_state(navigation),
                navigation=_gemini_navigation(navigation, link.vessel),
                frames=[_frame(f) for f in frames],
            )
        )
        limit = self.startup_timeout_s if k == 0 else self.timeout_s
        deadline = time.monotonic() + limit
        with link.cond:
            link.pending, link.command = k, None
            link.outbox.append(obs)
            link.cond.notify_all()
            waited = False
            while link.command is None:
                left = deadline - time.monotonic()
                # the process is looked at only once a wait brought no command (waitpid is not free at every step)
                why = self._exited() if waited else None
                if why is None and left <= 0:
                    why = f"it did not answer within {limit:g} s"
                if why is not None:
                    link.pending = None
                    raise ParameterError("agent", f"{self._where()} failed at step {k} (t = {time_s:.3f} s): {why}")
                link.cond.wait(min(left, POLL_S) if self._process is not None else left)
                waited = True
            command, self._tracks = link.command
            link.pending, link.command = None, None
        self._index += 1
        return command

    def tracks(self) -> list[TrackEstimate]:
        return list(self._tracks)

    def close(self, grace_s: float = 5.0) -> int | None:
        """Tell the agent the simulation has ended, stop serving, end a launched process (killed if it is still
        running after ``grace_s``); return its exit code (None if none was launched)."""
        with self._link.cond:
            self._link.closed = True
            self._link.cond.notify_all()
        code = None
        if self._process is not None:
            try:
                code = self._process.wait(grace_s)
            except subprocess.TimeoutExpired:
                self._process.kill()
                code = self._process.wait()
            self._log.close()
            self._process = None
        self._server.stop(0.5).wait()
        return code

    def __enter__(self) -> RemoteAgent:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
