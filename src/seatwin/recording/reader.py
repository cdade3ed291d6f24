"""Read recordings: ours (a run directory) and real ones (ROS 1 ``.bag``, rosbag2 SQLite3 or MCAP).

:func:`open_bag` accepts a run directory (with ``manifest.json``), a rosbag2 directory, or a
``.mcap`` / ``.db3`` / ``.bag`` file, and gives typed iterators: point clouds of any field layout
as numpy structured arrays, images (bgr8, rgb8, mono8, CompressedImage), radar plots,
/tf_static, and ground truth from our odometry/pose topics. Bags cut short (SIGKILL, full disk)
are read up to their last complete chunk. Reading knows no scenarios: for a bag without truth
topics, :meth:`Recording.scenario_file` names the scenario file beside it and
:func:`seatwin.evaluation.truth.recording_truth` reads it.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError
from seatwin.recording import backends as B
from seatwin.recording.chunks import ReadOptions
from seatwin.recording.config import TopicConfig, ros_name
from seatwin.recording.images import decode_compressed, image_to_array
from seatwin.recording.manifest import read_manifest
from seatwin.recording.mcap_check import check_mcap
from seatwin.recording.messages import StaticTransform
from seatwin.recording.pointcloud import unpack
from seatwin.recording.ros1_check import check_ros1
from seatwin.recording.sqlite_check import ReadableDb, check_sqlite
from seatwin.recording.sqlite_zstd import InflatingBackend, StagedBag, bag_compression

POINTCLOUD2 = "sensor_msgs/msg/PointCloud2"
IMAGE = "sensor_msgs/msg/Image"
COMPRESSED_IMAGE = "sensor_msgs/msg/CompressedImage"
ODOMETRY = "nav_msgs/msg/Odometry"
POSE_STAMPED = "geometry_msgs/msg/PoseStamped"
TF = "tf2_msgs/msg/TFMessage"


def stamp_s(stamp: Any) -> float:
    """A ``builtin_interfaces/Time`` as float POSIX seconds."""
    return float(stamp.sec) + float(stamp.nanosec) * 1e-9


@dataclass
class Message:
    topic: str
    msgtype: str
    log_time_ns: int
    msg: Any


@dataclass
class PointCloud:
    """One PointCloud2: ``points`` is a flat structured array with the message's own field names."""

    topic: str
    stamp: float
    frame_id: str
    points: NDArray[Any]
    height: int
    width: int
    is_dense: bool
    log_time_ns: int

    def xyz(self) -> NDArray[np.float64]:
        """N×3 float64 of x, y, z (non-finite points dropped)."""
        p = np.stack([np.asarray(self.points[k], float) for k in ("x", "y", "z")], axis=1)
        return p[np.isfinite(p).all(axis=1)]


def camera_of_topic(topic: str) -> str:
    """``/camera/front/image_raw[/compressed]`` or ``/camera/front/labels`` → ``/camera/front``."""
    return topic.removesuffix("/compressed").rsplit("/", 1)[0]


@dataclass
class ImageFrame:
    """One image: ``pixels`` H×W×C uint8 in ``encoding`` order (bgr8, rgb8 or mono8)."""

    topic: str
    stamp: float
    frame_id: str
    pixels: NDArray[np.uint8]
    encoding: str
    compressed_format: str | None
    log_time_ns: int


@dataclass
class VesselTruth:
    """Ground truth of one vessel over time, world NED frame, SI units; heading clockwise from north."""

    name: str
    time: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    down: NDArray[np.float64]
    heading: NDArray[np.float64]
    v_north: NDArray[np.float64]
    v_east: NDArray[np.float64]
    yaw_rate: NDArray[np.float64]
    ownship: bool = False
    source: str = ""


