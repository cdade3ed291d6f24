"""MCAP (rosbag2 storage ``mcap``): rosbags' MCAP storage writer with fewer copies.

rosbags builds every message record in its own ``BytesIO`` and copies each closed chunk twice
more before it reaches the file; for 138 kB point clouds those copies and the per-record Python
overhead are a measurable part of the recording cost. :class:`LeanMcapWriter` writes message
records straight into the chunk buffer and the chunk buffer straight into the file. Small
records give the same bytes as rosbags' (``tests/recording/test_storage.py``); a message of
``DIRECT_BYTES`` or more goes to the file as a chunk of its own.

Every closed chunk is flushed to the operating system at once; a flush closes the open chunk
(rosbags also closes one at 1 MiB).

CRCs (rosbags writes 0, "not written"): every chunk carries the CRC-32 of its records, and the
Data End record the CRC-32 of every byte before it (:class:`_CrcFile` keeps it while writing), so
a reader can tell a damaged bag (``seatwin.recording.mcap_check``).

Chunk compression (``chunk_compression``: ``lz4``, the default of seatwin's bags, ``zstd`` or ``none``):
each chunk's records are compressed as one frame (:class:`~seatwin.recording.storage.compression.ChunkCompressor`)
— a large message's chunk from its head and data without joining them; the CRC is that of the
uncompressed records, as the MCAP specification defines it. rosbag2's metadata says nothing of it
(``compression_mode`` is for rosbag2's own file/message compression): MCAP readers see it per chunk.
"""

from __future__ import annotations

import os
import struct
import zlib
from collections import defaultdict
from collections.abc import Sequence
from io import BytesIO
from itertools import chain
from pathlib import Path
from typing import Any

from rosbags.interfaces import Connection
from rosbags.rosbag2.enums import CompressionMode
from rosbags.rosbag2.storage_mcap import McapWriter, PendingChunk

from seatwin.recording.storage.compression import ChunkCompressor
from seatwin.recording.storage.rosbag2 import Rosbag2Storage

CHUNK_BYTES = 1 << 20
"""Close a chunk once it holds more than this (rosbags' own threshold)."""

_MSG_HEAD = struct.Struct("<BQHIQQ")  # op 0x05, record length, channel, sequence, log time, publish time
_U16, _U32, _U64 = struct.Struct("<H"), struct.Struct("<I"), struct.Struct("<Q")


class _CrcFile:
    """The MCAP file, keeping the CRC-32 of everything written; it puts that CRC into the Data End
    record that rosbags' ``close`` writes (``0x0F``, length 4, four zero bytes) once :attr:`closing` is set."""

    def __init__(self, raw: Any, crc: int) -> None:
        self.raw, self.crc = raw, crc
        self.closing = False
        self._state = 0  # 1: Data End opcode seen, 2: its length seen, 3: done
        self._data_crc = 0

    def write(self, data: bytes | memoryview) -> int:
        if self.closing and self._state < 3:
            data = self._data_end(data)
        self.crc = zlib.crc32(data, self.crc)
        return self.raw.write(data)

    def _data_end(self, data: bytes | memoryview) -> bytes | memoryview:
        if self._state == 0 and bytes(data) == b"\x0f":
            self._data_crc, self._state = self.crc, 1
        elif self._state == 1:
            self._state = 2 if bytes(data) == _U64.pack(4) else 0
        elif self._state == 2:
            self._state = 3
            if bytes(data) == bytes(4):
                return _U32.pack(self._data_crc)
        return data

    def tell(self) -> int:
        return self.raw.tell()

    def flush(self) -> None:
        self.raw.flush()

    def fileno(self) -> int:
        return self.raw.fileno()

    def close(self) -> None:
        self.raw.close()


