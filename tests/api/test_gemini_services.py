"""Gemini's ForceControl, Sensordata and SensorManagement services on ``seatwin serve``, through a real gRPC channel."""

from __future__ import annotations

import math
import threading
import time

import grpc
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.api.client import SimulationClient
from seatwin.api.motion import ForceDriven, LinearManoeuvring3DOF, ScenarioReplay, body_velocity
from seatwin.api.proto import (
    force_control_pb2,
    force_control_pb2_grpc,
    sensordata_pb2,
    sensordata_pb2_grpc,
    sensormanagement_pb2,
    sensormanagement_pb2_grpc,
)
from seatwin.api.sensor_services import ServedSensor, find_sensor, served_sensors
from seatwin.api.server import serve
from seatwin.errors import ParameterError
from seatwin.recording import open_bag

START = 1.6e9
POSES = [(40.0, 10.0, 90.0), (-30.0, 5.0, 180.0), (0.0, 0.0, 0.0)]  # Havfruen, Finn, milliAmpere


def _force(stub, vessel, x=0.0, y=0.0, n=0.0):
    g = force_control_pb2.GeneralizedForce(x=x, y=y, n=n)
    return stub.ApplyForce(force_control_pb2.ForceRequest(vesselId=vessel, generalizedForce=g))


# -- the dynamics ---------------------------------------------------------------------------------


def test_surge_from_rest_follows_the_closed_form():
    """A constant surge force from rest, heading north: u = X/d (1 − e^(−d t / m)), north = ∫u."""
    m = LinearManoeuvring3DOF()
    x = 1000.0
    eta, nu = m.step(np.zeros(3), np.zeros(3), np.array([x, 0.0, 0.0]), 7.3)
    k = m.d11 / m.m11
    t = 7.3
    assert nu[0] == pytest.approx(x / m.d11 * (1 - math.exp(-k * t)), rel=1e-9)
    assert eta[0] == pytest.approx(x / m.d11 * (t - (1 - math.exp(-k * t)) / k), rel=1e-9)
    assert eta[1] == nu[1] == eta[2] == nu[2] == 0.0


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-3000, 3000),
    st.floats(-3000, 3000),
    st.floats(-3000, 3000),
    st.lists(st.floats(0.001, 0.5), min_size=1, max_size=8),
)
def test_integration_does_not_depend_on_how_the_time_is_cut(x, y, n, dts):
    """Steps of any sizes give the state one step of their sum gives (RK4 sub-steps ≤ 10 ms: to 1e-6)."""
    m = LinearManoeuvring3DOF()
    tau = np.array([x, y, n])
    eta, nu = np.array([1.0, 2.0, 0.3]), np.array([0.5, -0.1, 0.02])
    e1, v1 = eta, nu
    for dt in dts:
        e1, v1 = m.step(e1, v1, tau, dt)
    e2, v2 = m.step(eta, nu, tau, sum(dts))
    np.testing.assert_allclose(e1, e2, atol=1e-6)
    np.testing.assert_allclose(v1, v2, atol=1e-6)


def test_model_parameters_are_checked():
    with pytest.raises(ParameterError, match="m11"):
        LinearManoeuvring3DOF(m11=0.0)
    with pytest.raises(ParameterError, match="max_dt_s"):
        LinearManoeuvring3DOF(max_dt_s=math.nan)
    motion = ForceDriven(LinearManoeuvring3DOF(), 0.0, np.zeros(3))
    with pytest.raises(ParameterError, match="generalizedForce"):
        motion.set_force(math.inf, 0.0, 0.0)


def test_a_proposed_pose_changes_nothing_until_committed():
    motion = ForceDriven(LinearManoeuvring3DOF(), 10.0, np.array([1.0, 2.0, 0.0]))
    motion.set_force(500.0, 0.0, 0.0)
    a = motion.pose(11.0, np.zeros(3))
    b = motion.pose(11.0, np.zeros(3))
    assert np.array_equal(a, b) and motion.t == 10.0
    motion.commit(11.0)
    assert motion.t == 11.0 and np.array_equal(motion.eta, a) and motion.nu[0] > 0
    assert np.array_equal(ScenarioReplay().pose(3.0, np.array([1.0, 2.0, 3.0])), [1.0, 2.0, 3.0])
    np.testing.assert_allclose(body_velocity(math.pi / 2, 0.0, 2.0, 0.1), [2.0, 0.0, 0.1], atol=1e-12)


