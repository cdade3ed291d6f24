"""Gemini's simulator-side gRPC services: ``seatwin serve``.

:func:`serve` starts a gRPC server whose ``Simulation.DoStep``/``SetStartTime`` (``GeminiOSPInterface``)
drive a :class:`~seatwin.api.lockstep.LockstepSimulation` (the one loop, recording as ``seatwin
simulate`` does), and ``DoStep`` answers only when the frames it made due are recorded (lock-step).
On the same address: ``gemini.forcecontrol.ForceControl.ApplyForce`` (the named vessel is then moved
by forces, :mod:`seatwin.api.motion`), ``sensordata.Sensordata`` and
``sensormanagement.SensorManagement`` (:mod:`seatwin.api.sensor_services`).

Concurrency: several gRPC worker threads take calls, so a client that is slow to send (or never
sends) its request body holds one of them, not the server; the calls are applied one at a time in
the order they take the servicer's lock, each on the one simulation thread, where the simulation is
built and closed too (a camera's EGL context works only on the thread that created it). A
connection lives at most ``connection_age_s`` (gRPC's ``max_connection_age``: the client is told to
reconnect, transparently for gRPC clients), plus a grace for the call in flight: so a request body
that never comes is given up after that time.

A bad request (NaN or infinite pose, wrong pose count, time going backwards or jumping more than
``max_step_s``, ``DoStep`` before ``SetStartTime``, a message over ``max_message_bytes``) is answered
with status ``INVALID_ARGUMENT`` (``RESOURCE_EXHAUSTED`` for the size) and a message, and changes
nothing; the server keeps serving. Once ``interrupt`` is set (Ctrl-C/SIGTERM) a step in progress
stops before its next frame and new steps are refused (``UNAVAILABLE``). :meth:`ServerHandle.stop`
finishes the bag (manifest ``completed: true``, or ``false`` if a step was interrupted).
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from concurrent import futures
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import grpc

from seatwin.api.channel import GRPC_OPTIONS, MAX_MESSAGE_BYTES  # noqa: F401 - GRPC_OPTIONS: re-exported
from seatwin.api.lockstep import LockstepSettings, LockstepSimulation
from seatwin.api.motion import VesselDynamics
from seatwin.api.proto import (
    force_control_pb2,
    force_control_pb2_grpc,
    sensordata_pb2,
    sensordata_pb2_grpc,
    sensormanagement_pb2,
    sensormanagement_pb2_grpc,
    simulation_pb2,
    simulation_pb2_grpc,
)
from seatwin.api.sensor_services import (
    RADAR,
    FrameBoard,
    ServedSensor,
    find_sensor,
    sensordata_bytes,
    sensordata_stream,
    served_sensors,
)
from seatwin.errors import InputError, ParameterError
from seatwin.recording import RecordingError
from seatwin.sim.loop import SimulationResult, StepInterrupted

STREAM_MAX_MESSAGE_BYTES = 64 * 1024 * 1024
"""What ``record-stream`` accepts: a 612×512 RGB image is 0.94 MB, a dense VLP-16 cloud (16 × 1800
points × 24 bytes) 0.69 MB, a 4K RGB image 25 MB."""

SERVE_MAX_MESSAGE_BYTES = 1024 * 1024
"""What ``serve`` accepts by default: a ``StepRequest`` is 17 bytes a vessel (60,000 vessels in 1 MiB)."""

POSE_BYTES = 17
"""The wire size of one ``Pose`` in a ``StepRequest`` (three float32 fields and their tags, the entry's tag and length)."""

CONNECTION_AGE_S = 60.0
"""How long a connection lives before the client is asked to reconnect (gRPC ``max_connection_age``)."""

CONNECTION_GRACE_S = 10.0
"""How long a call in flight on an aged connection may still take (``max_connection_age_grace``):
a request body that never comes is given up after ``CONNECTION_AGE_S`` + this."""

SERVER_WORKERS = 8
"""gRPC worker threads: calls waiting for their bodies (or for the lock) do not hold up the others."""


def server_options(
    max_message_bytes: int, connection_age_s: float = CONNECTION_AGE_S, grace_s: float = CONNECTION_GRACE_S
) -> list[tuple[str, int]]:
    """A server's gRPC options: receive at most ``max_message_bytes``; a connection lives ``connection_age_s``
    (+ ``grace_s`` for the call in flight); a port in use is an error, not shared (``so_reuseport`` off)."""
    if not int(max_message_bytes) >= 1024:
        raise ParameterError("max_message_bytes", f"expected at least 1024 bytes, got {max_message_bytes!r}")
    if not connection_age_s > 0 or not grace_s >= 0:
        raise ParameterError("connection_age_s", f"expected a positive age and grace, got {connection_age_s!r}, {grace_s!r}")
    return [
        ("grpc.max_receive_message_length", int(max_message_bytes)),
        ("grpc.max_send_message_length", MAX_MESSAGE_BYTES),
        ("grpc.max_connection_age_ms", max(1, int(connection_age_s * 1000))),
        ("grpc.max_connection_age_grace_ms", int(grace_s * 1000)),
        ("grpc.so_reuseport", 0),
    ]


_STEP_OK = simulation_pb2.StepResponse(success=True)


def _message(exc: InputError) -> str:
    return exc.render(exc.param) if isinstance(exc, ParameterError) else str(exc)


class SimulationServicer(simulation_pb2_grpc.SimulationServicer):
    """``DoStep``/``SetStartTime`` onto a :class:`LockstepSimulation`: one call at a time (``lock``), each
    run on the simulation's thread (``worker``); refused once ``interrupt`` is set."""

    def __init__(self, sim: LockstepSimulation, worker: futures.ThreadPoolExecutor, interrupt: threading.Event):
        self.sim, self.worker, self.interrupt = sim, worker, interrupt
        self.lock = threading.Lock()
        self.steps = 0
        self.rejected = 0
        self._counting = threading.Lock()

    def _refuse(self, context: grpc.ServicerContext, code: grpc.StatusCode, message: str) -> None:
        with self._counting:
            self.rejected += 1
        context.abort(code, message)

    def call(self, fn: Callable[[], Any], context: grpc.ServicerContext) -> None:
        with self.lock:
            if self.interrupt.is_set() or self.sim.closed:
                self._refuse(context, grpc.StatusCode.UNAVAILABLE, "the server is shutting down; no more steps are taken")
            try:
                self.worker.submit(fn).result()
            except RecordingError as exc:  # the disk, not the request
                self._refuse(context, grpc.StatusCode.INTERNAL, str(exc))
            except InputError as exc:
                self._refuse(context, grpc.StatusCode.INVALID_ARGUMENT, _message(exc))
            except StepInterrupted as exc:
                self._refuse(context, grpc.StatusCode.UNAVAILABLE, f"the server is shutting down: the step was {exc}")
            except Exception as exc:  # noqa: BLE001 - the server keeps serving; the client is told why
                self._refuse(context, grpc.StatusCode.INTERNAL, f"{type(exc).__name__}: {exc}")

    def DoStep(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - Gemini's name
        n, expected = len(request.VesselPoses), len(self.sim.settings.vessels)
        if n != expected:  # before converting anything
            self._refuse(
                context,
                grpc.StatusCode.INVALID_ARGUMENT,
                f"VesselPoses: expected {expected} poses ({', '.join(self.sim.settings.vessels)}), got {n}",
            )
        poses = [(p.north, p.east, p.heading) for p in request.VesselPoses]

        def step() -> None:  # on the simulation thread, one at a time
            self.sim.step(poses, request.time, request.stepSize, interrupt=self.interrupt)
            self.steps += 1

        self.call(step, context)
        return _STEP_OK

    def SetStartTime(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - Gemini's name
        self.call(lambda: self.sim.set_start_time(request.time), context)
        return simulation_pb2.SetStartTimeResponse(success=True)


class ForceControlServicer(force_control_pb2_grpc.ForceControlServicer):
    """``ApplyForce`` onto the simulation, one call at a time with the steps (the Simulation servicer's lock)."""

    def __init__(self, calls: SimulationServicer):
        self.calls = calls

    def ApplyForce(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - Gemini's name
        f = request.generalizedForce
        self.calls.call(lambda: self.calls.sim.apply_force(request.vesselId, f.x, f.y, f.n), context)
        return force_control_pb2.ForceResponse(success=True)


class SensorManagementServicer(sensormanagement_pb2_grpc.SensorManagementServicer):
    """Lists the served sensors (with the address their ``Sensordata`` is served on); starts and stops their rendering."""

    def __init__(self, calls: SimulationServicer, sensors: list[ServedSensor], host: str, port: int):
        self.calls, self.sensors, self.host, self.port = calls, sensors, host, port

    def _message(self, s: ServedSensor) -> Any:
        pb = sensormanagement_pb2
        kind = pb.SensorType.Value(s.type)
        return pb.Sensor(id=s.id, type=kind, sensorWidth=s.width, sensorHeight=s.height, ipAddress=self.host, port=self.port)

    def _render(self, sensor_id: int, on: bool, context: grpc.ServicerContext) -> bool:
        found = [s for s in self.sensors if s.id == sensor_id]
        if found:
            self.calls.call(lambda: self.calls.sim.set_rendering(found[0].name, on), context)
        return bool(found)

    def StartRendering(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - Gemini's name
        return sensormanagement_pb2.StartRenderingResponse(success=self._render(request.sensorID, True, context))

    def StopRendering(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802
        return sensormanagement_pb2.StopRenderingResponse(success=self._render(request.sensorID, False, context))

    def GetAllSensorsOfType(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802
        kind = sensormanagement_pb2.SensorType.Name(request.type)
        return sensormanagement_pb2.AllSensorsOfTypeResponse(sensors=[self._message(s) for s in self.sensors if s.type == kind])

    def GetAllSensorsOnVessel(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802
        vessels = self.calls.sim.settings.vessels
        if request.vesselID not in vessels:
            expected = f"vesselID: expected one of the served vessels {list(vessels)}"
            context.abort(grpc.StatusCode.NOT_FOUND, f"{expected}, got {request.vesselID!r}")
        on = [self._message(s) for s in self.sensors if s.vessel == request.vesselID]
        return sensormanagement_pb2.AllSensorsOnVesselResponse(sensors=on)


class SensordataServicer(sensordata_pb2_grpc.SensordataServicer):
    """A sensor's latest frame (``TransferSensordata``) or every new one (``StreamSensordata``); ``operation``
    names the sensor."""

    def __init__(self, board: FrameBoard, sensors: list[ServedSensor], radar_spokes: bool):
        self.board, self.sensors, self.radar_spokes = board, sensors, radar_spokes

    def _sensor(self, request: Any, context: grpc.ServicerContext) -> ServedSensor:
        try:
            sensor = find_sensor(self.sensors, request.operation)
        except ParameterError as exc:
            context.abort(grpc.StatusCode.INVALID_ARGUMENT, _message(exc))
            raise  # abort raises; this keeps type checkers content
        if sensor.type == RADAR and not self.radar_spokes:
            context.abort(grpc.StatusCode.FAILED_PRECONDITION, "the radar's spokes are not kept: serve with radar_spokes on")
        return sensor

    def TransferSensordata(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - Gemini's name
        sensor = self._sensor(request, context)
        seq, _, data = self.board.latest(sensor.source)
        payload = sensordata_bytes(sensor, data) if seq else b""
        return sensordata_pb2.SensordataResponse(data=payload, dataLength=len(payload))

    def StreamSensordata(self, request: Any, context: grpc.ServicerContext) -> Iterator[Any]:  # noqa: N802
        sensor = self._sensor(request, context)
        for _, payload in sensordata_stream(self.board, sensor, context.is_active):
            yield sensordata_pb2.SensordataResponse(data=payload, dataLength=len(payload))


def check_port(port: int) -> None:
    if not 0 <= int(port) <= 65535:
        raise ParameterError("port", f"expected a TCP port in 0..65535 (0: any free one), got {port!r}")


def bind(server: grpc.Server, host: str, port: int) -> int:
    """Bind ``server`` to ``host:port`` (0: a free port) without TLS; return the port."""
    check_port(port)
    address = f"[{host}]:{port}" if ":" in host else f"{host}:{port}"
    try:
        bound = server.add_insecure_port(address)
    except RuntimeError as exc:
        raise ParameterError("port", f"cannot listen on {address}: {exc}") from None
    if not bound:
        raise ParameterError("port", f"cannot listen on {address} (in use?)")
    return bound


@dataclass
class ServerHandle:
    """A running ``Simulation`` server: its port, the simulation, :meth:`stop`."""

    server: grpc.Server
    host: str
    port: int
    sim: LockstepSimulation
    servicer: SimulationServicer
    worker: futures.ThreadPoolExecutor
    """The one thread every call runs on (and the simulation was built on)."""
    interrupt: threading.Event
    """Set: steps are refused and a step in progress stops before its next frame (Ctrl-C, SIGTERM)."""
    board: FrameBoard
    """Each sensor's latest frame (``Sensordata``)."""
    sensors: list[ServedSensor]
    """What ``SensorManagement`` lists."""
    _result: SimulationResult | None = None

    @property
    def address(self) -> str:
        return f"{self.host}:{self.port}"

    def stop(self, grace: float | None = 1.0, completed: bool = True) -> SimulationResult:
        """Stop serving (calls in flight finish within ``grace`` s), run the frames still due (unless a step
        was interrupted), finish the bag."""
        if self._result is None:
            self.board.close()  # StreamSensordata calls end
            self.server.stop(grace).wait()
            with self.servicer.lock:
                self._result = self.worker.submit(self.sim.close, completed=completed).result()
            self.worker.shutdown()
        return self._result


def serve(
    run_dir: str | Path,
    settings: LockstepSettings | None = None,
    *,
    port: int = 50051,
    host: str = "127.0.0.1",
    on_frame: Callable[[Any, float, int, Any], None] | None = None,
    interrupt: threading.Event | None = None,
    max_message_bytes: int = SERVE_MAX_MESSAGE_BYTES,
    connection_age_s: float = CONNECTION_AGE_S,
    connection_grace_s: float = CONNECTION_GRACE_S,
    workers: int = SERVER_WORKERS,
    dynamics: VesselDynamics | None = None,
    **changes: Any,
) -> ServerHandle:
    """Start the ``Simulation`` server recording into the new run directory ``run_dir``; return its handle.

    ``settings`` (default :class:`LockstepSettings`) with ``changes`` to its fields; ``port`` 0
    picks a free one; ``on_frame(sensor, t, frame, data)`` sees every frame (streaming);
    ``interrupt``: an event whose setting (a signal handler's) refuses further steps and stops the one
    in progress; the gRPC limits as :func:`server_options`; ``workers`` gRPC threads; ``dynamics``: what
    a vessel moved by ``ForceControl`` follows (default :class:`~seatwin.api.motion.LinearManoeuvring3DOF`).
    """
    from seatwin.settings import validated

    settings = validated(LockstepSettings, {**(settings or LockstepSettings()).model_dump(), **changes})
    check_port(port)
    options = server_options(max_message_bytes, connection_age_s, connection_grace_s)
    if not 1 <= int(workers) <= 256:
        raise ParameterError("workers", f"expected 1..256 gRPC worker threads, got {workers!r}")
    interrupt = interrupt if interrupt is not None else threading.Event()
    worker = futures.ThreadPoolExecutor(max_workers=1, thread_name_prefix="seatwin-serve")
    board = FrameBoard()

    def frame_hook(sensor: Any, t: float, frame: int, data: Any) -> None:
        board.on_frame(sensor, t, frame, data)
        if on_frame is not None:
            on_frame(sensor, t, frame, data)

    try:
        sim = worker.submit(LockstepSimulation, run_dir, settings, on_frame=frame_hook, dynamics=dynamics).result()
    except BaseException:
        worker.shutdown()
        raise
    server = grpc.server(
        futures.ThreadPoolExecutor(max_workers=int(workers), thread_name_prefix="seatwin-grpc"),
        options=options,
        maximum_concurrent_rpcs=4 * int(workers),
    )
    servicer = SimulationServicer(sim, worker, interrupt)
    sensors = served_sensors(sim.sensors, settings.ownship)
    simulation_pb2_grpc.add_SimulationServicer_to_server(servicer, server)
    force_control_pb2_grpc.add_ForceControlServicer_to_server(ForceControlServicer(servicer), server)
    sensordata_pb2_grpc.add_SensordataServicer_to_server(SensordataServicer(board, sensors, settings.radar_spokes), server)
    management = SensorManagementServicer(servicer, sensors, host, port)
    sensormanagement_pb2_grpc.add_SensorManagementServicer_to_server(management, server)
    try:
        bound = bind(server, host, port)
    except ParameterError:
        worker.submit(sim.close, completed=False, error="the server could not start").result()
        worker.shutdown()
        raise
    management.port = bound
    server.start()
    return ServerHandle(server, host, bound, sim, servicer, worker, interrupt, board, sensors)
