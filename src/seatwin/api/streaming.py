"""Gemini's ``SensorStreaming`` and ``Navigation`` services, both sides.

* :class:`SensorStreamer` — the client: its :meth:`~SensorStreamer.on_frame` is the loop's
  ``on_frame`` hook (``seatwin simulate --stream``, ``seatwin serve --stream``) and sends every lidar
  cloud as a ``LidarStreamingRequest`` (thesis Table 4.2 layout, one row of points, little endian),
  every camera image as a ``CameraStreamingRequest`` (Gemini's wire order: RGB, rows bottom up; frame
  ``camera/<name>``) and every radar
  rotation's spokes as a ``RadarStreamingRequest``.
* :func:`record_stream` — the server (``seatwin record-stream``): writes what arrives into a ROS bag
  through :class:`~seatwin.recording.RecordingWriter`, as a Gemini/Unity simulator's ROS-side
  recorder: clouds as PointCloud2 on ``/<frame_id>/points`` (the layout they came in), camera images
  as ``sensor_msgs/Image`` on ``/<frame_id>/image_raw``, a radar rotation as a mono8 image (a row per
  spoke, a column per range sample) on ``/radar/spokes`` plus, same stamp, a PointCloud2 on
  ``/radar/spokes/azimuth`` with a point per spoke (row) in :data:`SPOKE_LAYOUT` — the request's
  per-spoke ``azimuth`` [rad clockwise from the bow] and ``timeInSeconds``, and its range start,
  range increment and intensity bounds — so :func:`recorded_spokes` gives back every field of the
  request; and ``NavigationRequest`` as the ground truth of its vessel (position x, y = north, east
  [m] in the scenario's NED frame, heading the quaternion's yaw about z down).
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from concurrent import futures
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from seatwin.api.proto import navigation_pb2, navigation_pb2_grpc, sensor_streaming_pb2, sensor_streaming_pb2_grpc
from seatwin.api.wire import camera_bytes, image_from_wire, lidar_bytes
from seatwin.errors import InputError, ParameterError
from seatwin.recording.pointcloud import FLOAT32, FLOAT64, UINT32, VLP16_LAYOUT, Field, Layout, pack

SPOKES_TOPIC = "/radar/spokes"
SPOKE_AZIMUTH_TOPIC = "/radar/spokes/azimuth"

SPOKE_LAYOUT = Layout(
    fields=(
        Field("azimuth", 0, FLOAT32),
        Field("time", 4, FLOAT64),
        Field("range_start", 12, FLOAT32),
        Field("range_increment", 16, FLOAT32),
        Field("min_intensity", 20, UINT32),
        Field("max_intensity", 24, UINT32),
    ),
    point_step=28,
)
"""A point per spoke of ``/radar/spokes/azimuth`` (row k of the ``/radar/spokes`` image): the
``RadarStreamingRequest``'s ``azimuth`` (float, as on the wire) and ``timeInSeconds`` (double) of
the spoke, and the rotation's ``rangeStart``, ``rangeIncrement``, ``minIntensity``, ``maxIntensity``."""

_POINTFIELD_CONSTANTS = {"INT8": 1, "UINT8": 2, "INT16": 3, "UINT16": 4, "INT32": 5, "UINT32": 6, "FLOAT32": 7, "FLOAT64": 8}


def lidar_request(frame_id: str, t: float, sweep: Any) -> Any:
    """A ``LidarStreamingRequest`` of one sweep (columns x, y, z, intensity, ring, time) in the Table 4.2 layout."""
    data = lidar_bytes(sweep)
    n = len(data) // VLP16_LAYOUT.point_step
    fields = [
        sensor_streaming_pb2.PointField(name=f.name, offset=f.offset, datatype=f.datatype, count=f.count, **_POINTFIELD_CONSTANTS)
        for f in VLP16_LAYOUT.fields
    ]
    return sensor_streaming_pb2.LidarStreamingRequest(
        timeInSeconds=float(t),
        height=1,
        width=n,
        fields=fields,
        isBigEndian=False,
        point_step=VLP16_LAYOUT.point_step,
        row_step=VLP16_LAYOUT.point_step * n,
        data=data,
        is_dense=True,
        frame_id=frame_id,
    )