# -- ForceControl ---------------------------------------------------------------------------------


def test_force_control_moves_the_ownship(tmp_path):
    """After ApplyForce the ownship follows the force (the steps' poses for it are ignored); the others the steps."""
    h = serve(tmp_path / "run", port=0, sensors=())
    channel = grpc.insecure_channel(h.address)
    stub = force_control_pb2_grpc.ForceControlStub(channel)
    try:
        with SimulationClient(h.address) as c:
            c.set_start_time(START)
            assert _force(stub, "milliAmpere", x=1000.0).success  # before the first step: starts at rest there
            for k in range(21):
                c.step(POSES, k * 0.1, 0.1)
            assert _force(stub, "milliAmpere", n=800.0).success  # then a yaw moment, surge force off
            for k in range(21, 41):
                c.step(POSES, k * 0.1, 0.1)
            for bad, code in (
                (lambda: _force(stub, "Titanic", x=1.0), "vesselId: expected one of the served vessels"),
                (lambda: _force(stub, "milliAmpere", x=math.nan), "generalizedForce: expected finite forces"),
            ):
                with pytest.raises(grpc.RpcError) as e:
                    bad()
                assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT and code in e.value.details()
    finally:
        channel.close()
        res = h.stop()
    assert res.completed
    model = LinearManoeuvring3DOF()
    eta2, nu2 = model.step(np.zeros(3), np.zeros(3), np.array([1000.0, 0.0, 0.0]), 2.0)
    e39, _ = model.step(eta2, nu2, np.array([0.0, 0.0, 800.0]), 1.9)
    with open_bag(tmp_path / "run") as bag:
        truth = bag.ground_truth()
    own = truth["milliAmpere"]
    at_2 = int(np.argmin(np.abs(own.time - (START + 2.0))))
    assert own.north[at_2] == pytest.approx(
        1000 / model.d11 * (2.0 - model.m11 / model.d11 * (1 - math.exp(-model.d11 * 2.0 / model.m11))), abs=1e-4
    )
    last = int(np.argmin(np.abs(own.time - (START + 4.0))))
    assert own.time[last] == pytest.approx(START + 3.9)  # ground truth runs up to the second-to-last step
    assert (own.north[last], own.east[last]) == pytest.approx((e39[0], e39[1]), abs=1e-3)
    assert own.heading[last] == pytest.approx(e39[2], abs=1e-5) and own.heading[last] > 0.1  # turned to starboard
    finder = truth["Finn"]
    assert np.allclose(finder.north, -30.0) and np.allclose(finder.east, 5.0)  # the others: the steps' poses


# -- SensorManagement and Sensordata ---------------------------------------------------------------


@pytest.fixture
def lidar_server(tmp_path):
    h = serve(tmp_path / "run", port=0, sensors=("lidar",))
    channel = grpc.insecure_channel(h.address)
    yield h, channel
    channel.close()
    h.stop()


def test_sensor_management_lists_and_stops_the_sensors(lidar_server, tmp_path):
    h, channel = lidar_server
    mgmt = sensormanagement_pb2_grpc.SensorManagementStub(channel)
    pb = sensormanagement_pb2
    (lidar,) = mgmt.GetAllSensorsOfType(pb.AllSensorsOfTypeRequest(type=pb.LIDAR)).sensors
    assert (lidar.id, lidar.type, lidar.sensorWidth, lidar.sensorHeight) == (1, pb.LIDAR, 1800, 16)
    assert (lidar.ipAddress, lidar.port) == ("127.0.0.1", h.port)
    assert not mgmt.GetAllSensorsOfType(pb.AllSensorsOfTypeRequest(type=pb.OPTICAL)).sensors
    assert [s.id for s in mgmt.GetAllSensorsOnVessel(pb.AllSensorsOnVesselRequest(vesselID="milliAmpere")).sensors] == [1]
    assert not mgmt.GetAllSensorsOnVessel(pb.AllSensorsOnVesselRequest(vesselID="Finn")).sensors
    with pytest.raises(grpc.RpcError) as e:
        mgmt.GetAllSensorsOnVessel(pb.AllSensorsOnVesselRequest(vesselID="Titanic"))
    assert e.value.code() == grpc.StatusCode.NOT_FOUND
    assert not mgmt.StopRendering(pb.StopRenderingRequest(sensorID=7)).success  # unknown: false, as Gemini's

    with SimulationClient(h.address) as c:
        c.set_start_time(START)
        for k in range(11):  # sweeps at 0.0 … 0.8 s run (a sweep runs once its 0.1 s span has arrived)
            c.step(POSES, k * 0.1, 0.1)
        assert mgmt.StopRendering(pb.StopRenderingRequest(sensorID=1)).success
        for k in range(11, 21):  # the sweeps at 0.9 … 1.8 s are not made
            c.step(POSES, k * 0.1, 0.1)
        assert mgmt.StartRendering(pb.StartRenderingRequest(sensorID=1)).success
        for k in range(21, 31):
            c.step(POSES, k * 0.1, 0.1)
    res = h.stop()
    with open_bag(tmp_path / "run") as bag:
        stamps = [round(cl.stamp - START, 3) for cl in bag.point_clouds("/lidar/points")]
    expected = [k / 10 for k in range(9)] + [k / 10 for k in range(19, 30)]
    assert res.frames["lidar"] == 20 and stamps == pytest.approx(expected, abs=1e-6)


