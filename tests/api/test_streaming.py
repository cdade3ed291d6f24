"""SensorStreaming/Navigation: ``simulate --stream`` into a real ``record-stream`` gRPC server on loopback."""

from __future__ import annotations

import json
import math

import grpc
import numpy as np
import pytest

from seatwin.api.proto import navigation_pb2, navigation_pb2_grpc, sensor_streaming_pb2, sensor_streaming_pb2_grpc
from seatwin.api.streaming import (
    SensorStreamer,
    camera_request,
    heading_of_quaternion,
    lidar_request,
    radar_request,
    record_stream,
    recorded_spokes,
)
from seatwin.recording import open_bag


def test_heading_of_quaternion():
    # 90° about z (down): east.
    s = math.sqrt(0.5)
    assert heading_of_quaternion(0.0, 0.0, s, s) == pytest.approx(math.pi / 2)
    assert heading_of_quaternion(0.0, 0.0, 0.0, 1.0) == 0.0


def test_lidar_request_has_the_table_4_2_layout():
    class Sweep:
        x = np.array([1.0, 2.0], np.float32)
        y = np.array([3.0, 4.0], np.float32)
        z = np.array([5.0, 6.0], np.float32)
        intensity = np.array([7.0, 8.0], np.float32)
        ring = np.array([9, 10], np.uint16)
        time = np.array([0.01, 0.02], np.float32)

    r = lidar_request("lidar", 12.5, Sweep())
    assert [(f.name, f.offset, f.datatype, f.count) for f in r.fields] == [
        ("x", 0, 7, 1),
        ("y", 4, 7, 1),
        ("z", 8, 7, 1),
        ("intensity", 12, 7, 1),
        ("ring", 16, 4, 1),
        ("time", 18, 7, 1),
    ]
    assert (r.point_step, r.row_step, r.width, r.height, r.isBigEndian) == (24, 48, 2, 1, False)
    assert r.fields[0].FLOAT32 == 7 and r.fields[0].UINT16 == 4
    assert np.frombuffer(r.data[16:18], np.uint16)[0] == 9 and np.frombuffer(r.data[0:4], np.float32)[0] == 1.0


@pytest.mark.slow
def test_simulate_streams_into_record_stream(tmp_path):
    from seatwin.pipeline.simulate import simulate_run

    rec = record_stream(tmp_path / "rec", port=0)
    streamer = SensorStreamer(rec.address)
    try:
        res = simulate_run(
            "ferry_crossing",
            tmp_path / "sim",
            duration=1.0,
            progress=False,
            sensors=("lidar", "radar"),
            radar_spokes=True,
            on_frame=streamer.on_frame,
        )
        channel = grpc.insecure_channel(rec.address)
        nav = navigation_pb2_grpc.NavigationStub(channel)
        s = math.sqrt(0.5)
        msg = navigation_pb2.NavigationRequest(
            timeStamp=1.6e9,
            position=navigation_pb2.Vec3(x=10.0, y=-5.0, z=0.0),
            orientation=navigation_pb2.Quaternion(x=0.0, y=0.0, z=s, w=s),
            linearVelocity=navigation_pb2.Vec3(x=0.0, y=1.5, z=0.0),
            vesselName="milliAmpere",
        )
        assert nav.SendNavigationMessage(msg).success
        bad = sensor_streaming_pb2.RadarStreamingRequest(numSpokes=4, numSamples=4, radarSpokes=b"123")
        with pytest.raises(grpc.RpcError) as e:
            sensor_streaming_pb2_grpc.SensorStreamingStub(channel).StreamRadarSensor(bad)
        assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT
        channel.close()
    finally:
        streamer.close()
        counts = rec.stop()
    nav = 3 * res.frames["ground_truth"]  # a NavigationRequest per vessel and ground-truth frame
    assert streamer.sent == {"lidar": res.frames["lidar"], "camera": 0, "radar": res.frames["radar"], "navigation": nav}
    assert res.frames["radar"] >= 1
    assert counts == {"lidar": 10, "camera": 0, "radar": res.frames["radar"], "navigation": nav + 1}
    assert json.loads((tmp_path / "rec" / "manifest.json").read_text())["completed"] is True
    with open_bag(tmp_path / "sim") as a, open_bag(tmp_path / "rec") as b:
        ca, cb = list(a.point_clouds("/lidar/points")), list(b.point_clouds("/lidar/points"))
        assert len(ca) == len(cb) == 10
        for x, y in zip(ca, cb):
            assert x.stamp == pytest.approx(y.stamp, abs=1e-6)
            assert x.points.tobytes() == y.points.tobytes()
        spokes = list(b.images("/radar/spokes"))
        assert len(spokes) == res.frames["radar"] and spokes[0].pixels.ndim >= 2
        truth = b.ground_truth()["milliAmpere"]
        sent = next(i for i, tt in enumerate(truth.time) if tt == pytest.approx(1.6e9))
        assert truth.north[sent] == pytest.approx(10.0) and truth.heading[sent] == pytest.approx(math.pi / 2, abs=1e-6)
    (rotation, *_) = recorded_spokes(tmp_path / "rec")  # each spoke's azimuth at the centre of its step
    ns = rotation.num_spokes
    assert rotation.intensities.shape == (ns, spokes[0].pixels.shape[1]) and len(rotation.azimuth) == ns > 100
    np.testing.assert_allclose(rotation.azimuth, (np.arange(ns) + 0.5) * 2 * np.pi / ns, rtol=1e-6)