def _what(exc: BaseException) -> str:
    """One line naming a bag library's error: its type and message (rosbags' ReaderError,
    TypesysError, mcap's errors, SQLite's CorruptError, struct.error, UnicodeDecodeError, and the
    AssertionError/AttributeError/KeyError the libraries raise on bytes they do not expect)."""
    text = " ".join(str(exc).split())
    if len(text) > 300:
        text = text[:300] + "…"
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _find_bag(path: Path) -> tuple[Path, str, Path | None]:
    """(bag path, format, run dir or None) for any accepted path."""
    if not path.exists():
        raise InputError(path, "no such file or directory")
    if path.is_file():
        if path.name.endswith(".db3.zstd") and (path.parent / "metadata.yaml").is_file():
            return _find_bag(path.parent)  # a file-compressed SQLite3 file: read through its rosbag2 folder
        fmt = {".bag": "ros1", ".mcap": "mcap", ".db3": "sqlite3"}.get(path.suffix)
        if fmt is None:
            raise InputError(path, "not a bag: expected a .bag, .mcap or .db3 file, a rosbag2 directory or a run directory")
        run = path.parent if (path.parent / "manifest.json").exists() else None
        if run is None and (path.parent.parent / "manifest.json").exists():
            run = path.parent.parent
        return path, fmt, run
    manifest = read_manifest(path)
    if manifest is not None:
        bag = path / str(manifest.get("bag", ""))
        if not manifest.get("bag") or not bag.exists():
            raise InputError(path / "manifest.json", f"the bag {manifest.get('bag')!r} it names is missing", where="bag")
        found, fmt, _ = _find_bag(bag)
        return found, fmt, path
    storage = sorted(path.glob("*.mcap")) + sorted(path.glob("*.db3"))
    if (path / "metadata.yaml").exists() or storage:
        parent = read_manifest(path.parent) if (path.parent / "manifest.json").exists() else None
        run = path.parent if parent is not None and parent.get("bag") == path.name else None
        return path, _rosbag2_dir_format(path), run
    bags = sorted(path.glob("*.bag"))
    if len(bags) == 1:
        return bags[0], "ros1", None
    subdirs = [
        d
        for d in sorted(path.iterdir())
        if d.is_dir() and ((d / "metadata.yaml").exists() or any(d.glob("*.mcap")) or any(d.glob("*.db3")))
    ]
    if len(subdirs) == 1:
        return subdirs[0], _rosbag2_dir_format(subdirs[0]), None
    raise InputError(path, "no bag found here (expected manifest.json, metadata.yaml, *.mcap, *.db3 or one *.bag)")


def _rosbag2_dir_format(path: Path) -> str:
    if any(path.glob("*.mcap")):
        return "mcap"
    if any(path.glob("*.db3")):
        return "sqlite3"
    meta = path / "metadata.yaml"
    text = meta.read_text(errors="replace") if meta.exists() else ""
    m = re.search(r"storage_identifier:\s*(\w+)", text)
    return m.group(1) if m else "unknown"


