"""``seatwin serve``: a Gemini client built from the .proto files drives the lock-step server over
loopback gRPC; the bag equals ``seatwin simulate``'s of the same scenario and seed."""

from __future__ import annotations

import json
import math

import grpc
import numpy as np
import pytest

from seatwin.api.client import SimulationClient, scenario_steps
from seatwin.api.lockstep import DEFAULT_VESSELS, LockstepSettings, LockstepSimulation, parse_start_time
from seatwin.api.server import serve
from seatwin.errors import ParameterError
from seatwin.recording import open_bag
from seatwin.scenario.builtin import builtin_scenario

SCENARIO = "ferry_crossing"
DURATION = 2.0


def _counts(run_dir):
    with open_bag(run_dir) as bag:
        out: dict[str, int] = {}
        for m in bag.raw_messages():
            out[m[0]] = out.get(m[0], 0) + 1
        return out


def _drive(address, scenario, start, duration, lead_in=0):
    with SimulationClient(address) as client:
        assert client.set_start_time(start)
        for rel, poses in scenario_steps(scenario, DEFAULT_VESSELS, start, duration, lead_in=lead_in):
            assert client.step(poses, rel, 0.1)


def _lockstep(run_dir, scenario, start, duration, lead_in=0, **settings):
    sim = LockstepSimulation(run_dir, LockstepSettings(**{"sensors": ("lidar",), **settings}))
    sim.set_start_time(repr(start))
    for rel, poses in scenario_steps(scenario, DEFAULT_VESSELS, start, duration, lead_in=lead_in):
        sim.step(poses, rel)
    return sim, sim.close()


@pytest.mark.slow
def test_served_bag_equals_simulated_bag(tmp_path):
    from seatwin.pipeline.simulate import simulate_run

    sc = builtin_scenario(SCENARIO)
    start = sc.start + 5.0
    ref = simulate_run(sc, tmp_path / "ref", start=start, duration=DURATION, progress=False, seed=7, sensors=("lidar",))
    handle = serve(tmp_path / "served", port=0, seed=7, sensors=("lidar",))
    try:
        _drive(handle.address, sc, start, DURATION, lead_in=1)  # a step before the start: central differences there too
    finally:
        res = handle.stop()
    assert res.completed and res.frames == ref.frames == {"ground_truth": 20, "lidar": 20}
    manifest = json.loads((tmp_path / "served" / "manifest.json").read_text())
    assert manifest["completed"] is True
    assert _counts(tmp_path / "served") == _counts(tmp_path / "ref")
    with open_bag(tmp_path / "ref") as a, open_bag(tmp_path / "served") as b:
        ta, tb = a.ground_truth(), b.ground_truth()
        assert set(ta) == set(tb) == set(DEFAULT_VESSELS)
        for name in ta:
            np.testing.assert_allclose(tb[name].time, ta[name].time, atol=1e-6)
            for f in ("north", "east"):
                np.testing.assert_allclose(getattr(tb[name], f), getattr(ta[name], f), atol=2e-3, err_msg=f"{name}.{f}")
            # Velocities: central differences of the received samples, the first frame's included (the lead-in step).
            for f in ("v_north", "v_east", "yaw_rate"):
                np.testing.assert_allclose(getattr(tb[name], f), getattr(ta[name], f), atol=2e-3, err_msg=f)
            dh = np.angle(np.exp(1j * (tb[name].heading - ta[name].heading)))
            assert np.abs(dh).max() < 1e-4
        ca, cb = list(a.point_clouds("/lidar/points")), list(b.point_clouds("/lidar/points"))
        assert len(ca) == len(cb) == 20
        for x, y in zip(ca, cb):
            assert x.stamp == pytest.approx(y.stamp, abs=1e-6)
            # Same seed: the same rays drop; points differ by the float32 poses of the wire only (~10 µm).
            assert len(x.points) == len(y.points) > 100
            assert np.abs(x.xyz() - y.xyz()).max() < 1e-3


def test_bad_requests_are_refused_and_the_server_keeps_serving(tmp_path):
    handle = serve(tmp_path / "r", port=0, sensors=())
    ok = [(0.0, 0.0, 0.0), (10.0, 0.0, 90.0), (20.0, 5.0, 180.0)]
    try:
        with SimulationClient(handle.address) as client:
            with pytest.raises(grpc.RpcError) as e:
                client.step(ok, 0.0)
            assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT and "SetStartTime" in e.value.details()
            assert client.set_start_time(1.6e9)
            for bad, why in (
                ([(math.nan, 0.0, 0.0), *ok[1:]], "not finite"),
                ([(0.0, math.inf, 0.0), *ok[1:]], "not finite"),
                (ok[:2], "expected 3 poses"),
            ):
                with pytest.raises(grpc.RpcError) as e:
                    client.step(bad, 0.0)
                assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT and why in e.value.details()
            assert client.step(ok, 0.0) and client.step(ok, 0.1)
            with pytest.raises(grpc.RpcError) as e:
                client.step(ok, 0.05)
            assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT and "time must increase" in e.value.details()
            with pytest.raises(grpc.RpcError) as e:
                client.set_start_time(1.7e9)
            assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT
            for k in range(2, 12):
                assert client.step(ok, k / 10)
    finally:
        res = handle.stop()
    assert res.completed and res.frames == {"ground_truth": 11}
    with open_bag(tmp_path / "r") as bag:
        truth = bag.ground_truth()
        assert truth["Finn"].heading[0] == pytest.approx(math.pi / 2)
        assert truth["milliAmpere"].north[-1] == pytest.approx(20.0)
        assert truth["Havfruen"].time[0] == pytest.approx(1.6e9)