def camera_request(frame_id: str, t: float, bgr: np.ndarray) -> Any:
    """A ``CameraStreamingRequest`` of an H×W×3 bgr8 image, in Gemini's wire order (:func:`camera_bytes`)."""
    h, w = np.shape(bgr)[:2]
    data = camera_bytes(bgr)
    return sensor_streaming_pb2.CameraStreamingRequest(data=data, timeStamp=float(t), width=w, height=h, frame_id=frame_id)


def radar_request(spokes: Any) -> Any:
    """A ``RadarStreamingRequest`` of one rotation's spokes (:class:`seatwin.sensors.radar.spokes.RadarSpokes`)."""
    d = spokes.to_request_dict()
    return sensor_streaming_pb2.RadarStreamingRequest(
        rangeIncrement=d["range_increment"],
        rangeStart=d["range_start"],
        numSamples=d["num_samples"],
        numSpokes=d["num_spokes"],
        minIntensity=d["min_intensity"],
        maxIntensity=d["max_intensity"],
        timeInSeconds=d["time_in_seconds"],
        azimuth=d["azimuth"],
        radarSpokes=d["radar_spokes"],
    )


CONNECT_TIMEOUT_S = 5.0
"""How long :class:`SensorStreamer` waits for its server to answer before the run starts."""


def navigation_request(t: float, pose: Any) -> Any:
    """A ``NavigationRequest`` of one vessel's ground truth (:class:`~seatwin.recording.VesselPose`): position
    (north, east, down) [m] in the scenario's NED frame, orientation the heading as a rotation about z (down),
    linear velocity (v_north, v_east, 0) [m/s] in that frame, angular velocity (0, 0, yaw rate) [rad/s] —
    what :class:`StreamRecorder` reads back."""
    half = 0.5 * float(pose.heading)
    return navigation_pb2.NavigationRequest(
        timeStamp=float(t),
        position=navigation_pb2.Vec3(x=float(pose.north), y=float(pose.east), z=float(pose.down)),
        orientation=navigation_pb2.Quaternion(x=0.0, y=0.0, z=math.sin(half), w=math.cos(half)),
        linearVelocity=navigation_pb2.Vec3(x=float(pose.v_north), y=float(pose.v_east), z=0.0),
        angularVelocity=navigation_pb2.Vec3(x=0.0, y=0.0, z=float(pose.yaw_rate)),
        vesselName=str(pose.name),
    )


