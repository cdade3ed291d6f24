"""Gemini's ``SensorStreaming`` and ``Navigation`` services, both sides.

* :class:`SensorStreamer` — the client: its :meth:`~SensorStreamer.on_frame` is the loop's
  ``on_frame`` hook (``seatwin simulate --stream``, ``seatwin serve --stream``) and sends every lidar
  cloud as a ``LidarStreamingRequest`` (thesis Table 4.2 layout, one row of points, little endian),
  every camera image as a ``CameraStreamingRequest`` (rgb8, frame ``camera/<name>``) and every radar
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

from seatwin.api.proto import navigation_pb2, navigation_pb2_grpc, sensorstreaming_pb2, sensorstreaming_pb2_grpc
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
    data = pack(VLP16_LAYOUT, x=sweep.x, y=sweep.y, z=sweep.z, intensity=sweep.intensity, ring=sweep.ring, time=sweep.time)
    n = len(data) // VLP16_LAYOUT.point_step
    fields = [
        sensorstreaming_pb2.PointField(name=f.name, offset=f.offset, datatype=f.datatype, count=f.count, **_POINTFIELD_CONSTANTS)
        for f in VLP16_LAYOUT.fields
    ]
    return sensorstreaming_pb2.LidarStreamingRequest(
        timeInSeconds=float(t),
        height=1,
        width=n,
        fields=fields,
        isBigEndian=False,
        point_step=VLP16_LAYOUT.point_step,
        row_step=VLP16_LAYOUT.point_step * n,
        data=np.ascontiguousarray(data).tobytes(),
        is_dense=True,
        frame_id=frame_id,
    )


def camera_request(frame_id: str, t: float, bgr: np.ndarray) -> Any:
    """A ``CameraStreamingRequest`` of an H×W×3 bgr8 image, sent as rgb8 (3 bytes a pixel, rows top down)."""
    rgb = np.ascontiguousarray(np.asarray(bgr, np.uint8)[:, :, ::-1])
    return sensorstreaming_pb2.CameraStreamingRequest(
        data=rgb.tobytes(), timeStamp=float(t), width=rgb.shape[1], height=rgb.shape[0], frame_id=frame_id
    )


def radar_request(spokes: Any) -> Any:
    """A ``RadarStreamingRequest`` of one rotation's spokes (:class:`seatwin.sensors.radar.spokes.RadarSpokes`)."""
    d = spokes.to_request_dict()
    return sensorstreaming_pb2.RadarStreamingRequest(
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


class SensorStreamer:
    """A ``SensorStreaming`` client for the loop's ``on_frame`` hook; counts what it sent."""

    def __init__(self, address: str, timeout_s: float = 30.0):
        import grpc

        from seatwin.api.server import GRPC_OPTIONS

        if ":" not in address:
            raise ParameterError("stream", f"expected HOST:PORT, got {address!r}")
        self.address = address
        self._grpc = grpc
        self.channel = grpc.insecure_channel(address, options=GRPC_OPTIONS)
        self.stub = sensorstreaming_pb2_grpc.SensorStreamingStub(self.channel)
        self.timeout_s = timeout_s
        self.sent: dict[str, int] = {"lidar": 0, "camera": 0, "radar": 0}

    def _send(self, call: Callable[..., Any], request: Any, kind: str) -> None:
        try:
            call(request, timeout=self.timeout_s, wait_for_ready=True)
        except self._grpc.RpcError as exc:
            raise ParameterError("stream", f"streaming to {self.address} failed: {exc.code().name}: {exc.details()}") from None
        self.sent[kind] += 1

    def on_frame(self, sensor: Any, t: float, frame: int, data: Any) -> None:
        """The loop's hook: stream a lidar sweep or a radar rotation's spokes (ground truth is not streamed)."""
        if hasattr(sensor, "lidar"):  # a LidarSensor
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


@dataclass
class StreamRecorder:
    """Writes streamed sensor data and navigation messages into a recording (thread-safe)."""

    writer: Any
    ownship: str | None = None
    counts: dict[str, int] = field(default_factory=lambda: {"lidar": 0, "camera": 0, "radar": 0, "navigation": 0})
    lock: threading.Lock = field(default_factory=threading.Lock)

    def lidar(self, r: Any) -> None:
        layout = _layout_of(r)
        buf = np.frombuffer(r.data, dtype=np.uint8)
        if r.isBigEndian:
            raise InputError("LidarStreamingRequest", "big-endian clouds are not supported")
        n = int(r.width) * max(int(r.height), 1)
        if len(buf) < n * layout.point_step:
            raise InputError("LidarStreamingRequest", f"data has {len(buf)} bytes, {n} points need {n * layout.point_step}")
        sensor = r.frame_id or "lidar"
        topic = self.writer.topics.topic("lidar", sensor=sensor)
        if layout == VLP16_LAYOUT:
            p = np.frombuffer(r.data, dtype=layout.dtype, count=n)
            self.writer.write_sweep(topic, sensor, r.timeInSeconds, p["x"], p["y"], p["z"], p["intensity"], p["ring"], p["time"])
        else:
            self.writer.write_cloud(topic, sensor, r.timeInSeconds, layout, buf[: n * layout.point_step], bool(r.is_dense))
        self.counts["lidar"] += 1

    def camera(self, r: Any) -> None:
        w, h = int(r.width), int(r.height)
        if w <= 0 or h <= 0 or len(r.data) % (w * h):
            raise InputError("CameraStreamingRequest", f"{len(r.data)} bytes are not a {w}×{h} image")
        c = len(r.data) // (w * h)
        enc = {1: "mono8", 3: "rgb8"}.get(c)
        if enc is None:
            raise InputError("CameraStreamingRequest", f"{c} bytes a pixel: expected 1 (mono8) or 3 (rgb8)")
        sensor = r.frame_id or "camera"
        pixels = np.frombuffer(r.data, np.uint8).reshape(h, w, c)
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


class _Servicer(sensorstreaming_pb2_grpc.SensorStreamingServicer, navigation_pb2_grpc.NavigationServicer):
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
        return sensorstreaming_pb2.LidarStreamingResponse(success=self._call(self.rec.lidar, request, context))

    def StreamCameraSensor(self, request: Any, context: Any) -> Any:  # noqa: N802
        return sensorstreaming_pb2.CameraStreamingResponse(success=self._call(self.rec.camera, request, context))

    def StreamRadarSensor(self, request: Any, context: Any) -> Any:  # noqa: N802
        return sensorstreaming_pb2.RadarStreamingResponse(success=self._call(self.rec.radar, request, context))

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
    compression: str | None = None,
    image_format: str = "raw",
) -> RecorderHandle:
    """Start a ``SensorStreaming`` + ``Navigation`` server recording into the new run directory ``run_dir``
    (``compression``, ``image_format``: the camera images', as :class:`~seatwin.recording.RecordingWriter`)."""
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
    recorder = StreamRecorder(writer, ownship)
    server = grpc.server(futures.ThreadPoolExecutor(max_workers=8), options=server_options(STREAM_MAX_MESSAGE_BYTES))
    servicer = _Servicer(recorder)
    sensorstreaming_pb2_grpc.add_SensorStreamingServicer_to_server(servicer, server)
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
