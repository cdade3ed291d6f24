"""RecordingWriter: a run directory holding a bag (rosbag2 MCAP or SQLite3, or ROS 1), the resolved
scenario and ``manifest.json``.

Layout of ``run_dir``::

    recording/            rosbag2 directory (metadata.yaml + recording.mcap | recording.db3)
    recording.bag         … or the ROS 1 bag
    manifest.json         seatwin version, seed, sensors, per-topic counts, completed flag
    <scenario file>       the resolved scenario (copied or written by the caller)

Data reach the operating system at least every ``flush_interval_s`` of recorded time or
``flush_wall_s`` of wall time, whichever comes first (MCAP: the open chunk is closed and the file
flushed; SQLite3: a commit; ROS 1: the open chunk is written), so a run killed with SIGKILL leaves
a bag readable up to its last flush (see :mod:`seatwin.recording.reader`). ``fsync=True`` also
forces them to the disk (for power loss; slower). The manifest's counts are refreshed at a flush
at most every ``manifest_wall_s`` of wall time; they never exceed what the bag holds.
"""

from __future__ import annotations

import contextlib
import datetime as dt
import functools
import os
import shutil
import time as _time
from collections.abc import Callable, Sequence
from pathlib import Path
from types import TracebackType
from typing import Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from seatwin import __version__
from seatwin.defaults import DEFAULT_IMAGE_FORMAT, DEFAULT_ROS_DISTRO, JPEG_QUALITY
from seatwin.errors import InputError
from seatwin.geo import GeodeticOrigin
from seatwin.recording import messages as M
from seatwin.recording.config import TopicConfig, check_compression, check_format, check_image_format, check_ros_distro
from seatwin.recording.fast_cdr import (
    NAV_SAT_FIX,
    ODOMETRY,
    POINT_CLOUD2,
    POSE_STAMPED,
    TF_MESSAGE,
    GroundTruthEncoder,
    PointCloudEncoder,
    VesselFrames,
)
from seatwin.recording.manifest import MANIFEST_NAME, MANIFEST_VERSION, write_manifest
from seatwin.recording.pointcloud import RADAR_LAYOUT, VLP16_LAYOUT, Layout
from seatwin.recording.storage import BagStorage, bag_path, open_storage
from seatwin.recording.tf_tree import vessel_transforms

F = TypeVar("F", bound=Callable[..., Any])


def _timed(method: F) -> F:
    """Add the time spent in an outermost public call to ``self.timing["total_s"]`` (less ``on_write``'s)."""

    @functools.wraps(method)
    def wrapper(self: RecordingWriter, *args: Any, **kwargs: Any) -> Any:
        if self._depth:
            return method(self, *args, **kwargs)
        self._depth = 1
        t0, live0 = _time.perf_counter(), self.timing["live_s"]
        try:
            return method(self, *args, **kwargs)
        finally:
            self._depth = 0
            self.timing["total_s"] += _time.perf_counter() - t0 - (self.timing["live_s"] - live0)

    return wrapper  # type: ignore[return-value]


class RecordingError(InputError):
    """Writing the recording failed (e.g. out of disk): names the bag; the bag so far stays readable, the
    manifest says incomplete and why. An :class:`~seatwin.errors.InputError`, so the CLI prints one line
    and exits with status 2."""