def _open_backend(bag: Path, fmt: str, options: ReadOptions, keep: list[ReadableDb | StagedBag]) -> tuple[B.Backend, int]:
    """The backend for ``bag`` and the number of chunks read despite a bad CRC (``options.ignore_crc``).
    Every storage file is checked first (MCAP structure, chunks and CRCs; ROS 1 chunks; SQLite3
    cells; rosbag2's zstd compression inflated within the budgets); a SQLite3 copy made to roll back a
    hot journal or a staged folder of a compressed rosbag2 (:mod:`~seatwin.recording.sqlite_zstd`) is
    appended to ``keep`` (closed with the recording)."""
    from rosbags.rosbag1 import ReaderError as Reader1Error
    from rosbags.rosbag2 import ReaderError as Reader2Error

    errors = (Reader1Error, Reader2Error, KeyError, ValueError, AssertionError)
    if fmt == "ros1":
        check_ros1(bag, options)  # before rosbags decompresses a chunk
        try:
            return B.RosbagsBackend(bag, "ros1"), 0
        except errors:
            return B.Ros1ScanBackend(bag, options), 0
    if fmt not in ("mcap", "sqlite3"):
        raise InputError(bag, f"unsupported rosbag2 storage {fmt!r}; expected mcap or sqlite3")
    compression = bag_compression(bag) if fmt == "sqlite3" and bag.is_dir() else "none"
    if compression == "file":  # inflated into a staged folder, within the budgets, before rosbags sees it
        staged = StagedBag(bag, "file", options)
        keep.append(staged)
        for db, source in staged.files:
            check_sqlite(db, source=source)
        try:
            return B.RosbagsBackend(staged.path, fmt), 0
        except errors as exc:
            raise InputError(bag, f"unreadable SQLite3 bag: {_what(exc)}") from None
    storage = [bag] if bag.is_file() else sorted(bag.glob("*.mcap" if fmt == "mcap" else "*.db3"))
    bad_crc = 0
    journaled = False
    dbs: list[ReadableDb] = []
    if fmt == "mcap":
        for f in storage:
            bad_crc += check_mcap(f, options).bad_crc  # before any MCAP reader trusts a length field (issue #14)
    else:
        for f in storage:
            db = ReadableDb(f)  # never written: a hot journal is rolled back in a copy
            keep.append(db)
            dbs.append(db)
            journaled = journaled or db.copied
            check_sqlite(db.path, source=f)
    if bad_crc:  # rosbags refuses a chunk whose CRC differs; mcap's stream reader reads it
        if len(storage) > 1:
            raise InputError(bag, f"{bad_crc} chunks with a bad CRC in a split rosbag2 cannot be read")
        return B.McapScanBackend(storage[0], options), bad_crc
    if bag.is_dir() and (bag / "metadata.yaml").exists() and not journaled:
        try:
            if compression == "message":  # rosbags reads the frames from a staged folder; they are inflated here
                staged = StagedBag(bag, "message", options, {db.original.name: db.path for db in dbs})
                keep.append(staged)
                return InflatingBackend(B.RosbagsBackend(staged.path, fmt), bag, options), 0
            return B.RosbagsBackend(bag, fmt), 0
        except errors:
            pass
    if not storage:
        raise InputError(bag, f"rosbag2 directory without {fmt} storage files")
    if len(storage) > 1:
        raise InputError(bag, "a split rosbag2 without metadata.yaml cannot be recovered (several storage files)")
    try:
        backend: B.Backend = B.RosbagsBackend(dbs[0].path if dbs else storage[0], fmt)
        backend.recovered = bag.is_dir() or journaled
    except errors as exc:
        if fmt == "mcap":
            return B.McapScanBackend(storage[0], options), 0
        raise InputError(storage[0], f"unreadable SQLite3 bag: {_what(exc)}") from None
    if fmt == "sqlite3":  # messages a killed run compressed (no metadata.yaml says so): zstd frames inflated
        backend = InflatingBackend(backend, storage[0], options, strict=compression == "message")
    return backend, 0


