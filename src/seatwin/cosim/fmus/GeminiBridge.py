# ruff: noqa: ANN001, ANN003, ANN201, ANN202, ANN204
"""The ``GeminiBridge`` FMU (FMI 2.0 co-simulation, built by ``pythonfmu``): sends vessel poses to a Gemini
``Simulation`` gRPC server (``seatwin serve``) with ``DoStep``, in lock-step.

Inputs ``<name>.north``, ``<name>.east`` [m], ``<name>.heading`` [deg] per vessel (connected from a
``ScenarioPlayer``) and ``start_time`` (POSIX); parameter ``address`` (``host:port``). At its first
step it sends ``SetStartTime``; at each step at time ``t`` it sends the poses it holds (the pose at
``t``) with ``time = t`` and ``stepSize``, and returns when the server has answered. The messages are
encoded here by hand (``GeminiOSPInterface`` wire format; ``tests/cosim`` checks the bytes against
the generated protobuf classes), so the FMU needs only ``grpcio`` in its Python.
"""

import json
import os
import struct

from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real, String


def _key(field, wire):
    return bytes([(field << 3) | wire])


def _varint(n):
    out = bytearray()
    while True:
        b = n & 0x7F
        n >>= 7
        if n:
            out.append(b | 0x80)
        else:
            out.append(b)
            return bytes(out)


def _float(field, v):
    return _key(field, 5) + struct.pack("<f", v) if v != 0.0 else b""


def step_request(poses, time, step_size):
    """``GeminiOSPInterface.StepRequest`` bytes: ``poses`` [(north, east, heading)], ``time``, ``stepSize``."""
    out = bytearray()
    for n, e, h in poses:
        p = _float(1, n) + _float(2, e) + _float(3, h)
        out += _key(1, 2) + _varint(len(p)) + p
    return bytes(out + _float(2, time) + _float(3, step_size))


def start_time_request(text):
    """``GeminiOSPInterface.SetStartTimeRequest`` bytes."""
    b = text.encode("utf-8")
    return _key(1, 2) + _varint(len(b)) + b if b else b""


def success(data):
    """``success`` of a ``StepResponse``/``SetStartTimeResponse``."""
    return data == b"\x08\x01"


class GeminiBridge(Fmi2Slave):
    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.author = "seatwin"
        self.description = "Sends vessel poses to a Gemini Simulation gRPC server with DoStep (lock-step)."
        with open(os.path.join(self.resources, "bridge.json"), encoding="utf-8") as f:
            meta = json.load(f)
        self.vessels = list(meta["vessels"])
        self.address = str(meta.get("address", "127.0.0.1:50051"))
        self.start_time = 0.0
        self._pose = [0.0] * (3 * len(self.vessels))
        self._channel = None
        self._started = False
        self.register_variable(String("address", causality=Fmi2Causality.parameter, variability=Fmi2Variability.tunable))
        self.register_variable(Real("start_time", causality=Fmi2Causality.input))
        for i, name in enumerate(self.vessels):
            for j, q in enumerate(("north", "east", "heading")):
                k = 3 * i + j
                self.register_variable(
                    Real(
                        f"{name}.{q}",
                        causality=Fmi2Causality.input,
                        getter=lambda k=k: self._pose[k],
                        setter=lambda v, k=k: self._pose.__setitem__(k, v),
                    )
                )

    def _call(self, method, payload):
        import grpc

        if self._channel is None:
            self._channel = grpc.insecure_channel(self.address)
        rpc = self._channel.unary_unary("/GeminiOSPInterface.Simulation/" + method)
        return success(rpc(payload, timeout=120.0, wait_for_ready=True))

    def do_step(self, current_time, step_size):
        try:
            if not self._started:
                self._started = self._call("SetStartTime", start_time_request(repr(float(self.start_time))))
            poses = [tuple(self._pose[3 * i : 3 * i + 3]) for i in range(len(self.vessels))]
            return self._call("DoStep", step_request(poses, current_time, step_size))
        except Exception as exc:  # noqa: BLE001 - an FMU reports failure by returning False
            self.log(f"GeminiBridge: {type(exc).__name__}: {exc}")
            return False

    def terminate(self):
        if self._channel is not None:
            self._channel.close()
            self._channel = None
