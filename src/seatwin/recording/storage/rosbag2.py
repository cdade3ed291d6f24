"""What MCAP and SQLite3 share: a rosbag2 directory with ``metadata.yaml``, in the metadata version of
the ROS 2 distribution it is written for (:data:`~seatwin.defaults.ROS_DISTROS`: Humble 5, Iron 7,
Jazzy and Kilted 9).

Each version has the fields rosbag2 added up to it (:data:`FIELDS_SINCE`); below 9 the offered QoS
profiles are a YAML *string* with numeric enums (what Humble and Iron parse), from 9 a YAML list with
names. In version 9 the connections, the metadata and the storage file are what rosbags'
``rosbag2.Writer`` writes (tested byte for byte, but for ``ros_distro``: rosbags writes ``rosbags``,
seatwin the distribution); the storage file itself is one of rosbags' storage plugins, and the YAML
texts come from :func:`~seatwin.recording.storage.metadata_yaml.dump_yaml`.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any, ClassVar

from rosbags.interfaces import (
    Connection,
    ConnectionExtRosbag2,
    MessageDefinition,
    MessageDefinitionFormat,
    Qos,
    QosDurability,
    QosHistory,
    QosLiveliness,
    QosReliability,
    QosTime,
)
from rosbags.rosbag2.enums import CompressionMode
from rosbags.rosbag2.metadata import dump_qos_v9
from rosbags.typesys.store import Typestore

from seatwin.defaults import DEFAULT_ROS_DISTRO, ROS_DISTROS
from seatwin.recording.storage.base import BagStorage
from seatwin.recording.storage.metadata_yaml import dump_yaml

FIELDS_SINCE = {"offered_qos_profiles": 4, "files": 5, "custom_data": 6, "type_description_hash": 7, "ros_distro": 8}
"""The metadata version that introduced each optional field (rosbag2's ``yaml.hpp`` decoders). seatwin writes
``ros_distro`` in every version (older readers ignore a key they do not know; it says which distro the bag is for)."""

_ZERO = QosTime(0, 0)
LATCHED_QOS = Qos(
    QosHistory.KEEP_LAST,
    1,
    QosReliability.RELIABLE,
    QosDurability.TRANSIENT_LOCAL,
    _ZERO,
    _ZERO,
    QosLiveliness.AUTOMATIC,
    _ZERO,
    False,
)
"""The QoS a latched topic (``/tf_static``) is offered with: keep last 1, reliable, transient local."""

_IDL_HEAD = "=" * 80 + "\nIDL: "


class Rosbag2Storage(BagStorage):
    """A rosbag2 directory: ``metadata.yaml`` beside one storage file written by :attr:`plugin`."""

    plugin: ClassVar[Any]
    """The rosbags storage writer class (``McapWriter``, ``Sqlite3Writer`` or a subclass); :attr:`writer` is the open one."""
    compression_format: str = ""
    """``metadata.yaml``'s ``compression_format``: ``zstd`` for rosbag2's own (file or message) compression, else empty."""
    compression_mode: str = ""
    """``metadata.yaml``'s ``compression_mode``: ``MESSAGE`` or ``FILE`` (as rosbag2 writes them), else empty."""

    def __init__(
        self,
        path: Path,
        store: Typestore,
        *,
        fsync: bool = False,
        ros_distro: str = DEFAULT_ROS_DISTRO,
        compression: str | None = None,
    ) -> None:
        super().__init__(path, store, fsync=fsync, ros_distro=ros_distro, compression=compression)
        self.version = ROS_DISTROS[self.ros_distro]
        """rosbag2 metadata version written."""
        self.connections: list[Connection] = []
        self.counts: dict[int, int] = {}
        self.min_timestamp = 2**63 - 1
        self.max_timestamp = 0
        self._definitions: dict[str, tuple[MessageDefinition, str]] = {}
        self.writer: Any = None

    def open(self) -> None:
        self.path.mkdir(mode=0o755, parents=True)  # FileExistsError: never overwrite a bag
        self.writer = self.plugin(self.path, CompressionMode.NONE)

    def _definition(self, msgtype: str) -> tuple[MessageDefinition, str]:
        """(message definition, RIHS01 hash) of ``msgtype``, generated once per type."""
        d = self._definitions.get(msgtype)
        if d is None:
            text, _ = self.store.generate_msgdef(msgtype, ros_version=2)
            fmt = MessageDefinitionFormat.IDL if text.startswith(_IDL_HEAD) else MessageDefinitionFormat.MSG
            d = self._definitions[msgtype] = (MessageDefinition(fmt, text), self.store.hash_rihs01(msgtype))
        return d

    def add_connection(self, topic: str, msgtype: str, *, latched: bool = False) -> Connection:
        new_type = msgtype not in self._definitions
        msgdef, digest = self._definition(msgtype)
        qos = [LATCHED_QOS] if latched else []
        conn = Connection(
            id=len(self.connections) + 1,
            topic=topic,
            msgtype=msgtype,
            msgdef=msgdef,
            digest=digest,
            msgcount=0,
            ext=ConnectionExtRosbag2(serialization_format="cdr", offered_qos_profiles=qos),
            owner=self,
        )
        if new_type:  # the schema, once per message type
            self.writer.add_msgtype(conn)
        self.writer.add_connection(conn, self._qos_text(qos))
        self.connections.append(conn)
        self.counts[conn.id] = 0
        return conn

    def _qos(self, qos: list[Qos]) -> str | list[Any]:
        """``offered_qos_profiles`` as this version's metadata has it: a YAML list (9), else a YAML string of the
        same maps with the enums as numbers (what rosbags' ``dump_qos_v8`` writes, without ruamel's cost)."""
        profiles = dump_qos_v9(qos)
        if self.version >= 9:
            return profiles
        for x, d in zip(qos, profiles):
            d.update(history=x.history.value, reliability=x.reliability.value, durability=x.durability.value)
            d.update(liveliness=x.liveliness.value)
        return dump_yaml(profiles).strip() if profiles else ""

    def _qos_text(self, qos: list[Qos]) -> str:
        """The QoS text a storage file keeps per topic (MCAP channel metadata, SQLite3 ``topics`` row)."""
        q = self._qos(qos)
        return q if isinstance(q, str) else dump_yaml(q).strip()

    def write(self, connection: Connection, timestamp: int, data: bytes | memoryview) -> None:
        self.write_many(((connection, data),), timestamp)

    def write_many(self, items: Sequence[tuple[Connection, bytes | memoryview]], timestamp: int) -> None:
        self._write_records(items, timestamp)
        counts = self.counts
        for connection, _ in items:
            counts[connection.id] += 1
        if timestamp < self.min_timestamp:
            self.min_timestamp = timestamp
        if timestamp > self.max_timestamp:
            self.max_timestamp = timestamp

    def _write_records(self, items: Sequence[tuple[Connection, bytes | memoryview]], timestamp: int) -> None:
        """Hand the messages to the storage plugin."""
        write = self.writer.write
        for connection, data in items:
            write(connection, timestamp, data)

    def metadata(self) -> dict[str, Any]:
        """``rosbag2_bagfile_information`` as rosbags' writer builds it."""
        name = self.writer.path.name
        duration = max(0, self.max_timestamp - self.min_timestamp)
        start = self.min_timestamp
        count = sum(self.counts.values())
        v = self.version
        topics = []
        for c in self.connections:
            meta = {"name": c.topic, "type": c.msgtype, "serialization_format": c.ext.serialization_format}  # type: ignore[union-attr]
            meta["offered_qos_profiles"] = self._qos(c.ext.offered_qos_profiles)  # type: ignore[union-attr]
            if v >= FIELDS_SINCE["type_description_hash"]:
                meta["type_description_hash"] = c.digest
            topics.append({"topic_metadata": meta, "message_count": self.counts[c.id]})
        info: dict[str, Any] = {
            "version": v,
            "storage_identifier": self.format,
            "relative_file_paths": [name],
            "duration": {"nanoseconds": duration},
            "starting_time": {"nanoseconds_since_epoch": start},
            "message_count": count,
            "topics_with_message_count": topics,
            "compression_format": self.compression_format,
            "compression_mode": self.compression_mode,
            "files": [
                {
                    "path": name,
                    "starting_time": {"nanoseconds_since_epoch": start},
                    "duration": {"nanoseconds": duration},
                    "message_count": count,
                }
            ],
            "ros_distro": self.ros_distro,
        }
        if v >= FIELDS_SINCE["custom_data"]:
            info["custom_data"] = None
        return info

    def close(self) -> None:
        info = self.metadata()
        self.writer.close(self.version, _dump_metadata(info).strip())
        self.writer = None
        self._finish_files()
        meta = self.path / "metadata.yaml"
        tmp = meta.with_suffix(".yaml.tmp")
        tmp.write_text(_dump_metadata({"rosbag2_bagfile_information": info}), "utf8")
        os.replace(tmp, meta)

    def _finish_files(self) -> None:
        """After the storage file is closed and before ``metadata.yaml`` is written (file compression)."""

    def abort(self) -> None:
        writer, self.writer = self.writer, None
        if writer is not None:
            writer.abort()


def _dump_metadata(doc: dict[str, Any]) -> str:
    """``doc`` as YAML; below version 9 each QoS *string* (several lines) goes in as a JSON string, which YAML
    reads as a double-quoted scalar — the rest through :func:`dump_yaml`, which hands a document with such a
    string whole to ruamel (~80 ms for a run's metadata)."""
    strings: list[str] = []

    def swap(node: Any) -> Any:
        if isinstance(node, dict):
            out = {}
            for k, v in node.items():
                if k == "offered_qos_profiles" and isinstance(v, str) and v:
                    strings.append(v)
                    v = f"qos_placeholder_{len(strings) - 1}"
                out[k] = swap(v)
            return out
        if isinstance(node, list):
            return [swap(x) for x in node]
        return node

    text = dump_yaml(swap(doc))
    for i in reversed(range(len(strings))):  # placeholder 1 before 10 would match a prefix of it
        text = text.replace(f"qos_placeholder_{i}", json.dumps(strings[i]))
    return text