class Recording:
    """A bag opened for reading (see the module docstring). Use as a context manager or call :meth:`close`.

    ``options``: decompression budgets and ``ignore_crc`` (:class:`~seatwin.recording.chunks.ReadOptions`);
    ``bad_crc``: CRC mismatches read anyway (only with ``ignore_crc``)."""

    def __init__(self, path: str | os.PathLike[str], options: ReadOptions | None = None) -> None:
        self.path = Path(path)
        self.options = options or ReadOptions.from_env()
        self.bag, self.format, self.run_dir = _find_bag(self.path)
        self.manifest = read_manifest(self.run_dir) if self.run_dir else None
        self._dbs: list[ReadableDb | StagedBag] = []
        try:
            self._b, self.bad_crc = _open_backend(self.bag, self.format, self.options, self._dbs)
        except InputError:
            self._close_dbs()
            raise
        except Exception as exc:  # noqa: BLE001 - any reader failure becomes one clear line
            self._close_dbs()
            raise InputError(self.bag, f"cannot read bag: {_what(exc)}") from None
        try:
            self.store = B.build_typestore(self._b.topics, self._b.ros1)
        except Exception as exc:  # noqa: BLE001 - rosbags' type system: a corrupt message definition
            self.close()
            raise InputError(self.bag, f"corrupt message definition: {_what(exc)}") from None
        self._deser = self.store.deserialize_ros1 if self._b.ros1 else self.store.deserialize_cdr
        cfg = (self.manifest or {}).get("topic_config")
        try:
            self.topic_config = TopicConfig.from_dict(cfg, source=str(self.run_dir)) if cfg else TopicConfig()
        except InputError:
            self.topic_config = TopicConfig()

    # ---------------------------------------------------------------- metadata
    @property
    def topics(self) -> dict[str, B.TopicInfo]:
        return self._b.topics

    @property
    def recovered(self) -> bool:
        """True when the bag was never finished and was read by a recovery scanner."""
        return self._b.recovered

    @property
    def truncated(self) -> bool:
        return self._b.truncated

    @property
    def complete(self) -> bool | None:
        """From our manifest: True/False; a bag with a run directory but no manifest is False; a foreign bag None."""
        if self.manifest is not None:
            return bool(self.manifest.get("completed")) and not self.recovered
        if self.run_dir is not None or self.recovered:
            return False
        return None

    @property
    def start_ns(self) -> int | None:
        return self._b.start_ns

    @property
    def end_ns(self) -> int | None:
        return self._b.end_ns

    @property
    def duration_s(self) -> float:
        if self.start_ns is None or self.end_ns is None:
            return 0.0
        return (self.end_ns - self.start_ns) * 1e-9

    def topics_of_type(self, msgtype: str) -> list[str]:
        return sorted(t for t, i in self.topics.items() if i.msgtype == msgtype)

    # ---------------------------------------------------------------- messages
    def messages(self, topics: list[str] | str | None = None) -> Iterator[Message]:
        """Deserialised messages (time order for indexed bags, file order for recovered ones)."""
        want = {topics} if isinstance(topics, str) else (set(topics) if topics is not None else None)
        if want is not None:
            unknown = sorted(want - set(self.topics))
            if unknown:
                raise InputError(self.bag, f"no topic(s) {unknown}; the bag has {sorted(self.topics)}")
        for topic, msgtype, ts, data in self.raw_messages(want):
            try:
                msg = self._deser(data, msgtype)
            except Exception as exc:  # noqa: BLE001 - any decoding failure of bag bytes is bad input
                raise InputError(self.bag, f"cannot decode a {msgtype} message at {ts} ns: {_what(exc)}", where=topic) from None
            yield Message(topic, msgtype, ts, msg)

    def raw_messages(self, topics: set[str] | None = None) -> Iterator[B.RawMessage]:
        """Serialised messages as (topic, msgtype, log time ns, bytes), in the order of :meth:`messages`,
        not decoded: for byte-level comparisons and fast scans (``topics``: all when None)."""
        it = self._b.messages(topics)
        while True:
            try:
                item = next(it)
            except StopIteration:
                return
            except InputError:
                raise
            except Exception as exc:  # noqa: BLE001 - the one boundary to rosbags/mcap/SQLite: see _what
                raise InputError(self.bag, f"cannot read bag: {_what(exc)}") from None
            yield item

    def _typed(self, topic: str | list[str] | None, msgtypes: tuple[str, ...]) -> list[str]:
        if topic is None:
            return sorted(t for t, i in self.topics.items() if i.msgtype in msgtypes)
        names = [topic] if isinstance(topic, str) else list(topic)
        for name in names:
            info = self.topics.get(name)
            if info is None:
                raise InputError(self.bag, f"no topic {name!r}; the bag has {sorted(self.topics)}")
            if info.msgtype not in msgtypes:
                raise InputError(self.bag, f"topic {name!r} is {info.msgtype}, expected {' or '.join(msgtypes)}")
        return names

    def point_clouds(self, topic: str | list[str] | None = None) -> Iterator[PointCloud]:
        """PointCloud2 messages (all PointCloud2 topics by default) with any field layout."""
        names = self._typed(topic, (POINTCLOUD2,))
        if not names:
            return
        for m in self.messages(names):
            c = m.msg
            with self._standard_fields(m):
                try:
                    pts = unpack(
                        c.data, c.fields, int(c.point_step), int(c.width), int(c.height), int(c.row_step), bool(c.is_bigendian)
                    )
                except InputError as exc:
                    raise InputError(self.bag, f"{exc.detail} (message at {m.log_time_ns} ns)", where=m.topic) from None
                cloud = PointCloud(
                    m.topic,
                    stamp_s(c.header.stamp),
                    c.header.frame_id,
                    pts,
                    int(c.height),
                    int(c.width),
                    bool(c.is_dense),
                    m.log_time_ns,
                )
            yield cloud

    @contextlib.contextmanager
    def _standard_fields(self, m: Message) -> Iterator[None]:
        """Turn a missing field of a decoded message into an :class:`InputError`: a bag whose own
        message definition of a standard type (PointCloud2, Odometry, …) differs from the standard."""
        try:
            yield
        except (AttributeError, TypeError) as exc:
            raise InputError(
                self.bag,
                f"a {m.msgtype} message at {m.log_time_ns} ns lacks the standard fields ({_what(exc)}); "
                "the bag's own definition of the type differs",
                where=m.topic,
            ) from None

    def radar_topics(self) -> list[str]:
        """PointCloud2 topics that look like radar plots (our radar template, or range+bearing fields)."""
        tmpl = self.topic_config.radar
        head, _, tail = tmpl.partition("{sensor}")
        rx = re.compile(re.escape(head) + ".+" + re.escape(tail) + "$")
        ours = [t for t in self.topics_of_type(POINTCLOUD2) if rx.match(t)]
        return ours or [t for t in self.topics_of_type(POINTCLOUD2) if "radar" in t.lower()]

    def radar_scans(self, topic: str | list[str] | None = None) -> Iterator[PointCloud]:
        """Radar plot scans (PointCloud2 with x, y, z, intensity, range, bearing, time)."""
        names = self.radar_topics() if topic is None else topic
        if not names:
            return
        yield from self.point_clouds(names)

    def images(self, topic: str | list[str] | None = None) -> Iterator[ImageFrame]:
        """Image and CompressedImage messages decoded to arrays (compressed colour → bgr8)."""
        names = self._typed(topic, (IMAGE, COMPRESSED_IMAGE))
        if not names:
            return
        for m in self.messages(names):
            yield self.decode_image(m)

    def decode_image(self, m: Message) -> ImageFrame:
        """The pixels of an Image or CompressedImage message ``m`` (from :meth:`messages`); a bad one is one
        :class:`InputError` naming the bag, the topic and the message's log time."""
        with self._standard_fields(m):
            try:
                if m.msgtype == IMAGE:
                    px, enc, cf = image_to_array(m.msg), str(m.msg.encoding), None
                elif m.msgtype == COMPRESSED_IMAGE:
                    (px, enc), cf = decode_compressed(m.msg), str(m.msg.format)
                else:
                    raise InputError(None, f"a {m.msgtype} message is not an image")
            except InputError as exc:
                raise InputError(self.bag, f"{exc.detail} (message at {m.log_time_ns} ns)", where=m.topic) from None
            return ImageFrame(m.topic, stamp_s(m.msg.header.stamp), m.msg.header.frame_id, px, enc, cf, m.log_time_ns)

    def camera_image_topics(self) -> list[str]:
        """One image topic per camera: its ``sensor_msgs/Image`` topic, else its ``CompressedImage`` one
        (``/camera/front/image_raw`` and ``…/image_raw/compressed`` are the same camera)."""
        raw = self.topics_of_type(IMAGE)
        cameras = {camera_of_topic(t) for t in raw}
        return sorted(raw + [t for t in self.topics_of_type(COMPRESSED_IMAGE) if camera_of_topic(t) not in cameras])

    def static_transforms(self) -> list[StaticTransform]:
        """All transforms on /tf_static (the sensor mounts and the display frame)."""
        topic = self.topic_config.tf_static
        if topic not in self.topics:
            return []
        out = []
        for m in self.messages(topic):
            with self._standard_fields(m):
                for tr in m.msg.transforms:
                    tt, q = tr.transform.translation, tr.transform.rotation
                    out.append(StaticTransform(tr.header.frame_id, tr.child_frame_id, (tt.x, tt.y, tt.z), (q.x, q.y, q.z, q.w)))
        return out

    # ---------------------------------------------------------------- ground truth
    def scenario_file(self) -> Path | None:
        """The scenario file beside the bag (named in the manifest, else ``scenario.*`` or a single
        ``*.csv``), or None. Only located here; :mod:`seatwin.evaluation.truth` reads it."""
        folder = self.run_dir or (self.bag.parent if self.bag.is_file() else self.bag.parent)
        if self.manifest and self.manifest.get("scenario"):
            p = folder / str(self.manifest["scenario"])
            if p.is_file():
                return p
        cands = sorted(folder.glob("scenario.*")) or sorted(folder.glob("*.csv"))
        return cands[0] if len(cands) == 1 else None

    def ground_truth(self) -> dict[str, VesselTruth]:
        """Ground truth per vessel from our odometry topics (pose topics, velocities differentiated, as a
        fallback); empty when the bag has neither. The ownship: the manifest's role, or a NavSatFix topic."""
        cfg = self.topic_config
        roles = (self.manifest or {}).get("vessels", {})
        fix_vessels = {cfg.vessel_from_topic("fix", t) for t in self.topics}
        out: dict[str, VesselTruth] = {}
        for kind, msgtype in (("odom", ODOMETRY), ("pose", POSE_STAMPED)):
            for topic in self.topics_of_type(msgtype):
                name = cfg.vessel_from_topic(kind, topic)
                name = next((v for v in roles if ros_name(v) == name), name)
                if name is None or name in out:
                    continue
                rows = []
                for m in self.messages(topic):
                    with self._standard_fields(m):
                        msg = m.msg
                        pose = msg.pose.pose if kind == "odom" else msg.pose
                        p, q = pose.position, pose.orientation
                        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
                        if kind == "odom":
                            lin, ang = msg.twist.twist.linear, msg.twist.twist.angular
                            c, s = math.cos(yaw), math.sin(yaw)
                            rows.append(
                                (
                                    stamp_s(msg.header.stamp),
                                    p.x,
                                    p.y,
                                    p.z,
                                    yaw,
                                    c * lin.x - s * lin.y,
                                    s * lin.x + c * lin.y,
                                    ang.z,
                                )
                            )
                        else:
                            rows.append((stamp_s(msg.header.stamp), p.x, p.y, p.z, yaw, np.nan, np.nan, np.nan))
                if not rows:
                    continue
                a = np.array(sorted(rows))
                if kind == "pose" and len(a) > 1:
                    a[:, 5] = np.gradient(a[:, 1], a[:, 0])
                    a[:, 6] = np.gradient(a[:, 2], a[:, 0])
                    a[:, 7] = np.gradient(np.unwrap(a[:, 4]), a[:, 0])
                out[name] = VesselTruth(
                    name,
                    *(a[:, i].copy() for i in range(8)),
                    ownship=roles.get(name) == "ownship" or name in fix_vessels,
                    source=f"{self.bag} {topic}",
                )
        return out

    def close(self) -> None:
        self._b.close()
        self._close_dbs()

    def _close_dbs(self) -> None:
        for db in self._dbs:
            db.close()
        self._dbs.clear()

    def __enter__(self) -> Recording:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def open_bag(path: str | os.PathLike[str], options: ReadOptions | None = None) -> Recording:
    """Open any recording for reading (run dir, rosbag2 dir, .mcap, .db3, .bag); ``options``: the
    decompression budgets and ``ignore_crc`` (default :meth:`ReadOptions.from_env`)."""
    return Recording(path, options)