def test_camera_images_and_serve_stream(tmp_path):
    """A camera frame goes on the wire in Gemini's order (RGB, rows bottom up) and is recorded as Gemini's ROS
    adapter publishes it (bgr8, rows top down): the simulated pixels exactly; ``serve``'s on_frame streams too."""
    from seatwin.api.client import SimulationClient
    from seatwin.api.server import serve

    class Img:
        name = "front"
        bgr = np.random.default_rng(0).integers(0, 255, (4, 6, 3), dtype=np.uint8)

    rec = record_stream(tmp_path / "rec", port=0)
    streamer = SensorStreamer(rec.address)
    try:
        streamer.on_frame(object(), 1.6e9, 0, [Img()])
        h = serve(tmp_path / "srv", port=0, sensors=(), on_frame=streamer.on_frame)
        with SimulationClient(h.address) as c:
            c.set_start_time(1.6e9)
            for k in range(3):
                c.step([(k, 0.0, 0.0)] * 3, k * 0.1)
        h.stop()
    finally:
        streamer.close()
        counts = rec.stop()
    assert counts["camera"] == 1 and streamer.sent == {"lidar": 0, "camera": 1, "radar": 0, "navigation": 3 * 2}
    with open_bag(tmp_path / "rec") as b:
        (img,) = list(b.images("/camera/front/image_raw"))
        assert img.encoding == "bgr8" and np.array_equal(np.asarray(img.pixels).reshape(4, 6, 3), Img.bgr)
    wire = np.frombuffer(camera_request("camera/front", 0.0, Img.bgr).data, np.uint8).reshape(4, 6, 3)
    assert np.array_equal(wire[0, 0], Img.bgr[3, 0, ::-1]) and np.array_equal(wire, Img.bgr[::-1, :, ::-1])


def test_record_stream_refuses_an_image_of_the_wrong_size(tmp_path):
    rec = record_stream(tmp_path / "rec", port=0)
    channel = grpc.insecure_channel(rec.address)
    try:
        stub = sensor_streaming_pb2_grpc.SensorStreamingStub(channel)
        for data in (b"\0" * (4 * 6 * 2), b""):
            bad = sensor_streaming_pb2.CameraStreamingRequest(data=data, width=6, height=4, frame_id="camera/front")
            with pytest.raises(grpc.RpcError) as e:
                stub.StreamCameraSensor(bad)
            assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT and "not a 6×4 image" in e.value.details()
        mono = sensor_streaming_pb2.CameraStreamingRequest(data=bytes(range(24)), width=6, height=4, frame_id="camera/ir")
        assert stub.StreamCameraSensor(mono).success
    finally:
        channel.close()
        rec.stop()
    with open_bag(tmp_path / "rec") as b:
        (img,) = list(b.images("/camera/ir/image_raw"))
    assert img.encoding == "mono8" and np.array_equal(np.asarray(img.pixels).reshape(4, 6), np.arange(24).reshape(4, 6)[::-1])


