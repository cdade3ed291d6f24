"""A Gemini ``Simulation`` client: what an OSP scenario generator sends, built from seatwin's .proto files.

:func:`scenario_steps` turns a scenario into the ``DoStep`` sequence a scenario player would send
(every vessel's north, east, heading in degrees at each step); :class:`SimulationClient` sends them.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

import numpy as np

from seatwin.scenario import Scenario


class SimulationClient:
    """``SetStartTime`` and ``DoStep`` to a ``Simulation`` server at ``address`` (``host:port``)."""

    def __init__(self, address: str, timeout_s: float | None = 60.0):
        import grpc

        from seatwin.api.channel import GRPC_OPTIONS
        from seatwin.api.proto import simulation_pb2, simulation_pb2_grpc

        self._pb = simulation_pb2
        self.channel = grpc.insecure_channel(address, options=GRPC_OPTIONS)
        self.stub = simulation_pb2_grpc.SimulationStub(self.channel)
        self.timeout_s = timeout_s

    def set_start_time(self, posix: float) -> bool:
        """Send the POSIX start time (as text, Gemini's convention)."""
        req = self._pb.SetStartTimeRequest(time=repr(float(posix)))
        return bool(self.stub.SetStartTime(req, timeout=self.timeout_s, wait_for_ready=True).success)

    def step(self, poses: Sequence[Sequence[float]], time: float, step_size: float = 0.0) -> bool:
        """``DoStep``: ``poses`` (north, east [m], heading [°]) per vessel at ``time`` s since the start."""
        req = self._pb.StepRequest(
            VesselPoses=[self._pb.Pose(north=float(n), east=float(e), heading=float(h)) for n, e, h in poses],
            time=float(time),
            stepSize=float(step_size),
        )
        return bool(self.stub.DoStep(req, timeout=self.timeout_s).success)

    def close(self) -> None:
        self.channel.close()

    def __enter__(self) -> SimulationClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def scenario_steps(
    scenario: Scenario, names: Sequence[str], start: float, duration: float, rate_hz: float = 10.0, lead_in: int = 0
) -> Iterator[tuple[float, list[tuple[float, float, float]]]]:
    """``(seconds since start, [(north, east, heading °) per vessel of names])`` at ``rate_hz`` over
    [start, start + duration], both ends included (a scenario player's output); ``lead_in`` steps
    more before the start (negative times: history the server only interpolates and differentiates,
    so the first frame's velocities are central differences, as ``seatwin simulate``'s)."""
    n = int(round(duration * rate_hz))
    for k in range(-int(lead_in), n + 1):
        rel = k / rate_hz
        poses = []
        for name in names:
            s = scenario.state_at(name, start + rel)
            poses.append((float(s.north), float(s.east), float(np.rad2deg(s.heading)) % 360.0))
        yield rel, poses