class RecordingWriter:
    """Write one run: sensor data, ground truth and tf into a bag, plus the manifest.

    Use as a context manager; leaving it normally marks the run completed, leaving it by an
    exception closes the bag cleanly but records ``completed: false`` and the error.

    ``scenario_file`` is copied into ``run_dir`` (a file already there is just named in the
    manifest); ``sensors`` and ``metadata`` go into the manifest as given (JSON-serialisable).
    ``ros_distro`` picks a rosbag2 bag's metadata version (:data:`~seatwin.defaults.ROS_DISTROS`).
    ``compression``: the bag's chunk compression (:data:`~seatwin.defaults.COMPRESSIONS`; None: the format's
    default, lz4 for MCAP and ROS 1). ``image_format``: :meth:`write_image` writes ``sensor_msgs/Image`` (``raw``) or a
    JPEG/PNG ``sensor_msgs/CompressedImage`` on ``<topic>/compressed`` (``jpeg``, ``png``).
    ``on_write`` sees every message written (:attr:`on_write`).
    """

    def __init__(
        self,
        run_dir: str | os.PathLike[str],
        fmt: str = "mcap",
        *,
        topics: TopicConfig | None = None,
        origin: GeodeticOrigin | None = None,
        seed: int | None = None,
        sensors: dict[str, Any] | None = None,
        scenario_file: str | os.PathLike[str] | None = None,
        metadata: dict[str, Any] | None = None,
        flush_interval_s: float = 1.0,
        flush_wall_s: float = 2.0,
        manifest_wall_s: float = 0.25,
        row_step_zero: bool = False,
        fsync: bool = False,
        ros_distro: str = DEFAULT_ROS_DISTRO,
        on_write: Callable[[str, str, int, bytes | memoryview], None] | None = None,
        compression: str | None = None,
        image_format: str = DEFAULT_IMAGE_FORMAT,
    ) -> None:
        self.format = check_format(fmt)
        self.on_write = on_write
        """Called with (topic, type, log time ns, serialised bytes) of every message once it is in the bag (a live
        view: :class:`~seatwin.recording.live.LiveServer`)."""
        ros_distro = check_ros_distro(ros_distro)
        compression = check_compression(self.format, compression)
        self.image_format = check_image_format(image_format)
        self.run_dir = Path(run_dir)
        self.topics = topics or TopicConfig()
        self.origin = origin
        self.store = M.typestore(self.format)
        self.flush_interval_s = float(flush_interval_s)
        self.flush_wall_s = float(flush_wall_s)
        self._last_flush_wall = _time.perf_counter()
        self.manifest_wall_s = float(manifest_wall_s)
        self._last_manifest_wall = float("-inf")
        self.row_step_zero = row_step_zero
        self.fsync = fsync
        self.counts: dict[str, int] = {}
        self.types: dict[str, str] = {}
        self.vessels: dict[str, str] = {}
        self._vessel_slots: dict[tuple[str, bool], tuple[VesselFrames, tuple[tuple[str, str], ...]]] = {}
        self.notes: list[str] = []
        self._conns: dict[str, Any] = {}
        self._t0: float | None = None
        self._t1: float | None = None
        self._last_flush: float | None = None
        self._static_written = False
        self._closed = False
        self._error: str | None = None
        self._serialize = self.store.serialize_ros1 if self.format == "ros1" else self.store.serialize_cdr
        self._gt = GroundTruthEncoder(self.format)
        self._clouds = PointCloudEncoder(self.format, row_step_zero)
        self.bag = bag_path(self.run_dir, self.format)
        self.timing = {"total_s": 0.0, "serialize_s": 0.0, "write_s": 0.0, "live_s": 0.0}
        """Seconds spent in this writer's calls (``total_s``; recording_share = total_s / wall time),
        of which serialising and handing bytes to the bag storage; ``live_s``: in ``on_write`` (not in the others)."""
        self._depth = 0
        self._frame_depth = 0
        self._frame_block = _FrameBlock(self._begin_frame, self._end_frame)
        self._flush_due: float | None = None
        """A flush postponed to the end of the :meth:`frame` block (the time it became due)."""

        for existing in (self.bag, self.run_dir / MANIFEST_NAME):
            if existing.exists():
                raise InputError(existing, "a recording exists here already; choose a new run directory")
        self.run_dir.mkdir(parents=True, exist_ok=True)
        scenario_name = None
        if scenario_file is not None:
            src = Path(scenario_file)
            if not src.is_file():
                raise InputError(src, "scenario file to record beside the bag does not exist")
            scenario_name = src.name
            if src.resolve() != (self.run_dir / src.name).resolve():
                shutil.copyfile(src, self.run_dir / src.name)
        self._manifest: dict[str, Any] = {
            "manifest_version": MANIFEST_VERSION,
            "seatwin_version": __version__,
            "completed": False,
            "format": self.format,
            "bag": self.bag.name,
            "started_utc": _utcnow(),
            "finished_utc": None,
            "seed": seed,
            "origin": None
            if origin is None
            else {"lat_deg": origin.lat_deg, "lon_deg": origin.lon_deg, "height_m": origin.height_m},
            "scenario": scenario_name,
            "sensors": sensors or {},
            "topic_config": self.topics.to_dict(),
            "metadata": metadata or {},
        }
        if self.format != "ros1":
            self._manifest["ros_distro"] = ros_distro
        self._manifest.update(compression=compression, image_format=self.image_format)
        self.storage: BagStorage = open_storage(
            self.format, self.bag, self.store, fsync=fsync, ros_distro=ros_distro, compression=compression
        )
        """The bag file(s): one :class:`~seatwin.recording.storage.BagStorage` class per format."""
        self._write_manifest()

    def _connection(self, topic: str, msgtype: str) -> Any:
        conn = self._conns.get(topic)
        if conn is not None:
            if self.types[topic] != msgtype:
                raise InputError(topic, f"topic already carries {self.types[topic]}, cannot write {msgtype}")
            return conn
        conn = self.storage.add_connection(topic, msgtype, latched=topic == self.topics.tf_static)
        self._conns[topic] = conn
        self.types[topic] = msgtype
        self.counts[topic] = 0
        return conn

    # ------------------------------------------------------------------ generic writing
    @_timed
    def write(self, topic: str, t: float, msg: Any) -> None:
        """Serialise and write a message object (from this writer's ``store``) at POSIX time ``t``."""
        t0 = _time.perf_counter()
        data = self._serialize(msg, msg.__msgtype__)
        self.timing["serialize_s"] += _time.perf_counter() - t0
        self.write_raw(topic, msg.__msgtype__, t, data)

    @_timed
    def write_raw(self, topic: str, msgtype: str, t: float, data: bytes | memoryview) -> None:
        """Write an already serialised message (CDR for rosbag2, ROS 1 for .bag)."""
        self._write_batch(t, ((topic, msgtype, data),))

    def _write_batch(self, t: float, items: Sequence[tuple[str, str, bytes | memoryview]]) -> None:
        """Write serialised messages all stamped ``t`` (one stamp conversion, one flush check); count them."""
        if self._closed:
            raise RecordingError(self.bag, "recording is closed")
        t0 = _time.perf_counter()
        try:
            stamp = M.stamp_ns(t)
            conns, types = self._conns, self.types
            batch = []
            for topic, msgtype, data in items:
                conn = conns.get(topic)
                if conn is None or types[topic] != msgtype:
                    break
                batch.append((conn, data))
            else:
                self.storage.write_many(batch, stamp)
                batch = None
            if batch is not None:  # a topic's first message: its connection goes into the bag just before it
                for topic, msgtype, data in items:
                    self.storage.write(self._connection(topic, msgtype), stamp, data)
            counts = self.counts
            for topic, _, _ in items:
                counts[topic] += 1
            if self.on_write is not None:
                t_live = _time.perf_counter()
                try:
                    for topic, msgtype, data in items:
                        self.on_write(topic, msgtype, stamp, data)
                finally:
                    live = _time.perf_counter() - t_live
                    self.timing["live_s"] += live
                    t0 += live  # not the bag's time
            if self._t0 is None or t < self._t0:
                self._t0 = t
            if self._t1 is None or t > self._t1:
                self._t1 = t
            if self._last_flush is None:
                self._last_flush = t
            elif t - self._last_flush >= self.flush_interval_s or t0 - self._last_flush_wall >= self.flush_wall_s:
                if self._frame_depth:
                    self._flush_due = t
                else:
                    self.flush()
                    self._last_flush, self._last_flush_wall = t, t0
        except OSError as exc:
            self._fail(exc)
        finally:
            self.timing["write_s"] += _time.perf_counter() - t0

    def frame(self) -> _FrameBlock:
        """A block whose messages (one frame's) reach the disk together: a flush that falls due inside it
        waits for its end, so a run killed outright (SIGKILL) leaves a SQLite3 bag ending at a frame boundary."""
        return self._frame_block

    def _begin_frame(self) -> None:
        self._frame_depth += 1

    def _end_frame(self) -> None:
        self._frame_depth -= 1
        if not self._frame_depth and self._flush_due is not None and not self._closed:
            t, self._flush_due = self._flush_due, None
            self.flush()
            self._last_flush, self._last_flush_wall = t, _time.perf_counter()

    @_timed
    def flush(self) -> None:
        """Flush the bag and refresh the manifest (``completed`` stays false until :meth:`close`)."""
        try:
            self.storage.flush()
            # The manifest (a small file rewritten and renamed) is refreshed at most once per
            # ``manifest_wall_s`` of wall time: at high real-time factors rewriting it at every
            # flush cost more than recording the data. It never claims more than was flushed.
            now = _time.perf_counter()
            if now - self._last_manifest_wall >= self.manifest_wall_s:
                self._write_manifest()
                self._last_manifest_wall = now
        except OSError as exc:
            self._fail(exc)

    def _fail(self, exc: OSError) -> None:
        self._error = f"{type(exc).__name__}: {_strerror(exc)}"
        self._closed = True
        with contextlib.suppress(Exception):  # the bag is being abandoned; its readable prefix stays
            self.storage.abort()
        with contextlib.suppress(OSError):
            self._write_manifest()
        raise RecordingError(
            self.bag, f"recording stopped: {_strerror(exc)}; the bag is readable up to its last flush ({MANIFEST_NAME} says so)"
        ) from exc

    # ------------------------------------------------------------------ typed helpers
    @_timed
    def write_sweep(
        self,
        topic: str,
        frame_id: str,
        t: float,
        x: ArrayLike,
        y: ArrayLike,
        z: ArrayLike,
        intensity: ArrayLike,
        ring: ArrayLike,
        time: ArrayLike,
    ) -> None:
        """A lidar sweep as PointCloud2 in the VLP-16 layout (thesis Table 4.2); ``t`` = sweep start,
        ``time`` = seconds since it; pass only returned points (no-return beams omitted: is_dense)."""
        columns = {"x": x, "y": y, "z": z, "intensity": intensity, "ring": ring, "time": time}
        self._write_cloud(topic, t, lambda: self._clouds.encode(t, frame_id, VLP16_LAYOUT, columns))

    @_timed
    def write_cloud(self, topic: str, frame_id: str, t: float, layout: Layout, data: np.ndarray, is_dense: bool = True) -> None:
        """A PointCloud2 of any fixed ``layout`` from packed bytes (see :func:`pointcloud.pack`)."""
        self._write_cloud(topic, t, lambda: self._clouds.encode_packed(t, frame_id, layout, data, is_dense))

    def _write_cloud(self, topic: str, t: float, encode: Callable[[], bytearray]) -> None:
        """Serialise a PointCloud2 directly (:class:`~seatwin.recording.fast_cdr.PointCloudEncoder`) and write it."""
        t0 = _time.perf_counter()
        data = encode()
        self.timing["serialize_s"] += _time.perf_counter() - t0
        self._write_batch(t, ((topic, POINT_CLOUD2, data),))

    @_timed
    def write_radar(
        self,
        topic: str,
        frame_id: str,
        t: float,
        x: ArrayLike,
        y: ArrayLike,
        z: ArrayLike | None = None,
        *,
        intensity: ArrayLike | None = None,
        range: ArrayLike | None = None,
        bearing: ArrayLike | None = None,
        time: ArrayLike | None = None,
        origin: tuple[float, float] = (0.0, 0.0),
    ) -> None:
        """Radar plots of one scan as PointCloud2 (:data:`pointcloud.RADAR_LAYOUT`).

        ``x, y, z`` in ``frame_id`` (the radar frame, or the world NED frame for imported data);
        range and bearing default to those of (x, y) seen from ``origin`` (the radar's x, y in
        that frame), bearing clockwise from x seen from above — in a z-up (FLU) frame that is
        atan2(−y, x), in the z-down world NED frame atan2(y, x).
        """
        xa, ya = np.asarray(x, float).reshape(-1), np.asarray(y, float).reshape(-1)
        dx, dy = xa - origin[0], ya - origin[1]
        z_down = frame_id == self.topics.world_frame or frame_id.endswith("_ned")
        if range is None:
            range = np.hypot(dx, dy)
        if bearing is None:
            bearing = np.arctan2(dy if z_down else -dy, dx)
        columns = {"x": xa, "y": ya, "z": z, "intensity": intensity, "range": range, "bearing": bearing, "time": time}
        self._write_cloud(topic, t, lambda: self._clouds.encode(t, frame_id, RADAR_LAYOUT, columns))

    @_timed
    def write_image(
        self, topic: str, frame_id: str, t: float, pixels: np.ndarray, encoding: str = "bgr8", image_format: str | None = None
    ) -> None:
        """A camera image in ``image_format`` (default: the writer's :attr:`image_format`): a ``sensor_msgs/Image``
        on ``topic`` (raw; thesis: bgr8, 612×512), or a JPEG/PNG ``sensor_msgs/CompressedImage`` on
        ``topic + "/compressed"`` (image_transport's convention: ``/camera/front/image_raw/compressed``)."""
        kind = self.image_format if image_format is None else check_image_format(image_format)
        if kind == "raw":
            self.write(topic, t, M.image(self.store, t, frame_id, pixels, encoding))
        else:
            self.write_compressed_image(f"{topic}/compressed", frame_id, t, pixels, kind, encoding)

    @_timed
    def write_camera_info(
        self,
        topic: str,
        frame_id: str,
        t: float,
        width: int,
        height: int,
        k: ArrayLike,
        d: Sequence[float],
        r: ArrayLike | None = None,
        p: ArrayLike | None = None,
        distortion_model: str = "plumb_bob",
    ) -> None:
        """A ``sensor_msgs/CameraInfo``: K (3×3), D (plumb-bob k1 k2 t1 t2 k3), R (default I), P (default [K | 0])."""
        kk = np.asarray(k, float).reshape(3, 3)
        if p is None:
            p = np.concatenate([kk, np.zeros((3, 1))], axis=1)
        r = np.eye(3) if r is None else r
        self.write(topic, t, M.camera_info(self.store, t, frame_id, width, height, kk, d, r, p, distortion_model))

    @_timed
    def write_labels(self, topic: str, frame_id: str, t: float, boxes: Sequence[M.Box2D]) -> None:
        """2-D boxes as a ``vision_msgs/Detection2DArray`` (vision_msgs 4.x layout)."""
        self.write(topic, t, M.detection2d_array(self.store, t, frame_id, boxes))

    @_timed
    def write_compressed_image(
        self,
        topic: str,
        frame_id: str,
        t: float,
        pixels: np.ndarray,
        fmt: str = "jpeg",
        encoding: str = "bgr8",
        quality: int = JPEG_QUALITY,
    ) -> None:
        """A ``sensor_msgs/CompressedImage`` (JPEG or PNG via Pillow) from an H×W(×C) ``encoding`` array; its
        ``format`` as compressed_image_transport writes it (``bgr8; jpeg compressed bgr8``)."""
        from seatwin.recording.images import encode_image, transport_format

        payload = encode_image(pixels, fmt, encoding, quality)
        self.write(topic, t, M.compressed_image(self.store, t, frame_id, payload, transport_format(fmt, encoding)))

    @_timed
    def write_static_transforms(self, t: float, transforms: Sequence[M.StaticTransform] = ()) -> None:
        """Sensor mounts (and, the first time, ``world_ned`` below the ENU ``map`` frame) on /tf_static."""
        items = [(s.parent, s.child, s.translation, s.rotation) for s in transforms]
        if not self._static_written and self.topics.display_frame:
            items.insert(0, (self.topics.display_frame, self.topics.world_frame, (0.0, 0.0, 0.0), ENU_NED_ROTATION))
        if not items:
            return
        t0 = _time.perf_counter()
        data = self._gt.tf_message(t, items)
        self.timing["serialize_s"] += _time.perf_counter() - t0
        self._write_batch(t, ((self.topics.tf_static, TF_MESSAGE, data),))
        self._static_written = True

    @_timed
    def write_ground_truth(self, t: float, vessels: Sequence[M.VesselPose]) -> None:
        """Ground truth of every vessel at ``t``: PoseStamped + Odometry each (``world_ned``, FRD body), NavSatFix
        of the ownship (its ``gnss`` frame), one /tf of every FLU ``base_link`` in its ``odom`` (REP-105); a
        vessel's fixed frames go on /tf_static when it first appears (:func:`~seatwin.recording.tf_tree.vessel_transforms`).

        Serialised directly (:mod:`seatwin.recording.fast_cdr`, byte-identical to the typestore path)."""
        if not self._static_written:
            self.write_static_transforms(t)
        t0 = _time.perf_counter()
        entries, topics, new = [], [], []
        for v in vessels:
            fix = v.ownship and (v.llh is not None or self.origin is not None)
            slot = self._vessel_slots.get((v.name, fix))
            if slot is None:
                slot = self._vessel_slot(v, fix)
                new += vessel_transforms(self.topics, v.name, gnss=fix)
            entries.append((v, slot[0]))
            topics += slot[1]
        if new:  # a vessel's fixed frames (odom, base_link_frd, gnss) on /tf_static, before its first /tf
            self.write_static_transforms(t, new)
        if entries:
            topics.append((self.topics.tf, TF_MESSAGE))
        msgs = self._gt.step(t, self.topics.world_frame, entries, self.origin)
        self.timing["serialize_s"] += _time.perf_counter() - t0
        self._write_batch(t, [(topic, msgtype, data) for (topic, msgtype), data in zip(topics, msgs)])

    def _vessel_slot(self, v: M.VesselPose, fix: bool) -> tuple[VesselFrames, tuple[tuple[str, str], ...]]:
        """(frame ids, (topic, type) of its pose, odometry and, with ``fix``, NavSatFix) of a vessel seen
        for the first time (in this role); its role noted."""
        tp = self.topics
        self.vessels[v.name] = "ownship" if v.ownship else "target"
        if v.ownship and not fix and not any("NavSatFix" in n for n in self.notes):
            self.notes.append("no geodetic origin given: the ownship's NavSatFix was not recorded")
        kinds = [("pose", POSE_STAMPED), ("odom", ODOMETRY)] + ([("fix", NAV_SAT_FIX)] if fix else [])
        topics = tuple((tp.topic(kind, vessel=v.name), msgtype) for kind, msgtype in kinds)
        gnss = tp.frame("gnss_frame", v.name) if fix else None
        frames = (tp.body(v.name), gnss, tp.frame("odom_frame", v.name), tp.frame("base_frame", v.name))
        slot = self._vessel_slots[(v.name, fix)] = (frames, topics)
        return slot

    # ------------------------------------------------------------------ manifest and closing
    def _write_manifest(self, completed: bool = False) -> None:
        m = self._manifest
        m.update(
            completed=completed,
            error=self._error,
            start_time=self._t0,
            end_time=self._t1,
            vessels=dict(self.vessels),
            topics={k: {"type": self.types[k], "count": self.counts[k]} for k in sorted(self.counts)},
            message_count=sum(self.counts.values()),
            notes=list(self.notes),
            recording_time_s={k: round(v, 6) for k, v in self.timing.items()},
        )
        if completed or self._error:
            m["finished_utc"] = _utcnow()
        write_manifest(self.run_dir, m)

    @_timed
    def close(self, completed: bool = True, error: str | None = None) -> None:
        """Finish the bag (index, footer, metadata.yaml) and write the manifest; idempotent."""
        if self._closed:
            return
        self._closed = True
        if error:
            self._error = error
        try:
            self.storage.close()
        except OSError as exc:
            self._error = f"{type(exc).__name__}: {_strerror(exc)}"
            with contextlib.suppress(Exception):
                self.storage.abort()
            completed = False
        try:
            self._write_manifest(completed=completed and self._error is None)
        except OSError as exc:
            raise RecordingError(self.run_dir / MANIFEST_NAME, f"cannot write the manifest: {_strerror(exc)}") from exc
        if self._error and not error:
            raise RecordingError(self.bag, f"closing failed: {self._error}")

    @property
    def manifest(self) -> dict[str, Any]:
        return dict(self._manifest)

    def __enter__(self) -> RecordingWriter:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None) -> None:
        if exc is None:
            self.close()
        elif not self._closed:
            self.close(completed=False, error=f"{type(exc).__name__}: {exc}")