def test_sensordata_serves_the_latest_frame_and_streams_the_next(lidar_server, tmp_path):
    h, channel = lidar_server
    data = sensordata_pb2_grpc.SensordataStub(channel)
    empty = data.TransferSensordata(sensordata_pb2.SensordataRequest(operation="lidar"))
    assert empty.data == b"" and empty.dataLength == 0  # no frame yet
    for op in ("camera/front", "7", "everything"):
        with pytest.raises(grpc.RpcError) as e:
            data.TransferSensordata(sensordata_pb2.SensordataRequest(operation=op))
        assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT and "1 lidar" in e.value.details()

    got: list[bytes] = []
    with SimulationClient(h.address) as c:
        c.set_start_time(START)
        for k in range(3):  # the sweep at 0.0 s (made at the step after its span: the third)
            c.step(POSES, k * 0.1, 0.1)
        first = data.TransferSensordata(sensordata_pb2.SensordataRequest(operation="1"))
        stream = data.StreamSensordata(sensordata_pb2.SensordataRequest(operation="streaming"))  # Gemini's client's operation
        reader = threading.Thread(target=lambda: got.extend(r.data for r in stream))
        reader.start()
        deadline = time.monotonic() + 30
        while not got and time.monotonic() < deadline:  # the stream begins with the latest frame, before any new one
            time.sleep(0.01)
        assert got == [first.data] and first.dataLength > 0
        for k in range(3, 8):
            c.step(POSES, k * 0.1, 0.1)
        latest = data.TransferSensordata(sensordata_pb2.SensordataRequest(operation="1"))
    h.stop()  # the stream ends with the server
    reader.join(10)
    with open_bag(tmp_path / "run") as bag:
        clouds = list(bag.point_clouds("/lidar/points"))
    assert len(clouds) == 7  # 0.0 … 0.5 s after the steps (a sweep runs once its span has arrived), 0.6 s at the end
    assert latest.dataLength == len(latest.data) == len(clouds[5].points) * 24 > 0
    assert latest.data == clouds[5].points.tobytes()
    assert got == [cl.points.tobytes() for cl in clouds[:6]]  # every sweep made while the stream was open


def test_served_sensors_list_every_rig_camera_and_find_them():
    class Cfg:
        columns, rings, width, height = 1800, 16, 612, 512

    class Lidar:
        name, lidar = "lidar", type("L", (), {"config": Cfg})()

    class Mount:
        def __init__(self, name):
            self.name = name

    class Rig:
        name, config, mounts = "camera", Cfg, [Mount("front"), Mount("left"), Mount("right")]

    got = served_sensors([Lidar(), Rig(), object()], "milliAmpere")
    assert [(s.id, s.name, s.type, s.width, s.height) for s in got] == [
        (1, "lidar", "LIDAR", 1800, 16),
        (2, "camera/front", "OPTICAL", 612, 512),
        (3, "camera/left", "OPTICAL", 612, 512),
        (4, "camera/right", "OPTICAL", 612, 512),
    ]
    assert find_sensor(got, "3").name == "camera/left" and find_sensor(got, " camera/right ").id == 4
    with pytest.raises(ParameterError, match="1 lidar, 2 camera/front"):
        find_sensor(got, "streaming")  # several sensors: the operation must name one
    one = [ServedSensor(1, "radar", "RADAR", 10, 20, "milliAmpere", "radar")]
    assert find_sensor(one, "").name == find_sensor(one, "streaming").name == "radar"