def test_lockstep_checks_its_settings(tmp_path):
    with pytest.raises(ParameterError, match="ownship"):
        LockstepSimulation(tmp_path / "a", LockstepSettings(ownship="Nobody"))
    assert parse_start_time("1600000000.5") == 1600000000.5
    assert parse_start_time("2020-09-15T12:00:00Z") == 1600171200.0
    with pytest.raises(ParameterError):
        parse_start_time("noon")
    with pytest.raises(ParameterError, match="port"):
        h = serve(tmp_path / "b", port=0, sensors=())
        try:
            serve(tmp_path / "c", port=h.port, sensors=())
        finally:
            h.stop()


def test_first_velocity_without_and_with_a_step_before_the_start(tmp_path):
    """Without history the first frame's velocity is one-sided — what simulate's ground truth gives for
    the received poses alone; one step before the start makes it simulate's (central) for the scenario."""
    from seatwin.pipeline.simulate import simulate_run
    from seatwin.sim.sensors import GroundTruthSensor

    sc = builtin_scenario(SCENARIO)
    start = sc.start + 4.0  # the ferry accelerates (0.35 m/s²): the one-sided and central differences differ
    ref = simulate_run(sc, tmp_path / "ref", start=start, duration=1.0, progress=False, sensors=("lidar",))
    sim, res = _lockstep(tmp_path / "plain", sc, start, 1.0)
    _, res_lead = _lockstep(tmp_path / "lead", sc, start, 1.0, lead_in=1)
    assert res.frames == res_lead.frames == ref.frames == {"ground_truth": 10, "lidar": 10}
    received = GroundTruthSensor(sim.received_scenario()).capture(start, 0)
    with open_bag(tmp_path / "ref") as a, open_bag(tmp_path / "plain") as b, open_bag(tmp_path / "lead") as c:
        ta, tb, tc = a.ground_truth(), b.ground_truth(), c.ground_truth()
    for pose in received:
        name = pose.name
        assert tb[name].time[0] == tc[name].time[0] == pytest.approx(start, abs=1e-6)
        assert tb[name].v_north[0] == pytest.approx(pose.v_north, abs=1e-9)
        assert tb[name].v_east[0] == pytest.approx(pose.v_east, abs=1e-9)
        assert tb[name].yaw_rate[0] == pytest.approx(pose.yaw_rate, abs=1e-9)
        for f in ("v_north", "v_east", "yaw_rate"):
            np.testing.assert_allclose(getattr(tc[name], f), getattr(ta[name], f), atol=2e-3, err_msg=f"{name}.{f}")
            np.testing.assert_allclose(getattr(tb[name], f)[1:], getattr(ta[name], f)[1:], atol=2e-3, err_msg=f"{name}.{f}")
    own = "milliAmpere"
    assert abs(tb[own].v_north[0] - ta[own].v_north[0]) + abs(tb[own].v_east[0] - ta[own].v_east[0]) > 5e-3


def test_each_sensor_waits_only_for_its_own_span(tmp_path):
    """With the radar on (a 2.5 s rotation), lidar and ground truth still run to the last step, as simulate's."""
    from seatwin.pipeline.simulate import simulate_run

    sc = builtin_scenario(SCENARIO)
    start = sc.start + 5.0
    ref = simulate_run(sc, tmp_path / "ref", start=start, duration=3.0, progress=False, seed=3, sensors=("lidar", "radar"))
    _, res = _lockstep(tmp_path / "served", sc, start, 3.0, seed=3, sensors=("lidar", "radar"))
    # The rotation starting 2.5 s in would end after the last step: simulate sees the scenario go on, serve cannot.
    assert ref.frames == {"ground_truth": 30, "lidar": 30, "radar": 2} and res.frames == {**ref.frames, "radar": 1}
    with open_bag(tmp_path / "ref") as a, open_bag(tmp_path / "served") as b:
        (ra, _), (rb,) = list(a.radar_scans()), list(b.radar_scans())
        assert ra.stamp == pytest.approx(rb.stamp, abs=1e-6) and len(ra.points) == len(rb.points)


def test_serve_renders_the_camera_rig(tmp_path):
    """``--sensors camera``: the rig renders on the server's one thread; each image is labelled from ground truth."""
    from seatwin.errors import InputError

    try:
        handle = serve(tmp_path / "cam", port=0, sensors=("camera",))
    except InputError as exc:  # no EGL here
        pytest.skip(str(exc))
    try:
        with SimulationClient(handle.address) as client:
            client.set_start_time(1.6e9)
            for k in range(4):  # Havfruen 20 m ahead of the ownship, Finn off to port
                client.step([(20.0 + k, 2.0, 0.0), (10.0, -30.0, 90.0), (0.0, 0.0, 0.0)], k * 0.1)
    finally:
        res = handle.stop()
    assert res.frames == {"ground_truth": 3, "camera": 2}  # before the last step (0.3 s): 10 Hz and 5 Hz frames
    counts = _counts(tmp_path / "cam")
    for cam in ("front", "left", "right"):
        for kind in ("image_raw", "camera_info", "labels"):
            assert counts[f"/camera/{cam}/{kind}"] == 2
    with open_bag(tmp_path / "cam") as bag:
        images = list(bag.images("/camera/front/image_raw"))
        labels = [m.msg for m in bag.messages("/camera/front/labels")]
    assert images[0].pixels.shape[:2] == (512, 612) and np.ptp(images[0].pixels) > 50  # sky, sea and a vessel
    assert [d.id for d in labels[0].detections] == ["Havfruen", "moored_trawler"]  # a moored boat in view is labelled too