class SensorStreamer:
    """A ``SensorStreaming`` + ``Navigation`` client for the loop's ``on_frame`` hook; counts what it sent.

    It fails at once (:class:`ParameterError`, one line) when nothing answers at ``address`` within
    ``connect_timeout_s``; a call then waits at most ``timeout_s`` for its answer."""

    def __init__(self, address: str, timeout_s: float = 30.0, connect_timeout_s: float = CONNECT_TIMEOUT_S):
        import grpc

        from seatwin.api.channel import GRPC_OPTIONS

        if ":" not in address:
            raise ParameterError("stream", f"expected HOST:PORT, got {address!r}")
        self.address = address
        self._grpc = grpc
        self.channel = grpc.insecure_channel(address, options=GRPC_OPTIONS)
        try:
            grpc.channel_ready_future(self.channel).result(timeout=connect_timeout_s)
        except grpc.FutureTimeoutError:
            self.channel.close()
            raise ParameterError(
                "stream",
                f"nothing answers at {address} (waited {connect_timeout_s:g} s): is a SensorStreaming server running there?",
            ) from None
        self.stub = sensor_streaming_pb2_grpc.SensorStreamingStub(self.channel)
        self.navigation = navigation_pb2_grpc.NavigationStub(self.channel)
        self.timeout_s = timeout_s
        self.sent: dict[str, int] = {"lidar": 0, "camera": 0, "radar": 0, "navigation": 0}

    def _send(self, call: Callable[..., Any], request: Any, kind: str) -> None:
        try:
            call(request, timeout=self.timeout_s, wait_for_ready=True)
        except self._grpc.RpcError as exc:
            raise ParameterError("stream", f"streaming to {self.address} failed: {exc.code().name}: {exc.details()}") from None
        self.sent[kind] += 1

    def on_frame(self, sensor: Any, t: float, frame: int, data: Any) -> None:
        """The loop's hook: stream a lidar sweep, a rig's camera images, a radar rotation's spokes, or a ground-truth
        frame as a ``NavigationRequest`` per vessel (so a bag recorded from the stream can be tracked)."""
        from seatwin.recording import VesselPose

        if isinstance(data, list) and data and isinstance(data[0], VesselPose):  # ground truth
            for pose in data:
                self._send(self.navigation.SendNavigationMessage, navigation_request(t, pose), "navigation")
        elif hasattr(sensor, "lidar"):  # a LidarSensor
            self._send(self.stub.StreamLidarSensor, lidar_request(sensor.name, t, data), "lidar")
        elif isinstance(data, list) and data and hasattr(data[0], "bgr"):  # a CameraSensor's images
            for img in data:
                self._send(self.stub.StreamCameraSensor, camera_request(f"camera/{img.name}", t, img.bgr), "camera")
        elif getattr(data, "spokes", None) is not None:
            self._send(self.stub.StreamRadarSensor, radar_request(data.spokes), "radar")

    def close(self) -> None:
        self.channel.close()


# -- the ROS-side recorder ------------------------------------------------------------------------


def _layout_of(request: Any) -> Layout:
    fields = tuple(Field(f.name, int(f.offset), int(f.datatype), int(f.count) or 1) for f in request.fields)
    if not fields or request.point_step <= 0:
        raise InputError("LidarStreamingRequest", "a cloud needs fields and a point_step")
    return Layout(fields, int(request.point_step))


