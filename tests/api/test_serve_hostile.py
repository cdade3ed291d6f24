"""``seatwin serve`` against a misbehaving client: time jumps, huge or malformed requests, a request body
that never comes, steps after a signal — each refused without changing anything, the others still served."""

from __future__ import annotations

import json
import threading
import time

import grpc
import pytest

from seatwin.api.client import SimulationClient
from seatwin.api.proto import simulation_pb2
from seatwin.api.server import serve
from seatwin.recording import open_bag

OK = [(0.0, 0.0, 0.0), (10.0, 0.0, 90.0), (20.0, 5.0, 180.0)]


def _refused(call, code=grpc.StatusCode.INVALID_ARGUMENT) -> str:
    with pytest.raises(grpc.RpcError) as e:
        call()
    assert e.value.code() == code, e.value.details()
    return e.value.details()


def test_time_is_checked_against_the_last_step_and_step_size_before_anything_changes(tmp_path):
    handle = serve(tmp_path / "r", port=0, sensors=())
    sim = handle.sim
    try:
        with SimulationClient(handle.address) as c:
            assert c.set_start_time(1.6e9)
            assert _refused(lambda: c.step(OK, 1.6e9)).startswith("time: expected seconds since the start time")
            assert c.step(OK, 0.0) and c.step(OK, 0.1, 0.1)
            n = sim.tracks.n
            assert "at most 1 s" in _refused(lambda: c.step(OK, 0.1 + 1e5, 0.1))  # max(10 × 0.1, 1 s)
            assert "at most 5 s" in _refused(lambda: c.step(OK, 5.2, 0.5))  # 10 × stepSize
            assert "time must increase" in _refused(lambda: c.step(OK, 0.05, 0.1))
            assert "stepSize" in _refused(lambda: c.step(OK, 0.2, float("nan")))
            assert sim.tracks.n == n and handle.servicer.steps == 2  # nothing of the refused steps was kept
            assert c.step(OK, 5.1, 0.5)  # exactly 5 s
            for k in range(52, 60):
                assert c.step(OK, k / 10, 0.1)
    finally:
        res = handle.stop()
    assert res.completed and handle.servicer.rejected == 5
    with open_bag(tmp_path / "r") as bag:
        t = bag.ground_truth()["Finn"].time
    assert len(t) == 59 and t[-1] - t[0] == pytest.approx(5.8)


def test_max_step_setting(tmp_path):
    handle = serve(tmp_path / "r", port=0, sensors=(), max_step_s=0.25)
    try:
        with SimulationClient(handle.address) as c:
            c.set_start_time(1.6e9)
            assert c.step(OK, 0.0, 1.0) and c.step(OK, 0.25, 1.0)
            assert "at most 0.25 s" in _refused(lambda: c.step(OK, 0.6, 1.0))
    finally:
        handle.stop()


def test_message_size_and_pose_count_are_capped(tmp_path):
    handle = serve(tmp_path / "r", port=0, sensors=(), max_message_bytes=64 * 1024)
    try:
        with SimulationClient(handle.address) as c:
            c.set_start_time(1.6e9)
            big = [(1.0, 2.0, 3.0)] * 10_000  # 170 kB
            _refused(lambda: c.step(big, 0.0), grpc.StatusCode.RESOURCE_EXHAUSTED)
            many = [(1.0, 2.0, 3.0)] * 3000  # 51 kB: under the cap, refused by its count
            assert "expected 3 poses" in _refused(lambda: c.step(many, 0.0))
            assert c.step(OK, 0.0) and c.step(OK, 0.1)
    finally:
        res = handle.stop()
    assert res.completed and handle.servicer.steps == 2


def _stalled_call(address: str, release: threading.Event) -> tuple[threading.Thread, list]:
    """A DoStep whose headers are sent but whose body never comes (until ``release``): what it ended with."""
    channel = grpc.insecure_channel(address)
    call = channel.stream_unary(
        "/GeminiOSPInterface.Simulation/DoStep",
        request_serializer=simulation_pb2.StepRequest.SerializeToString,
        response_deserializer=simulation_pb2.StepResponse.FromString,
    )
    outcome: list = []

    def body():
        release.wait(120)
        return
        yield  # a generator that yields nothing until released

    def run():
        try:
            outcome.append(call(body(), timeout=120))
        except grpc.RpcError as exc:
            outcome.append(exc.code())
        finally:
            channel.close()

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    return thread, outcome


