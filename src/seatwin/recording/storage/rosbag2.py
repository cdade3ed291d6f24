"""What MCAP and SQLite3 share: a rosbag2 directory (version 9) with ``metadata.yaml``.

Connections, the metadata and the storage file are the same as rosbags' ``rosbag2.Writer``
writes (tested byte for byte); the storage file itself is one of rosbags' storage plugins, and
the YAML texts come from :func:`~seatwin.recording.storage.metadata_yaml.dump_yaml`.
"""

from __future__ import annotations

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

from seatwin.recording.storage.base import BagStorage
from seatwin.recording.storage.metadata_yaml import dump_yaml

VERSION = 9
"""rosbag2 bag format version written."""

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

    def __init__(self, path: Path, store: Typestore, *, fsync: bool = False) -> None:
        super().__init__(path, store, fsync=fsync)
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
        self.writer.add_connection(conn, dump_yaml(dump_qos_v9(qos)).strip())
        self.connections.append(conn)
        self.counts[conn.id] = 0
        return conn

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
        return {
            "version": VERSION,
            "storage_identifier": self.format,
            "relative_file_paths": [name],
            "duration": {"nanoseconds": duration},
            "starting_time": {"nanoseconds_since_epoch": start},
            "message_count": count,
            "topics_with_message_count": [
                {
                    "topic_metadata": {
                        "name": c.topic,
                        "type": c.msgtype,
                        "serialization_format": c.ext.serialization_format,  # type: ignore[union-attr]
                        "offered_qos_profiles": dump_qos_v9(c.ext.offered_qos_profiles),  # type: ignore[union-attr]
                        "type_description_hash": c.digest,
                    },
                    "message_count": self.counts[c.id],
                }
                for c in self.connections
            ],
            "compression_format": "",
            "compression_mode": "",
            "files": [
                {
                    "path": name,
                    "starting_time": {"nanoseconds_since_epoch": start},
                    "duration": {"nanoseconds": duration},
                    "message_count": count,
                }
            ],
            "custom_data": None,
            "ros_distro": "rosbags",
        }

    def close(self) -> None:
        info = self.metadata()
        self.writer.close(VERSION, dump_yaml(info).strip())
        self.writer = None
        meta = self.path / "metadata.yaml"
        tmp = meta.with_suffix(".yaml.tmp")
        tmp.write_text(dump_yaml({"rosbag2_bagfile_information": info}), "utf8")
        os.replace(tmp, meta)

    def abort(self) -> None:
        writer, self.writer = self.writer, None
        if writer is not None:
            writer.abort()