def heading_of_quaternion(x: float, y: float, z: float, w: float) -> float:
    """Yaw [rad] of a quaternion about z: the heading clockwise from north in NED (z down)."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def thesis_mounts(ownship: str, topics: Any) -> dict[str, list[Any]]:
    """The mounts ``seatwin simulate`` records for its default sensors on ``ownship`` (the thesis's milliAmpere rig:
    the lidar upside down at its measured height, the radar, each rig camera's optical frame), by frame id as the
    sensors stream them (``lidar``, ``radar``, ``camera/<name>``), each hung on ``{ownship}/base_link`` as
    :func:`~seatwin.recording.tf_tree.sensor_mount` does for a simulated run. Gemini's streaming carries no mounts."""
    from seatwin.recording.tf_tree import sensor_mount
    from seatwin.sensors.camera.config import CameraConfig
    from seatwin.sensors.camera.rig import rig_mounts
    from seatwin.sensors.lidar_config import MILLIAMPERE_LIDAR_MOUNT
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.sim.radar import radar_mount

    m = MILLIAMPERE_LIDAR_MOUNT
    out = {"lidar": sensor_mount(topics, ownship, "lidar", (m.x, m.y, m.z), m.rotation(), math.radians(m.roll_deg))}
    out["radar"] = radar_mount(RadarConfig(), ownship, "radar", topics, frame_id="radar")
    for cam in rig_mounts(CameraConfig()):
        out[f"camera/{cam.name}"] = sensor_mount(topics, ownship, f"camera/{cam.name}", cam.translation, cam.rotation)
    return out


@dataclass
class StreamRecorder:
    """Writes streamed sensor data and navigation messages into a recording (thread-safe); the first frame of a
    sensor whose frame id has an entry in ``mounts`` also writes that mount on /tf_static."""

    writer: Any
    ownship: str | None = None
    counts: dict[str, int] = field(default_factory=lambda: {"lidar": 0, "camera": 0, "radar": 0, "navigation": 0})
    lock: threading.Lock = field(default_factory=threading.Lock)
    mounts: dict[str, list[Any]] = field(default_factory=dict)

    def _mount(self, frame_id: str, t: float) -> None:
        mount = self.mounts.pop(frame_id, None)
        if mount:
            self.writer.write_static_transforms(t, mount)

    def lidar(self, r: Any) -> None:
        layout = _layout_of(r)
        buf = np.frombuffer(r.data, dtype=np.uint8)
        if r.isBigEndian:
            raise InputError("LidarStreamingRequest", "big-endian clouds are not supported")
        n = int(r.width) * max(int(r.height), 1)
        if len(buf) < n * layout.point_step:
            raise InputError("LidarStreamingRequest", f"data has {len(buf)} bytes, {n} points need {n * layout.point_step}")
        sensor = r.frame_id or "lidar"
        self._mount(sensor, r.timeInSeconds)
        topic = self.writer.topics.topic("lidar", sensor=sensor)
        if layout == VLP16_LAYOUT:
            p = np.frombuffer(r.data, dtype=layout.dtype, count=n)
            self.writer.write_sweep(topic, sensor, r.timeInSeconds, p["x"], p["y"], p["z"], p["intensity"], p["ring"], p["time"])
        else:
            self.writer.write_cloud(topic, sensor, r.timeInSeconds, layout, buf[: n * layout.point_step], bool(r.is_dense))
        self.counts["lidar"] += 1

    def camera(self, r: Any) -> None:
        """Gemini's wire order (:func:`camera_bytes`: RGB, rows bottom up) recorded as its ROS adapter publishes
        it: bgr8, rows top down; 1 byte a pixel: mono8, rows flipped the same way."""
        w, h = int(r.width), int(r.height)
        if w <= 0 or h <= 0 or len(r.data) != 3 * w * h and len(r.data) != w * h:
            expected = f"expected {3 * w * h} RGB or {w * h} mono"
            raise InputError("CameraStreamingRequest", f"{len(r.data)} bytes are not a {w}×{h} image ({expected})")
        sensor = r.frame_id or "camera"
        self._mount(sensor, r.timeStamp)
        if len(r.data) == w * h:
            pixels, enc = np.ascontiguousarray(np.frombuffer(r.data, np.uint8).reshape(h, w)[::-1]), "mono8"
        else:
            pixels, enc = image_from_wire(r.data, w, h), "bgr8"
        self.writer.write_image(self.writer.topics.topic("camera", sensor=sensor), sensor, r.timeStamp, pixels, enc)
        self.counts["camera"] += 1

    def radar(self, r: Any) -> None:
        ns, nr = int(r.numSpokes), int(r.numSamples)
        if ns <= 0 or nr <= 0 or len(r.radarSpokes) != ns * nr:
            raise InputError("RadarStreamingRequest", f"radarSpokes has {len(r.radarSpokes)} bytes, not {ns}×{nr}")
        for name in ("azimuth", "timeInSeconds"):
            if len(getattr(r, name)) not in (0, ns):
                raise InputError("RadarStreamingRequest", f"{name} has {len(getattr(r, name))} values for {ns} spokes")
        times = np.asarray(r.timeInSeconds, np.float64) if len(r.timeInSeconds) else np.zeros(ns)
        azimuth = np.asarray(r.azimuth, np.float32) if len(r.azimuth) else np.full(ns, np.nan, np.float32)
        t = float(times[0])
        self._mount("radar", t)
        img = np.frombuffer(r.radarSpokes, np.uint8).reshape(ns, nr)
        self.writer.write_image(SPOKES_TOPIC, "radar", t, img, "mono8", image_format="raw")  # data, not a picture
        spokes = pack(
            SPOKE_LAYOUT,
            azimuth=azimuth,
            time=times,
            range_start=np.full(ns, r.rangeStart, np.float32),
            range_increment=np.full(ns, r.rangeIncrement, np.float32),
            min_intensity=np.full(ns, r.minIntensity, np.uint32),
            max_intensity=np.full(ns, r.maxIntensity, np.uint32),
        )
        self.writer.write_cloud(SPOKE_AZIMUTH_TOPIC, "radar", t, SPOKE_LAYOUT, spokes)
        self.counts["radar"] += 1

    def navigation(self, r: Any) -> None:
        from seatwin.recording import VesselPose

        if not r.vesselName:
            raise InputError("NavigationRequest", "vesselName is empty")
        q = r.orientation
        values = [r.timeStamp, r.position.x, r.position.y, q.x, q.y, q.z, q.w]
        if not all(math.isfinite(v) for v in values):
            raise InputError("NavigationRequest", f"non-finite values in the message of {r.vesselName!r}")
        pose = VesselPose(
            name=r.vesselName,
            north=float(r.position.x),
            east=float(r.position.y),
            down=float(r.position.z),
            heading=heading_of_quaternion(q.x, q.y, q.z, q.w) if (q.x, q.y, q.z, q.w) != (0, 0, 0, 0) else 0.0,
            v_north=float(r.linearVelocity.x),
            v_east=float(r.linearVelocity.y),
            yaw_rate=float(r.angularVelocity.z),
            ownship=r.vesselName == self.ownship,
        )
        self.writer.write_ground_truth(float(r.timeStamp), [pose])
        self.counts["navigation"] += 1


class _Servicer(sensor_streaming_pb2_grpc.SensorStreamingServicer, navigation_pb2_grpc.NavigationServicer):
    def __init__(self, recorder: StreamRecorder):
        self.rec = recorder

    def _call(self, fn: Callable[[Any], None], request: Any, context: Any) -> bool:
        import grpc

        from seatwin.recording import RecordingError

        with self.rec.lock:
            try:
                fn(request)
            except RecordingError as exc:  # the disk, or the recording finished (after Ctrl-C/SIGTERM): not the request
                context.abort(grpc.StatusCode.UNAVAILABLE, str(exc))
            except InputError as exc:
                context.abort(grpc.StatusCode.INVALID_ARGUMENT, str(exc))
        return True

    def StreamLidarSensor(self, request: Any, context: Any) -> Any:  # noqa: N802 - Gemini's name
        return sensor_streaming_pb2.LidarStreamingResponse(success=self._call(self.rec.lidar, request, context))

    def StreamCameraSensor(self, request: Any, context: Any) -> Any:  # noqa: N802
        return sensor_streaming_pb2.CameraStreamingResponse(success=self._call(self.rec.camera, request, context))

    def StreamRadarSensor(self, request: Any, context: Any) -> Any:  # noqa: N802
        return sensor_streaming_pb2.RadarStreamingResponse(success=self._call(self.rec.radar, request, context))

    def SendNavigationMessage(self, request: Any, context: Any) -> Any:  # noqa: N802
        return navigation_pb2.NavigationResponse(success=self._call(self.rec.navigation, request, context))


@dataclass
class RecorderHandle:
    """A running ``SensorStreaming`` + ``Navigation`` server: its port and :meth:`stop`."""

    server: Any
    host: str
    port: int
    recorder: StreamRecorder
    _stopped: bool = False

    @property
    def address(self) -> str:
        return f"{self.host}:{self.port}"

    def stop(self, grace: float | None = 1.0, completed: bool = True) -> dict[str, int]:
        """Stop serving, finish the bag (manifest ``completed``); return what was recorded."""
        if not self._stopped:
            self._stopped = True
            self.server.stop(grace).wait()
            with self.recorder.lock:
                self.recorder.writer.close(completed=completed)
        return dict(self.recorder.counts)


def record_stream(
    run_dir: str | Path,
    *,
    port: int = 50052,
    host: str = "127.0.0.1",
    fmt: str = "mcap",
    ownship: str | None = "milliAmpere",
    mounts: bool = True,
    compression: str | None = None,
    image_format: str = "raw",
) -> RecorderHandle:
    """Start a ``SensorStreaming`` + ``Navigation`` server recording into the new run directory ``run_dir``
    (``compression``, ``image_format``: the camera images', as :class:`~seatwin.recording.RecordingWriter`).

    ``mounts``: write the thesis rig's sensor mounts (:func:`thesis_mounts`) on /tf_static as each sensor first
    streams, so the bag can be tracked with the ``NavigationRequest``s as ownship ground truth."""
    import grpc

    from seatwin.api.server import STREAM_MAX_MESSAGE_BYTES, bind, check_port, server_options
    from seatwin.recording import RecordingWriter
    from seatwin.recording.config import check_compression, check_format, check_image_format
    from seatwin.recording.manifest import MANIFEST_NAME
    from seatwin.scenario.defaults import RAVNKLOA

    check_port(port)
    options = {"compression": check_compression(check_format(fmt), compression), "image_format": check_image_format(image_format)}
    run_dir = Path(run_dir)
    if (run_dir / MANIFEST_NAME).exists():
        raise InputError(run_dir, "a recording exists here already; choose a new run directory")
    run_dir.mkdir(parents=True, exist_ok=True)
    writer = RecordingWriter(run_dir, fmt, origin=RAVNKLOA, metadata={"recorded_by": "seatwin record-stream"}, **options)
    recorder = StreamRecorder(writer, ownship, mounts=thesis_mounts(ownship, writer.topics) if mounts and ownship else {})
    server = grpc.server(futures.ThreadPoolExecutor(max_workers=8), options=server_options(STREAM_MAX_MESSAGE_BYTES))
    servicer = _Servicer(recorder)
    sensor_streaming_pb2_grpc.add_SensorStreamingServicer_to_server(servicer, server)
    navigation_pb2_grpc.add_NavigationServicer_to_server(servicer, server)
    try:
        bound = bind(server, host, port)
    except ParameterError:
        writer.close(completed=False, error="the server could not start")
        raise
    server.start()
    return RecorderHandle(server, host, bound, recorder)


def recorded_spokes(run_dir: str | Path) -> list[Any]:
    """Every radar rotation ``record-stream`` recorded, as :class:`~seatwin.sensors.radar.spokes.RadarSpokes`
    (azimuths and range fields as the requests carried them: float32; times float64)."""
    from seatwin.recording import open_bag
    from seatwin.sensors.radar.spokes import RadarSpokes

    with open_bag(run_dir) as bag:
        images = list(bag.images(SPOKES_TOPIC))
        clouds = list(bag.point_clouds(SPOKE_AZIMUTH_TOPIC))
    if len(images) != len(clouds):
        raise InputError(run_dir, f"{len(images)} radar spoke images but {len(clouds)} {SPOKE_AZIMUTH_TOPIC} messages")
    out = []
    for img, cloud in zip(images, clouds):
        p, px = cloud.points, np.asarray(img.pixels, np.uint8)
        if px.shape[0] != len(p) or abs(img.stamp - cloud.stamp) > 1e-6:
            raise InputError(run_dir, f"the spoke image at {img.stamp!r} does not match its azimuths at {cloud.stamp!r}")
        out.append(
            RadarSpokes(
                range_start=float(p["range_start"][0]),
                range_increment=float(p["range_increment"][0]),
                min_intensity=int(p["min_intensity"][0]),
                max_intensity=int(p["max_intensity"][0]),
                time_in_seconds=np.asarray(p["time"], np.float64),
                azimuth=np.asarray(p["azimuth"], np.float64),
                intensities=px.reshape(len(p), -1),
            )
        )
    return out