class _FrameBlock:
    """:meth:`RecordingWriter.frame`'s context manager (one per writer, re-entrant; a class: entered once a frame)."""

    __slots__ = ("begin", "end")

    def __init__(self, begin: Callable[[], None], end: Callable[[], None]) -> None:
        self.begin, self.end = begin, end

    def __enter__(self) -> None:
        self.begin()

    def __exit__(self, *exc: object) -> None:
        self.end()


def open_recording(run_dir: str | os.PathLike[str], fmt: str = "mcap", **kwargs: Any) -> RecordingWriter:
    """Start a recording in ``run_dir`` (see :class:`RecordingWriter` for the options)."""
    return RecordingWriter(run_dir, fmt, **kwargs)


ENU_NED_ROTATION = (0.7071067811865475, 0.7071067811865475, 0.0, 0.0)
"""The rotation of ``world_ned`` in the ENU ``map`` frame: ``quaternion_from_matrix(R_ENU_NED)`` (tested),
written out so that the first recorded step does not wait for scipy to load."""


def _strerror(exc: OSError) -> str:
    """An operating-system error as one line: ``No space left on device (errno 28)``."""
    return f"{exc.strerror} (errno {exc.errno})" if exc.strerror else str(exc)


def _utcnow() -> str:
    return dt.datetime.now(dt.UTC).isoformat(timespec="seconds")