class LeanMcapWriter(McapWriter):
    """rosbags' MCAP storage with direct writes.

    Messages below ``DIRECT_BYTES`` give the same bytes as rosbags; a larger message (a point
    cloud, an image) goes to the file as a chunk of its own, without passing through the chunk
    buffer (the pending chunk is closed first, so the file order stays the write order).
    """

    DIRECT_BYTES: int | None = 64 * 1024

    def __init__(self, path: Path, compression: CompressionMode, chunk_compression: str = "none") -> None:
        super().__init__(path, compression)
        self._compressor = None if chunk_compression == "none" else ChunkCompressor(chunk_compression)
        self.compression = "" if self._compressor is None else chunk_compression
        """The chunks' ``compression`` field (rosbags' attribute): ``""`` (none), ``zstd`` or ``lz4``."""
        self.bio.flush()
        self.bio = _CrcFile(self.bio, zlib.crc32(self.path.read_bytes()))  # the magic and Header record so far

    def close(self, version: int, metadata: str) -> None:
        self.bio.closing = True
        super().close(version, metadata)

    def write(self, connection: Connection, timestamp: int, data: bytes | memoryview) -> None:
        if self.DIRECT_BYTES is not None and len(data) >= self.DIRECT_BYTES:
            self._write_own_chunk(connection, timestamp, data)
            return
        chunk = self.chunk
        self._times(chunk, timestamp)
        self.channel_stats[connection.id] += 1
        bio = chunk.bio
        chunk.msgs[connection.id].append((timestamp, bio.tell()))
        bio.write(_MSG_HEAD.pack(0x05, 22 + len(data), connection.id, 0, timestamp, timestamp))
        bio.write(data)
        if bio.tell() > CHUNK_BYTES:
            self.close_chunk()

    def write_many(self, items: Sequence[tuple[Connection, bytes | memoryview]], timestamp: int) -> None:
        """Messages all logged at ``timestamp``: the same bytes as :meth:`write` one by one, the small
        ones in a row handed to the chunk buffer at once."""
        direct = self.DIRECT_BYTES
        parts: list[bytes | memoryview] = []
        chunk = self.chunk
        pos = chunk.bio.tell()
        stats = self.channel_stats
        for conn, data in items:
            size = len(data)
            if direct is not None and size >= direct:
                if parts:
                    chunk.bio.writelines(parts)
                    parts = []
                self._write_own_chunk(conn, timestamp, data)
                chunk = self.chunk
                pos = chunk.bio.tell()
                continue
            if not parts:
                self._times(chunk, timestamp)
            cid = conn.id
            stats[cid] += 1
            chunk.msgs[cid].append((timestamp, pos))
            parts += (_MSG_HEAD.pack(0x05, 22 + size, cid, 0, timestamp, timestamp), data)
            pos += 31 + size  # the message record's head is 31 bytes
            if pos > CHUNK_BYTES:  # as :meth:`write`: the chunk closes after the message that fills it
                chunk.bio.writelines(parts)
                parts = []
                self.close_chunk()
                chunk = self.chunk
                pos = chunk.bio.tell()
        if parts:
            chunk.bio.writelines(parts)

    def _times(self, chunk: PendingChunk, timestamp: int) -> None:
        """Widen the file's and ``chunk``'s message time spans to ``timestamp``."""
        if timestamp < self.message_start_time:
            self.message_start_time = timestamp
        if timestamp > self.message_end_time:
            self.message_end_time = timestamp
        if timestamp < chunk.message_start_time:
            chunk.message_start_time = timestamp
        if timestamp > chunk.message_end_time:
            chunk.message_end_time = timestamp

    def _write_own_chunk(self, connection: Connection, timestamp: int, data: bytes | memoryview) -> None:
        chunk = self.chunk
        out = self.bio
        if chunk.msgs:
            self.close_chunk()
        elif chunk.bio.tell():  # schema/channel records only: they may stand outside chunks
            out.write(chunk.bio.getbuffer())
            self.chunk = PendingChunk(2**63 - 1, 0, BytesIO(), defaultdict(list))
        self.message_start_time = min(self.message_start_time, timestamp)
        self.message_end_time = max(self.message_end_time, timestamp)
        self.channel_stats[connection.id] += 1
        msg_head = _MSG_HEAD.pack(0x05, 22 + len(data), connection.id, 0, timestamp, timestamp)
        size = len(msg_head) + len(data)
        t = _U64.pack(timestamp)
        crc = zlib.crc32(data, zlib.crc32(msg_head))
        comp = self.compression.encode()
        payload = None if self._compressor is None else self._compressor.compress((msg_head, data), size)
        n_payload = size if payload is None else len(payload)
        head = t + t + _U64.pack(size) + _U32.pack(crc) + _U32.pack(len(comp)) + comp + _U64.pack(n_payload)
        chunk_start = out.tell()
        if payload is None:
            out.write(b"\x06" + _U64.pack(len(head) + size) + head + msg_head)
            out.write(data)
        else:
            out.write(b"\x06" + _U64.pack(len(head) + n_payload) + head)
            out.write(payload)
        chunk_end = out.tell()
        index_start = chunk_end
        out.write(b"\x07" + _U64.pack(22) + _U16.pack(connection.id) + _U32.pack(16) + t + _U64.pack(0))
        rec = BytesIO()
        rec.write(t + t + _U64.pack(chunk_start) + _U64.pack(chunk_end - chunk_start))
        rec.write(_U32.pack(10) + _U16.pack(connection.id) + _U64.pack(index_start))
        rec.write(_U64.pack(out.tell() - chunk_end) + _U32.pack(len(comp)) + comp + _U64.pack(n_payload) + _U64.pack(size))
        self.chunks.append(rec)
        out.flush()

    def close_chunk(self) -> None:
        chunk = self.chunk
        size = chunk.bio.tell()
        buf = chunk.bio.getbuffer()
        payload = buf if self._compressor is None else self._compressor.compress((buf,), size)
        n_payload = len(payload)
        comp = self.compression.encode()
        head = (
            _U64.pack(chunk.message_start_time)
            + _U64.pack(chunk.message_end_time)
            + _U64.pack(size)
            + _U32.pack(zlib.crc32(buf))
            + _U32.pack(len(comp))
            + comp
            + _U64.pack(n_payload)
        )
        out = self.bio
        chunk_start = out.tell()
        out.write(b"\x06" + _U64.pack(len(head) + n_payload) + head)
        out.write(payload)
        chunk_end = out.tell()
        del payload
        buf.release()

        offsets: list[tuple[int, int]] = []
        for cid, msgs in chunk.msgs.items():
            offsets.append((cid, out.tell()))
            body = _U16.pack(cid) + _U32.pack(len(msgs) * 16) + struct.pack(f"<{2 * len(msgs)}Q", *chain.from_iterable(msgs))
            out.write(b"\x07" + _U64.pack(len(body)) + body)

        rec = BytesIO()
        rec.write(_U64.pack(chunk.message_start_time) + _U64.pack(chunk.message_end_time))
        rec.write(_U64.pack(chunk_start) + _U64.pack(chunk_end - chunk_start))
        rec.write(_U32.pack(len(offsets) * 10) + b"".join(_U16.pack(c) + _U64.pack(o) for c, o in offsets))
        rec.write(_U64.pack(out.tell() - chunk_end) + _U32.pack(len(comp)) + comp)
        rec.write(_U64.pack(n_payload) + _U64.pack(size))
        self.chunks.append(rec)
        self.chunk = PendingChunk(2**63 - 1, 0, BytesIO(), defaultdict(list))
        out.flush()  # a closed chunk reaches the operating system at once (SIGKILL-safe)


class McapStorage(Rosbag2Storage):
    """A rosbag2 directory with one ``.mcap`` file (:class:`LeanMcapWriter`), chunks compressed with :attr:`compression`."""

    format = "mcap"
    plugin = LeanMcapWriter

    def open(self) -> None:
        self.path.mkdir(mode=0o755, parents=True)  # FileExistsError: never overwrite a bag
        self.writer = LeanMcapWriter(self.path, CompressionMode.NONE, self.compression)

    def _write_records(self, items: Sequence[tuple[Connection, bytes | memoryview]], timestamp: int) -> None:
        self.writer.write_many(items, timestamp)

    def flush(self) -> None:
        st = self.writer
        if st.chunk.msgs:
            st.close_chunk()
        else:
            st.bio.flush()
        if self.fsync:
            os.fsync(st.bio.fileno())
