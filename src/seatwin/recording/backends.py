"""Raw bag access for all three formats, with recovery of bags cut short (SIGKILL, full disk).

A backend lists the topics (type, count, message definition) and yields raw messages
``(topic, msgtype, log_time_ns, data)``. Intact bags go through rosbags' indexed readers (time
order); when those refuse a bag, the recovery scanners read it front to back (file order) up to
the last complete chunk:

* MCAP without summary/footer → ``mcap``'s non-seeking :class:`~mcap.stream_reader.StreamReader`;
* rosbag2 without ``metadata.yaml`` → the storage file itself (a SQLite3 file with a hot journal
  of an interrupted transaction is read from a rolled-back copy: :mod:`~seatwin.recording.sqlite_check`);
* ROS 1 bag without index (``index_pos = 0``) → a chunk scanner here.
"""

from __future__ import annotations

import contextlib
import mmap
import struct
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosbags.interfaces import MessageDefinitionFormat
from rosbags.typesys import Stores, get_types_from_idl, get_types_from_msg, get_typestore
from rosbags.typesys.msg import normalize_msgtype
from rosbags.typesys.store import Typestore

from seatwin.errors import InputError
from seatwin.recording.chunks import ReadOptions
from seatwin.recording.ros1_check import OP_CHUNK, OP_CONN, OP_MSG, fields, inflate_chunk, records

RawMessage = tuple[str, str, int, bytes]


@dataclass
class TopicInfo:
    topic: str
    msgtype: str
    count: int = 0
    msgdef: str = ""
    msgdef_format: str = "msg"
    """``msg``, ``idl`` or ``""`` (no definition in the bag)."""


@dataclass
class Backend:
    """Common state; subclasses fill ``topics`` and implement :meth:`messages`."""

    path: Path
    format: str
    ros1: bool = False
    recovered: bool = False
    """Read by a recovery scanner (the bag was not finished)."""
    truncated: bool = False
    """The scan stopped at a damaged or cut-off record."""
    topics: dict[str, TopicInfo] = field(default_factory=dict)
    start_ns: int | None = None
    end_ns: int | None = None

    def messages(self, topics: set[str] | None = None) -> Iterator[RawMessage]:  # pragma: no cover - abstract
        raise NotImplementedError

    def close(self) -> None:
        pass

    def _count(self, topic: str, ts: int) -> None:
        self.topics[topic].count += 1
        self.start_ns = ts if self.start_ns is None else min(self.start_ns, ts)
        self.end_ns = ts if self.end_ns is None else max(self.end_ns, ts)


def build_typestore(topics: dict[str, TopicInfo], ros1: bool) -> Typestore:
    """A typestore from the bag's own message definitions; the default store for types without one."""
    store = get_typestore(Stores.ROS1_NOETIC if ros1 else Stores.ROS2_HUMBLE)
    typs: dict[str, Any] = {}
    for info in topics.values():
        if not info.msgdef:
            continue
        if info.msgdef_format == "idl":
            sep = "=" * 80 + "\n"
            parts = info.msgdef.split(sep)[1:] if info.msgdef.startswith(sep + "IDL: ") else [info.msgdef]
            for part in parts:
                typs.update(get_types_from_idl(part.split("\n", 1)[1] if part.startswith("IDL: ") else part))
        else:
            typs.update(get_types_from_msg(info.msgdef, info.msgtype))
    if typs:
        own = get_typestore(Stores.EMPTY)
        own.register(typs)
        missing = {k: v for k, v in store.fielddefs.items() if k not in own.fielddefs}
        own.register(missing)
        return own
    return store


# ----------------------------------------------------------------------------- rosbags (indexed)
class RosbagsBackend(Backend):
    """An intact bag through rosbags' ``rosbag1.Reader`` / ``rosbag2.Reader`` (time order)."""

    def __init__(self, path: Path, fmt: str) -> None:
        super().__init__(path=path, format=fmt, ros1=fmt == "ros1")
        if self.ros1:
            from rosbags.rosbag1 import Reader
        else:
            from rosbags.rosbag2 import Reader
        self._reader = Reader(path)
        self._reader.open()
        r = self._reader
        for conn in r.connections:
            fmt_ = {MessageDefinitionFormat.MSG: "msg", MessageDefinitionFormat.IDL: "idl"}.get(conn.msgdef.format, "")
            info = self.topics.setdefault(
                conn.topic, TopicInfo(conn.topic, conn.msgtype, 0, conn.msgdef.data if fmt_ else "", fmt_)
            )
            info.count += max(conn.msgcount, 0)
        if r.message_count:
            self.start_ns, self.end_ns = r.start_time, r.end_time - 1

    def messages(self, topics: set[str] | None = None) -> Iterator[RawMessage]:
        conns = [c for c in self._reader.connections if topics is None or c.topic in topics]
        if not conns:
            return
        for conn, ts, data in self._reader.messages(connections=conns):
            yield conn.topic, conn.msgtype, ts, data

    def close(self) -> None:
        self._reader.close()


