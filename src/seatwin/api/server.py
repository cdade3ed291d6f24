"""The Gemini ``Simulation`` gRPC service (``GeminiOSPInterface``): ``seatwin serve``.

:func:`serve` starts a gRPC server whose ``DoStep``/``SetStartTime`` drive a
:class:`~seatwin.api.lockstep.LockstepSimulation` (the one loop, recording as ``seatwin simulate``
does). Calls are handled one at a time, and ``DoStep`` answers only when the frames it made due are
recorded (lock-step). Every call runs on the server's one worker thread, where the simulation is
built and closed too (a camera's EGL context works only on the thread that created it; each thread
gets its own, :func:`seatwin.render.context.create_context`). A bad request (NaN or infinite pose,
wrong pose count, time going backwards, ``DoStep`` before ``SetStartTime``) is answered with status
``INVALID_ARGUMENT`` and a message; the server keeps serving. :meth:`ServerHandle.stop` finishes
the bag (manifest ``completed: true``).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent import futures
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import grpc

from seatwin.api.lockstep import LockstepSettings, LockstepSimulation
from seatwin.api.proto import gemini_osp_pb2, gemini_osp_pb2_grpc
from seatwin.errors import InputError, ParameterError
from seatwin.sim.loop import SimulationResult

MAX_MESSAGE_BYTES = 256 * 1024 * 1024
"""gRPC message-size limit both ways: a 612×512 RGB image is 0.94 MB, a dense VLP-16 cloud
(16 × 1800 points × 24 bytes) 0.69 MB; the 4 MB default would do, but a denser lidar would not."""

GRPC_OPTIONS = [
    ("grpc.max_receive_message_length", MAX_MESSAGE_BYTES),
    ("grpc.max_send_message_length", MAX_MESSAGE_BYTES),
]

SERVER_OPTIONS = [*GRPC_OPTIONS, ("grpc.so_reuseport", 0)]
"""A port in use is an error, not shared with the other server."""


_STEP_OK = gemini_osp_pb2.StepResponse(success=True)


def _message(exc: InputError) -> str:
    return exc.render(exc.param) if isinstance(exc, ParameterError) else str(exc)


class SimulationServicer(gemini_osp_pb2_grpc.SimulationServicer):
    """``DoStep``/``SetStartTime`` onto a :class:`LockstepSimulation`, one call at a time."""

    def __init__(self, sim: LockstepSimulation):
        self.sim = sim
        self.lock = threading.Lock()
        self.steps = 0
        self.rejected = 0

    def _call(self, fn: Callable[[], Any], context: grpc.ServicerContext) -> None:
        with self.lock:
            try:
                fn()
            except InputError as exc:
                self.rejected += 1
                context.abort(grpc.StatusCode.INVALID_ARGUMENT, _message(exc))
            except Exception as exc:  # noqa: BLE001 - the server keeps serving; the client is told why
                self.rejected += 1
                context.abort(grpc.StatusCode.INTERNAL, f"{type(exc).__name__}: {exc}")

    def DoStep(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - Gemini's name
        poses = [(p.north, p.east, p.heading) for p in request.VesselPoses]
        self._call(lambda: self.sim.step(poses, request.time), context)
        self.steps += 1
        return _STEP_OK

    def SetStartTime(self, request: Any, context: grpc.ServicerContext) -> Any:  # noqa: N802 - Gemini's name
        self._call(lambda: self.sim.set_start_time(request.time), context)
        return gemini_osp_pb2.SetStartTimeResponse(success=True)


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
    _result: SimulationResult | None = None

    @property
    def address(self) -> str:
        return f"{self.host}:{self.port}"

    def stop(self, grace: float | None = 1.0, completed: bool = True) -> SimulationResult:
        """Stop serving (calls in flight finish within ``grace`` s), run the frames still due, finish the bag."""
        if self._result is None:
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
    **changes: Any,
) -> ServerHandle:
    """Start the ``Simulation`` server recording into the new run directory ``run_dir``; return its handle.

    ``settings`` (default :class:`LockstepSettings`) with ``changes`` to its fields; ``port`` 0
    picks a free one; ``on_frame(sensor, t, frame, data)`` sees every frame (streaming).
    """
    from seatwin.settings import validated

    settings = validated(LockstepSettings, {**(settings or LockstepSettings()).model_dump(), **changes})
    check_port(port)
    worker = futures.ThreadPoolExecutor(max_workers=1, thread_name_prefix="seatwin-serve")
    try:
        sim = worker.submit(LockstepSimulation, run_dir, settings, on_frame=on_frame).result()
    except BaseException:
        worker.shutdown()
        raise
    server = grpc.server(worker, options=SERVER_OPTIONS)
    servicer = SimulationServicer(sim)
    gemini_osp_pb2_grpc.add_SimulationServicer_to_server(servicer, server)
    try:
        bound = bind(server, host, port)
    except ParameterError:
        worker.submit(sim.close, completed=False, error="the server could not start").result()
        worker.shutdown()
        raise
    server.start()
    return ServerHandle(server, host, bound, sim, servicer, worker)