def test_radar_spokes_keep_their_azimuths(tmp_path):
    """Every spoke's azimuth and time go on the wire (RadarStreamingRequest) and into the recording."""
    from seatwin.sensors.radar.spokes import RadarSpokes

    rng = np.random.default_rng(1)
    n = 6
    spokes = RadarSpokes(
        range_start=2.5,
        range_increment=0.75,
        min_intensity=3,
        max_intensity=200,
        time_in_seconds=1.6e9 + np.sort(rng.uniform(0.0, 2.5, n)),
        azimuth=np.sort(rng.uniform(0.0, 2 * np.pi, n)),  # uneven: not recoverable from the row index
        intensities=rng.integers(0, 255, (n, 5), dtype=np.uint8),
    )
    req = radar_request(spokes)
    assert (req.numSpokes, req.numSamples) == (n, 5) and len(req.azimuth) == len(req.timeInSeconds) == n
    assert np.array_equal(np.asarray(req.azimuth, np.float32), spokes.azimuth.astype(np.float32))
    assert np.array_equal(np.asarray(req.timeInSeconds), spokes.time_in_seconds)

    class Scan:  # what the radar sensor captures, with its spokes
        pass

    scan = Scan()
    scan.spokes = spokes
    rec = record_stream(tmp_path / "rec", port=0)
    streamer = SensorStreamer(rec.address)
    try:
        streamer.on_frame(object(), 1.6e9, 0, scan)
        streamer.on_frame(object(), 1.6e9 + 2.5, 1, scan)
    finally:
        streamer.close()
        counts = rec.stop()
    assert counts["radar"] == 2 and streamer.sent["radar"] == 2
    got = recorded_spokes(tmp_path / "rec")
    assert len(got) == 2
    for g in got:
        assert np.array_equal(g.azimuth, spokes.azimuth.astype(np.float32).astype(np.float64))
        assert np.array_equal(g.time_in_seconds, spokes.time_in_seconds)
        assert np.array_equal(g.intensities, spokes.intensities)
        assert (g.range_start, g.range_increment, g.min_intensity, g.max_intensity) == (2.5, 0.75, 3, 200)


def test_stream_to_a_port_where_nothing_listens_fails_at_once_in_one_line(tmp_path, capsys):
    import socket

    from seatwin.cli.main import run
    from seatwin.errors import ParameterError

    with socket.socket() as s:  # a free port, closed again: nothing listens there
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with pytest.raises(ParameterError, match=rf"nothing answers at 127.0.0.1:{port} \(waited 0.5 s\)"):
        SensorStreamer(f"127.0.0.1:{port}", connect_timeout_s=0.5)
    args = ["simulate", "ferry_crossing", "--duration", "1", "--sensors", "lidar", "--no-progress"]
    assert run([*args, "--out", str(tmp_path / "r"), "--stream", f"127.0.0.1:{port}"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--stream" in err[0] and f"nothing answers at 127.0.0.1:{port}" in err[0]
    assert not (tmp_path / "r" / "manifest.json").exists()  # failed before the run started


@pytest.mark.slow
def test_a_bag_recorded_from_simulate_stream_can_be_tracked(tmp_path):
    """simulate → --stream → record-stream: the NavigationRequests are the ownship's ground truth and the lidar mount
    is the thesis rig's, so ``seatwin track`` runs on the streamed bag as on simulate's own."""
    from seatwin.pipeline.simulate import simulate_run
    from seatwin.pipeline.track import map_hint, track_recording

    rec = record_stream(tmp_path / "rec", port=0)
    streamer = SensorStreamer(rec.address)
    try:
        sim = tmp_path / "sim"
        res = simulate_run("ferry_crossing", sim, duration=4.0, progress=False, sensors=("lidar",), on_frame=streamer.on_frame)
    finally:
        streamer.close()
        rec.stop()
    water = map_hint(json.loads((sim / "manifest.json").read_text()), sim)  # the stream carries no map: give both the same
    a = track_recording(sim, sensors=("lidar",), map_spec=water)
    b = track_recording(tmp_path / "rec", sensors=("lidar",), map_spec=water)
    assert b.n_scans == a.n_scans == res.frames["lidar"] == 40
    assert b.n_confirmed == a.n_confirmed >= 1 and b.n_tracks == a.n_tracks
    assert np.array_equal(b.tracks.track_id, a.tracks.track_id)
    np.testing.assert_allclose(b.tracks.state[:, :2], a.tracks.state[:, :2], atol=1e-2)  # the ownship pose: float32 on the wire