# ----------------------------------------------------------------------------- MCAP recovery
class McapScanBackend(Backend):
    """An MCAP file without footer/summary (or one rosbags refuses), read record by record up to the
    last complete one. ``ros1``-encoded channels are decoded as ROS 1 messages."""

    def __init__(self, path: Path, options: ReadOptions | None = None) -> None:
        from seatwin.recording.mcap_check import check_mcap

        super().__init__(path=path, format="mcap", recovered=True)
        self._layout = check_mcap(path, options)  # every record it lets through fits in the file (issue #14)
        # a finished file rosbags refused (e.g. another profile): read it in full, not "recovered"
        self.recovered = not self._layout.finished
        for topic, _, ts, _ in self._scan(None, want_data=False):
            self._count(topic, ts)

    def _scan(self, topics: set[str] | None, want_data: bool = True) -> Iterator[RawMessage]:
        import mcap.exceptions
        from mcap.records import Channel, Message, Schema
        from mcap.stream_reader import StreamReader

        schemas: dict[int, Any] = {}
        channels: dict[int, tuple[str, str]] = {}
        with self.path.open("rb") as f:
            if f.read(8) != b"\x89MCAP0\r\n":
                raise InputError(self.path, "not an MCAP file (bad magic bytes)")
            f.seek(0)
            end = self._layout.readable_end  # the scan never reads past the last complete record
            stream = _Bounded(f, end)
            records = StreamReader(stream, record_size_limit=end).records  # type: ignore[arg-type]
            while True:
                try:
                    rec = next(records)
                except StopIteration:
                    self.truncated = self.truncated or self._layout.truncated
                    return
                except (mcap.exceptions.McapError, struct.error, EOFError, ValueError, MemoryError, OSError):
                    self.truncated = True
                    return
                if isinstance(rec, Schema):
                    schemas[rec.id] = rec
                elif isinstance(rec, Channel):
                    schema = schemas.get(rec.schema_id)
                    msgtype = schema.name if schema else "__schemaless__"
                    if schema is not None and schema.encoding == "ros1msg":
                        msgtype = normalize_msgtype(msgtype)
                    channels[rec.id] = (rec.topic, msgtype)
                    if rec.message_encoding == "ros1":
                        self.ros1 = True
                    if rec.topic not in self.topics:
                        enc = schema.encoding if schema else ""
                        self.topics[rec.topic] = TopicInfo(
                            rec.topic,
                            msgtype,
                            0,
                            schema.data.decode() if schema else "",
                            {"ros2msg": "msg", "ros1msg": "msg", "ros2idl": "idl"}.get(enc, ""),
                        )
                elif isinstance(rec, Message):
                    ch = channels.get(rec.channel_id)
                    if ch is None or (topics is not None and ch[0] not in topics):
                        continue
                    yield ch[0], ch[1], rec.log_time, rec.data if want_data else b""

    def messages(self, topics: set[str] | None = None) -> Iterator[RawMessage]:
        yield from self._scan(topics)


class _Bounded:
    """A read-only view of a file's first ``end`` bytes (reads past it return ``b""``)."""

    def __init__(self, f: Any, end: int) -> None:
        self.f, self.end = f, end

    def read(self, n: int = -1) -> bytes:
        left = max(self.end - self.f.tell(), 0)
        return self.f.read(left if n is None or n < 0 else min(n, left))


# ----------------------------------------------------------------------------- ROS 1 recovery
class Ros1ScanBackend(Backend):
    """A ROS 1 bag whose index was never written: its chunks are scanned in file order."""

    def __init__(self, path: Path, options: ReadOptions | None = None) -> None:
        super().__init__(path=path, format="ros1", ros1=True, recovered=True)
        self._options = options or ReadOptions.from_env()
        with path.open("rb") as f:
            try:
                self._data: bytes | mmap.mmap = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
            except ValueError:  # empty file
                self._data = b""
        for topic, _, ts, _ in self._scan(None):
            self._count(topic, ts)

    def _scan(self, topics: set[str] | None) -> Iterator[RawMessage]:
        data = self._data
        if data[:13] != b"#ROSBAG V2.0\n":
            raise InputError(self.path, "not a ROS 1 bag (expected '#ROSBAG V2.0' at the start)")
        start = data.find(b"\n") + 1
        conns: dict[int, tuple[str, str]] = {}
        end = start
        pos = start
        for hdr, body, end in records(data, start):  # noqa: B007 - the last record's end is checked below
            op = hdr.get("op", b"\x00")[0]
            at, pos = pos, end
            if op != OP_CHUNK:
                if op == OP_CONN:
                    self._connection(hdr, body, conns)
                continue
            inner = b"".join(inflate_chunk(self.path, at, hdr, body, self._options))
            ipos = 0
            for ihdr, ibody, iend in records(inner):
                if len(ihdr.get("op", b"")) != 1:  # e.g. zeros: stop at once, not after millions of empty records
                    raise InputError(self.path, f"corrupt ROS 1 bag: chunk at byte {at}: a record without op at offset {ipos}")
                iop, ipos = ihdr["op"][0], iend
                if iop == OP_CONN:
                    self._connection(ihdr, ibody, conns)
                elif iop == OP_MSG:
                    (cid,) = struct.unpack("<I", ihdr["conn"])
                    sec, nsec = struct.unpack("<II", ihdr["time"])
                    topic, msgtype = conns[cid]
                    if topics is None or topic in topics:
                        yield topic, msgtype, sec * 1_000_000_000 + nsec, bytes(ibody)
        if end < len(data):
            self.truncated = True

    def close(self) -> None:
        if isinstance(self._data, mmap.mmap):
            with contextlib.suppress(BufferError):  # an unfinished generator still holds a view; the GC closes it
                self._data.close()

    def _connection(self, hdr: dict[str, bytes], body: memoryview, conns: dict[int, tuple[str, str]]) -> None:
        (cid,) = struct.unpack("<I", hdr["conn"])
        info = fields(bytes(body))
        topic = hdr.get("topic", info.get("topic", b"")).decode()
        msgtype = normalize_msgtype(info.get("type", b"").decode())
        conns[cid] = (topic, msgtype)
        self.topics.setdefault(topic, TopicInfo(topic, msgtype, 0, info.get("message_definition", b"").decode(), "msg"))

    def messages(self, topics: set[str] | None = None) -> Iterator[RawMessage]:
        yield from self._scan(topics)