@pytest.mark.slow
def test_a_body_that_never_comes_stalls_no_one_and_is_given_up(tmp_path):
    handle = serve(tmp_path / "r", port=0, sensors=(), workers=2, connection_age_s=2.0, connection_grace_s=1.0)
    release = threading.Event()
    try:
        stalled = [_stalled_call(handle.address, release) for _ in range(2)]  # as many as the worker threads
        time.sleep(0.5)
        with SimulationClient(handle.address, timeout_s=30) as c:
            c.set_start_time(1.6e9)
            for k in range(10):
                assert c.step(OK, k / 10)
        for thread, outcome in stalled:
            thread.join(60)  # given up after the connection's age and grace
            assert not thread.is_alive() and outcome and outcome[0] != simulation_pb2.StepResponse(success=True), outcome
    finally:
        release.set()
        res = handle.stop()
    assert res.completed and handle.servicer.steps == 10


def test_after_the_interrupt_steps_are_refused_and_a_step_in_progress_stops(tmp_path):
    stopped_at = []
    handle = None

    def on_frame(sensor, t, k, data):  # the signal arrives during the step's first frame
        stopped_at.append(k)
        handle.interrupt.set()

    handle = serve(tmp_path / "r", port=0, sensors=(), on_frame=on_frame)
    try:
        with SimulationClient(handle.address) as c:
            c.set_start_time(1.6e9)
            assert c.step(OK, 0.0) and c.step(OK, 1.0)  # no frame yet: ground truth waits for the step after
            # ten ground-truth frames due in [0, 1): the first runs, the interrupt stops the other nine
            assert "shutting down" in _refused(lambda: c.step(OK, 2.0), grpc.StatusCode.UNAVAILABLE)
            assert "shutting down" in _refused(lambda: c.step(OK, 2.1), grpc.StatusCode.UNAVAILABLE)
    finally:
        res = handle.stop()
    assert stopped_at == [0] and res.frames == {"ground_truth": 1}
    manifest = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert manifest["completed"] is False and manifest["error"].startswith("interrupted: the step at 2 s")
    with open_bag(tmp_path / "r") as bag:
        assert not bag.recovered and len(bag.ground_truth()["Finn"].time) == 1


def test_an_interrupt_between_steps_finishes_the_run(tmp_path):
    handle = serve(tmp_path / "r", port=0, sensors=())
    try:
        with SimulationClient(handle.address) as c:
            c.set_start_time(1.6e9)
            for k in range(5):
                assert c.step(OK, k / 10)
            handle.interrupt.set()
            _refused(lambda: c.step(OK, 0.5), grpc.StatusCode.UNAVAILABLE)
    finally:
        res = handle.stop()
    assert res.completed and res.frames == {"ground_truth": 4} and handle.servicer.steps == 5


@pytest.mark.slow
def test_a_client_outliving_its_connections_is_served_on(tmp_path):
    """The connection age that bounds a stalled body makes ordinary clients reconnect, transparently."""
    handle = serve(tmp_path / "r", port=0, sensors=(), connection_age_s=0.3, connection_grace_s=1.0)
    try:
        with SimulationClient(handle.address) as c:
            c.set_start_time(1.6e9)
            for k in range(15):  # over several connection ages
                assert c.step(OK, k / 10)
                time.sleep(0.15)
    finally:
        res = handle.stop()
    assert res.completed and handle.servicer.steps == 15 and handle.servicer.rejected == 0


def test_a_failing_frame_is_answered_internal_and_the_bag_still_finished(tmp_path):
    def on_frame(sensor, t, k, data):  # the ground-truth frames from 0.5 s on fail
        if k >= 5:
            raise RuntimeError(f"frame {k} failed")

    handle = serve(tmp_path / "r", port=0, sensors=(), on_frame=on_frame)
    try:
        with SimulationClient(handle.address) as c:
            c.set_start_time(1.6e9)
            for k in range(7):  # ground truth runs up to the step before: frames 0..4
                assert c.step(OK, k / 10)
            assert "frame 5 failed" in _refused(lambda: c.step(OK, 0.7), grpc.StatusCode.INTERNAL)
    finally:
        res = handle.stop()  # the frames still due fail again: the bag is finished all the same, nothing raised
    assert not res.completed
    manifest = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert manifest["completed"] is False and "RuntimeError: frame 6 failed" in manifest["error"]
    with open_bag(tmp_path / "r") as bag:
        assert not bag.recovered and bag.topics["/tf"].count == 7  # frames 0..6, each recorded before its hook failed
