"""The out-of-process agent transport (seatwin.api.agent_link): an agent in another process, built only from the
protos (docs/examples/agents/grpc_agent.py), gives bit-identical runs to the same agent in process; a slow agent
skips no step; a dead or hanging agent is one clear error, not a hang."""

from __future__ import annotations

import ast
import importlib.util
import json
import struct
import sys
import threading
from pathlib import Path

import grpc
import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from seatwin.agents import ForceCommand, SetPoint, ThrusterCommand, TrackEstimate
from seatwin.api.agent_link import RemoteAgent
from seatwin.encounters import encounter_scenario, space
from seatwin.errors import ParameterError
from seatwin.verification import judge, run_closed_loop

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "agents" / "grpc_agent.py"


def _example():
    spec = importlib.util.spec_from_file_location("grpc_agent_example", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


class InProcessTwin:
    """The example's policy as an agent in process (what the external agent computes, without the wire)."""

    sensors = ("truth",)

    def __init__(self, mode: str):
        self.name, self.mode, self.ex = f"twin-{mode}", mode, _example()
        self._tracks: list[TrackEstimate] = []

    def reset(self, mission):
        self.mission = mission

    def step(self, time, frames, navigation):
        targets = [(t.north, t.east, t.v_north, t.v_east) for f in frames if f.sensor == "truth" for t in f.data]
        own = (navigation.north, navigation.east, navigation.heading, navigation.u, navigation.v, navigation.r)
        m = self.mission
        speed, course = self.ex.decide((m.goal_north, m.goal_east), m.cruise_speed, own, targets)
        self._tracks = [TrackEstimate(i + 1, *t) for i, t in enumerate(targets)] if self.mode != "gemini-force" else []
        if self.mode == "velocity":
            return SetPoint(speed, course)
        if self.mode == "force":
            return ForceCommand(*self.ex.force(speed, course, own))
        if self.mode == "gemini-force":  # Gemini's GeneralizedForce is float32
            return ForceCommand(*(_f32(x) for x in self.ex.force(speed, course, own)))
        angles, thrusts = self.ex.thrust(speed, course, own)
        return ThrusterCommand(angles, thrusts)

    def tracks(self):
        return self._tracks


@pytest.fixture(scope="module")
def scenario():
    sp = space("head_on", tcpa=(15.0, 15.0), run_out=5.0)
    return encounter_scenario(sp.encounter([0.5] * sp.dimension), "head_on_link", "none", 3)[0]


def _remote(*args: str, timeout_s: float = 30.0, name: str = "grpc") -> RemoteAgent:
    return RemoteAgent(name, ("truth",), command=[sys.executable, str(EXAMPLE), "{address}", *args], timeout_s=timeout_s)


def _same(a, b) -> None:
    """Bit for bit: the sailed states, commands, targets, tracking, and the verdict."""
    assert a.own.tobytes() == b.own.tobytes()
    assert a.time.tobytes() == b.time.tobytes()
    assert a.command.tobytes() == b.command.tobytes()
    assert a.n_tracks.tobytes() == b.n_tracks.tobytes()
    assert {k: v.tobytes() for k, v in a.tracked.items()} == {k: v.tobytes() for k, v in b.tracked.items()}
    assert json.dumps(judge(a).row(), sort_keys=True, default=str) == json.dumps(judge(b).row(), sort_keys=True, default=str)


def test_the_example_agent_imports_only_the_protos_and_grpc():
    names = set()
    for node in ast.walk(ast.parse(EXAMPLE.read_text())):
        if isinstance(node, ast.Import):
            names |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            names.add(node.module)
    assert {n for n in names if n.startswith("seatwin")} == {"seatwin.api.proto"}
    assert names <= {"__future__", "argparse", "math", "os", "sys", "time", "grpc", "seatwin.api.proto"}


@pytest.mark.parametrize(
    "mode, calls", [("velocity", ()), ("force", ()), ("gemini-force", ()), ("thrust", ()), ("velocity", ("--one-call",))]
)
def test_an_agent_over_grpc_is_bit_identical_to_it_in_process(scenario, mode, calls):
    local = run_closed_loop(scenario, InProcessTwin(mode), duration=12.0)
    with _remote("--mode", mode, *calls) as agent:
        remote = run_closed_loop(scenario, agent, duration=12.0)
    _same(local, remote)
    assert np.isfinite(remote.command[:-1]).all() and remote.command.shape[0] == 121
    assert np.ptp(remote.own[:, 2]) > 0.2  # it turned away from the head-on target: steering, not idling
    if mode != "gemini-force":
        assert remote.n_tracks[0] == 1  # its self-reported tracks crossed the wire


def test_a_slow_agent_slows_the_loop_and_skips_no_step(scenario):
    fast = run_closed_loop(scenario, InProcessTwin("velocity"), duration=3.0)
    with _remote("--sleep", "0.02") as agent:
        slow = run_closed_loop(scenario, agent, duration=3.0)
        assert agent._index == 31  # every step was sent and answered, in order
    _same(fast, slow)


def test_an_agent_process_that_dies_is_one_clear_error(scenario):
    agent = _remote("--die-at", "5")
    with pytest.raises(ParameterError, match=r"failed at step 5 .*exited with code 3: grpc_agent: dying at step 5"):
        run_closed_loop(scenario, agent, duration=3.0)
    agent.close()


def test_a_hanging_agent_times_out(scenario):
    agent = _remote("--hang-at", "2", timeout_s=1.0)
    with pytest.raises(ParameterError, match=r"failed at step 2 .*did not answer within 1 s"):
        run_closed_loop(scenario, agent, duration=3.0)
    assert agent.close(grace_s=0.1) is not None  # killed


def test_an_agent_that_never_connects_times_out(scenario):
    never = r"agent 'absent' at 127\.0\.0\.1:\d+ failed at step 0 .*within 0\.3 s"
    with RemoteAgent("absent", startup_timeout_s=0.3) as agent, pytest.raises(ParameterError, match=never):
        run_closed_loop(scenario, agent, duration=1.0)


def test_an_agent_started_separately_serves_run_after_run(scenario):
    """``address`` mode: the agent runs on its own (``--keep``) and each run's server comes up at the same address."""
    import socket
    import subprocess

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        address = f"127.0.0.1:{s.getsockname()[1]}"
    proc = subprocess.Popen([sys.executable, str(EXAMPLE), address, "--keep"], stderr=subprocess.PIPE)
    try:
        runs = []
        for _ in range(2):
            with RemoteAgent("kept", address=address) as agent:
                runs.append(run_closed_loop(scenario, agent, duration=2.0))
        assert proc.poll() is None  # still there for the next simulation
    finally:
        proc.kill()
        proc.wait()
    _same(runs[0], runs[1])
    _same(runs[0], run_closed_loop(scenario, InProcessTwin("velocity"), duration=2.0))


def test_bad_commands_are_refused_and_change_nothing():
    from seatwin.agents import Navigation
    from seatwin.api.proto import agent_link_pb2 as pb
    from seatwin.api.proto import agent_link_pb2_grpc, force_control_pb2, force_control_pb2_grpc

    with RemoteAgent("hostile", timeout_s=5.0, vessel="own") as agent:
        channel = grpc.insecure_channel(agent.address)
        link, gemini = agent_link_pb2_grpc.AgentLinkStub(channel), force_control_pb2_grpc.ForceControlStub(channel)
        with pytest.raises(grpc.RpcError) as e:
            link.SetVelocity(pb.VelocityRequest(step=0, speed=1.0, heading=0.0), timeout=5)
        assert e.value.code() == grpc.StatusCode.FAILED_PRECONDITION and "Observe first" in e.value.details()
        answer = {}
        nav = Navigation(0.0, 1.0, 2.0, 0.5, 1.0, 0.0, 0.0)
        t = threading.Thread(target=lambda: answer.setdefault("c", agent.step(0.0, [], nav)))
        t.start()
        obs = link.Observe(pb.ObserveRequest(agent="hostile"), timeout=5)
        assert obs.step.index == 0 and obs.step.own.east == 2.0 and obs.step.navigation.vesselName == "own"
        refusals = [
            (lambda: link.SetVelocity(pb.VelocityRequest(step=1, speed=1.0), timeout=5), "FAILED_PRECONDITION", "names step 1"),
            (lambda: link.ApplyForce(pb.ForceRequest(step=0, x=float("nan")), timeout=5), "INVALID_ARGUMENT", "non-finite"),
            (lambda: link.ApplyThrust(pb.ThrustRequest(step=0, angles=[0.0]), timeout=5), "INVALID_ARGUMENT", "as many thrusts"),
            (lambda: link.Act(pb.Action(), timeout=5), "INVALID_ARGUMENT", "needs a command"),
            (lambda: link.Act(pb.Action(force=pb.ForceRequest(step=3)), timeout=5), "FAILED_PRECONDITION", "names step 3"),
            (
                lambda: gemini.ApplyForce(force_control_pb2.ForceRequest(vesselId="other"), timeout=5),
                "NOT_FOUND",
                "expected 'own'",
            ),
        ]
        for call, code, text in refusals:
            with pytest.raises(grpc.RpcError) as e:
                call()
            assert e.value.code().name == code and text in e.value.details()
        assert t.is_alive()  # still waiting: nothing was taken as its command
        tau = force_control_pb2.GeneralizedForce(x=0.5, n=-0.25)
        assert gemini.ApplyForce(force_control_pb2.ForceRequest(vesselId="own", generalizedForce=tau), timeout=5).success
        t.join(5)
        assert answer["c"] == ForceCommand(0.5, 0.0, -0.25)
        with pytest.raises(grpc.RpcError) as e:
            link.SetVelocity(pb.VelocityRequest(step=0, speed=1.0), timeout=5)
        assert e.value.code() == grpc.StatusCode.FAILED_PRECONDITION
        channel.close()


def test_bad_parameters_are_named():
    with pytest.raises(ParameterError, match="sensors"):
        RemoteAgent(sensors=("camera",))
    with pytest.raises(ParameterError, match="HOST:PORT"):
        RemoteAgent(address="nowhere")
    with pytest.raises(ParameterError, match="cannot start the agent"):
        RemoteAgent(command=["/nonexistent/agent"])


HOST = (
    "import sys; from seatwin.agents import make_agent; from seatwin.api.agent_host import host_agent; "
    "sys.exit(0 if host_agent(make_agent('reference', sensors=tuple(sys.argv[2:])), sys.argv[1]) > 0 else 1)"
)
"""``python -c HOST ADDRESS SENSOR...``: seatwin's reference agent on those sensors, hosted in its own process."""


def test_the_reference_agent_on_lidar_and_radar_is_bit_identical_hosted_in_another_process(scenario):
    """seatwin's own agent (lidar clustering, radar plots, one JIPDA per sensor, velocity obstacles) in another
    process: lidar sweeps (float32 columns in Gemini's message), their mounts, radar plots and the navigation cross
    the wire without a bit lost."""
    from seatwin.agents import make_agent

    sensors = ("lidar", "radar")
    local = run_closed_loop(scenario, make_agent("reference", sensors=sensors), duration=6.0)
    with RemoteAgent("reference", sensors, command=[sys.executable, "-c", HOST, "{address}", *sensors]) as agent:
        remote = run_closed_loop(scenario, agent, duration=6.0)
        assert agent.close() == 0
    assert remote.frames == local.frames and local.frames["lidar"] > 40 and local.frames["radar"] >= 1
    assert local.n_tracks.max() >= 1  # it tracked the target: the frames carried information
    _same(local, remote)


def test_hostile_frames_are_named():
    from seatwin.api.agent_host import frames_of
    from seatwin.api.proto import agent_link_pb2 as pb
    from seatwin.errors import InputError

    bad_mount = pb.Step(frames=[pb.Frame(sensor="truth", truth=pb.TruthFrame(), mount=[1.0, 2.0])])
    with pytest.raises(InputError, match="12 numbers"):
        frames_of(bad_mount, {})
    with pytest.raises(InputError, match="no data"):
        frames_of(pb.Step(frames=[pb.Frame(sensor="lidar")]), {})
    short = pb.RadarPlots(range=[1.0, 2.0], azimuth=[0.0], north=[0.0], east=[0.0], cells=[1], extent=[1.0])
    with pytest.raises(InputError, match="RadarPlots"):
        frames_of(pb.Step(frames=[pb.Frame(sensor="radar", radar=short)]), {})


_WIRE_SETTINGS = {"deadline": None, "suppress_health_check": list(HealthCheck), "derandomize": True}


@settings(max_examples=60, **_WIRE_SETTINGS)
@given(
    width=st.integers(0, 40),
    height=st.integers(0, 3),
    point_step=st.integers(0, 40),
    row_step=st.integers(0, 400),
    data=st.binary(max_size=600),
    fields=st.lists(
        st.tuples(st.sampled_from(["x", "y", "z", "intensity", "ring", "time", "", "q"]), st.integers(-2, 40), st.integers(0, 9)),
        max_size=7,
    ),
    big_endian=st.booleans(),
)
@example(2, 1, 12, 0, bytes(range(24)), [("x", 0, 7), ("y", 4, 7), ("z", 8, 7)], False)  # a valid one decodes
def test_any_lidar_message_decodes_or_is_one_input_error(width, height, point_step, row_step, data, fields, big_endian):
    """The agent side reads hostile ``LidarStreamingRequest``s: a sweep, or an InputError — nothing else escapes."""
    from seatwin.api.agent_host import frames_of
    from seatwin.api.proto import agent_link_pb2 as pb
    from seatwin.api.proto import sensor_streaming_pb2 as s
    from seatwin.errors import InputError

    req = s.LidarStreamingRequest(
        width=width,
        height=height,
        point_step=point_step,
        row_step=row_step,
        data=data,
        isBigEndian=big_endian,
        fields=[s.PointField(name=n, offset=max(o, 0), datatype=d, count=1) for n, o, d in fields],
    )
    try:
        (frame,) = frames_of(pb.Step(frames=[pb.Frame(sensor="lidar", time=1.0, lidar=req)]), {})
    except InputError:
        return
    assert len(frame.data.x) == len(frame.data.y) == len(frame.data.z) == width * height
