"""ROS 1 ``.bag`` (format 2.0): rosbags' ROS 1 writer, a large message written as a chunk of its own, lz4 chunks
in the frame layout ROS's ``roslz4`` reads.

rosbags copies every message into the open chunk's ``BytesIO`` and the chunk again on its way
to the file; for images (940 kB) and point clouds that costs milliseconds. Here a message of
``DIRECT_BYTES`` or more (uncompressed bags only) is written straight to the file as a one-message
chunk with its index record; the pending chunk is written first, so the file order stays the
write order. Smaller messages take rosbags' own path. A flush writes the open chunk.
"""

from __future__ import annotations

import os
from collections import defaultdict
from io import BytesIO

from rosbags.interfaces import Connection
from rosbags.rosbag1 import Writer
from rosbags.rosbag1.reader import RecordType
from rosbags.rosbag1.writer import MAXSIZE, Header, WriteChunk, WriterError, serialize_time, serialize_uint32

from seatwin.recording.storage.base import BagStorage


def roslz4_compress(data: bytes) -> bytes:
    """An LZ4 frame as ROS 1's ``roslz4`` writes it and, alone, reads it: independent blocks of at most 1 MB, a
    content checksum, no content size (frame descriptor ``0x64 0x60``). rosbags' default frame (linked blocks,
    content size, no checksum) is refused by ROS's ``rosbag`` ("malformed data to decompress")."""
    from lz4.frame import BLOCKSIZE_MAX1MB, compress

    return compress(data, 0, block_size=BLOCKSIZE_MAX1MB, block_linked=False, content_checksum=True, store_size=False)


class LeanRos1Writer(Writer):
    """rosbags' ROS 1 ``Writer`` with direct writes of large messages and lz4 chunks that ROS's own ``rosbag``
    reads (:func:`roslz4_compress`)."""

    DIRECT_BYTES: int | None = 64 * 1024

    def set_compression(self, fmt: Writer.CompressionFormat) -> None:
        super().set_compression(fmt)
        if self.compression_format == "lz4":
            self.compressor = roslz4_compress

    def write(self, connection: Connection, timestamp: int, data: bytes | memoryview) -> None:
        if self.DIRECT_BYTES is None or len(data) < self.DIRECT_BYTES or self.compression_format != "none":
            super().write(connection, timestamp, data)
            return
        if not self.bio:
            raise WriterError("Bag was not opened.")
        if connection not in self.connections:
            raise WriterError(f"There is no connection {connection!r}.")
        pending = self.chunks[-1]
        prefix = b""
        if any(pending.connections.values()):
            self.write_chunk(pending)
        elif pending.data.tell():  # connection records only: they open the new chunk
            prefix = pending.data.getvalue()
            pending.data.close()
            self.chunks.pop()
        hbuf = BytesIO()
        header = Header()
        header.set_uint32("conn", connection.id)
        header.set_time("time", timestamp)
        header.write(hbuf, RecordType.MSGDATA)
        head = prefix + hbuf.getvalue() + serialize_uint32(len(data))
        size = len(head) + len(data)

        chunk = WriteChunk(BytesIO(), self.bio.tell(), timestamp, timestamp, defaultdict(list))
        chunk.connections[connection.id].append((timestamp, len(prefix)))
        ch = Header()
        ch.set_string("compression", "none")
        ch.set_uint32("size", size)
        ch.write(self.bio, RecordType.CHUNK)
        self.bio.write(serialize_uint32(size) + head)
        self.bio.write(data)
        ih = Header()
        ih.set_uint32("ver", 1)
        ih.set_uint32("conn", connection.id)
        ih.set_uint32("count", 1)
        ih.write(self.bio, RecordType.IDXDATA)
        self.bio.write(serialize_uint32(12) + serialize_time(timestamp) + serialize_uint32(len(prefix)))
        chunk.data.close()
        self.chunks.append(chunk)
        self.chunks.append(WriteChunk(BytesIO(), -1, MAXSIZE, 0, defaultdict(list)))


class Ros1Storage(BagStorage):
    """A ROS 1 bag file (:class:`LeanRos1Writer`), chunks compressed with :attr:`compression` (lz4, bz2 or none);
    ``/tf_static`` and other latched topics get ``latching=1``."""

    format = "ros1"
    ros1 = True
    writer: LeanRos1Writer
    """rosbags' writer underneath (set by :meth:`open`)."""

    def open(self) -> None:
        self.writer = LeanRos1Writer(self.path)
        if self.compression != "none":  # rosbags' compressors: bz2 level 9, lz4 level 0 (as ``rosbag record``)
            self.writer.set_compression(Writer.CompressionFormat[self.compression.upper()])
        self.writer.open()

    def add_connection(self, topic: str, msgtype: str, *, latched: bool = False) -> Connection:
        return self.writer.add_connection(topic, msgtype, typestore=self.store, latching=1 if latched else None)

    def write(self, connection: Connection, timestamp: int, data: bytes | memoryview) -> None:
        self.writer.write(connection, timestamp, data)

    def flush(self) -> None:
        w = self.writer
        chunk = w.chunks[-1]
        if chunk.data.tell() > 0 and any(chunk.connections.values()):
            w.write_chunk(chunk)
        w.bio.flush()
        if self.fsync:
            os.fsync(w.bio.fileno())

    def close(self) -> None:
        self.writer.close()

    def abort(self) -> None:
        self.writer.abort()
