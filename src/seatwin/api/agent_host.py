"""The agent's side of the gRPC transport, for an agent written against seatwin's :class:`~seatwin.agents.Agent`
interface: :func:`host_agent` runs it in this process as the client of a simulation's ``AgentLink``
(:mod:`seatwin.api.agent_link`) — the messages decoded into the interface's types, its commands sent back — so the
same agent object sails the same runs in process or from another process (or machine).

Decoding: a ``Mission`` → :class:`~seatwin.agents.Mission`; a ``State`` → :class:`~seatwin.agents.Navigation`; a
truth frame → :class:`~seatwin.agents.TruthTarget` tuples; a lidar frame's ``LidarStreamingRequest`` →
:class:`~seatwin.sensors.lidar.LidarSweep` (its float32 columns as sent; ``stamp`` the frame's time, ``frame`` its count
in the run, ``object_id`` −1: ground truth does not cross the wire), with its ``mount``; a radar frame's plots →
:class:`~seatwin.sensors.radar.model.RadarScan` (``object_id`` and ``kind`` −1, no spokes). A command goes back in
an ``Act`` call (a set-point, a force in doubles, or thrusts, with the agent's ``tracks()``), whose answer is the next
observation.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from seatwin.agents.interface import (
    Agent,
    ForceCommand,
    Mission,
    Navigation,
    SensorFrame,
    SetPoint,
    ThrusterCommand,
    TruthTarget,
)
from seatwin.api.proto import agent_link_pb2, agent_link_pb2_grpc
from seatwin.errors import InputError, ParameterError
from seatwin.perception.frames import Mount
from seatwin.recording.pointcloud import unpack

KEEP_PAUSE_S = 0.2
"""With ``keep``: the pause after a simulation ends before observing the next one (its server is going away)."""


def mission_of(m: Any) -> Mission:
    return Mission(m.start_north, m.start_east, m.goal_north, m.goal_east, m.cruise_speed, m.harbour, m.length, m.beam)


def navigation_of(s: Any) -> Navigation:
    return Navigation(s.time, s.north, s.east, s.heading, s.u, s.v, s.r)


def _mount(f: Any) -> Mount | None:
    if not f.mount:
        return None
    if len(f.mount) != 12:
        raise InputError("Frame.mount", f"expected 12 numbers (translation, rotation row by row), got {len(f.mount)}")
    m = np.asarray(f.mount, dtype=float)
    return Mount((float(m[0]), float(m[1]), float(m[2])), m[3:].reshape(3, 3))


def _sweep(r: Any, count: int) -> Any:
    from seatwin.sensors.lidar import LidarSweep

    pts = unpack(r.data, r.fields, r.point_step, r.width, r.height, r.row_step, r.isBigEndian)
    missing = [c for c in ("x", "y", "z") if c not in (pts.dtype.names or ())]
    if missing:
        raise InputError("LidarStreamingRequest", f"the cloud has no {', '.join(missing)} field")
    n = pts.size

    def col(name: str, dtype: Any, default: float = 0.0) -> Any:
        return pts[name].astype(dtype) if name in (pts.dtype.names or ()) else np.full(n, default, dtype)

    return LidarSweep(
        r.timeInSeconds,
        count,
        col("x", np.float32),
        col("y", np.float32),
        col("z", np.float32),
        col("intensity", np.float32),
        col("ring", np.uint16),
        col("time", np.float32),
        np.full(n, -1, np.int32),
    )


def _plots(t: float, r: Any, count: int) -> Any:
    from seatwin.sensors.radar.geometry import AntennaPose
    from seatwin.sensors.radar.model import RadarScan

    cols = [np.asarray(c, dtype=float) for c in (r.range, r.azimuth, r.north, r.east, r.extent)]
    cells = np.asarray(r.cells, dtype=np.int64)
    n = cells.size
    if any(c.size != n for c in cols) or len(r.intensity) not in (0, n):
        expected = "one range, azimuth, north, east, cells, extent (and intensity) a plot"
        raise InputError("RadarPlots", f"expected {expected}; the columns' lengths differ from {n} cells")
    antenna = AntennaPose(r.antenna_north, r.antenna_east, r.antenna_heading, r.antenna_height)
    unknown = np.full(n, -1, np.int64)
    return RadarScan(t, count, antenna, *cols[:4], cells, cols[4], unknown, unknown.copy(), np.asarray(r.intensity, float))


def frames_of(step: Any, counts: dict[str, int]) -> list[SensorFrame]:
    """A ``Step``'s frames as the interface's :class:`SensorFrame` (``counts``: lidar sweeps so far, updated)."""
    out = []
    for f in step.frames:
        nav = navigation_of(f.navigation)
        kind = f.WhichOneof("data")
        if kind == "truth":
            data: Any = tuple(
                TruthTarget(t.name, t.north, t.east, t.v_north, t.v_east, t.length, t.beam) for t in f.truth.targets
            )
        elif kind in ("lidar", "radar"):
            n = counts.get(kind, 0)
            data = _sweep(f.lidar, n) if kind == "lidar" else _plots(f.time, f.radar, n)
            counts[kind] = n + 1
        else:
            raise InputError("Frame", f"frame {f.sensor!r} at t = {f.time} carries no data")
        out.append(SensorFrame(f.sensor, f.time, data, nav, _mount(f)))
    return out


def host_agent(agent: Agent, address: str, *, keep: bool = False) -> int:
    """Be ``agent``'s process: observe the simulation at ``address``, answer every step, until it ends (with
    ``keep``: for ever, one simulation after another). Returns the steps answered."""
    import grpc

    from seatwin.api.channel import GRPC_OPTIONS, KEPT_AGENT_OPTIONS

    pb = agent_link_pb2
    channel = grpc.insecure_channel(address, options=GRPC_OPTIONS + KEPT_AGENT_OPTIONS)
    link = agent_link_pb2_grpc.AgentLinkStub(channel)
    answered, counts, obs = 0, {}, None
    try:
        while True:
            if obs is None:  # else Act brought it
                try:
                    obs = link.Observe(pb.ObserveRequest(agent=agent.name), wait_for_ready=True)
                except grpc.RpcError as exc:
                    if keep and exc.code() in (grpc.StatusCode.CANCELLED, grpc.StatusCode.UNAVAILABLE):
                        time.sleep(KEEP_PAUSE_S)  # the last simulation's server went away under this call
                        continue
                    raise
            what, message, obs = obs.WhichOneof("what"), obs, None

            if what == "finished":
                if keep:
                    time.sleep(KEEP_PAUSE_S)
                    continue
                return answered
            if what == "mission":
                agent.reset(mission_of(message.mission))
                counts = {}
                continue
            s = message.step
            command = agent.step(s.time, frames_of(s, counts), navigation_of(s.own))
            tracks = [pb.Track(id=t.id, north=t.north, east=t.east, v_north=t.v_north, v_east=t.v_east) for t in agent.tracks()]
            if isinstance(command, SetPoint):
                v = pb.VelocityRequest(step=s.index, speed=command.speed, heading=command.heading, tracks=tracks)
                action = pb.Action(velocity=v)
            elif isinstance(command, ForceCommand):
                action = pb.Action(force=pb.ForceRequest(step=s.index, x=command.X, y=command.Y, n=command.N, tracks=tracks))
            elif isinstance(command, ThrusterCommand):
                thrust = pb.ThrustRequest(step=s.index, angles=command.angles, thrusts=command.thrusts, tracks=tracks)
                action = pb.Action(thrust=thrust)
            else:
                raise ParameterError("agent", f"agent {agent.name!r} answered {type(command).__name__}, not a command")
            obs = link.Act(action)  # the command, answered with the next observation: one call a step
            answered += 1
    except grpc.RpcError as exc:
        raise ParameterError("address", f"the simulation at {address} failed: {exc.code().name}: {exc.details()}") from None
    finally:
        channel.close()
