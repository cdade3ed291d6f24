"""ROS 1 bag records, and a check of every chunk before rosbags decompresses one.

A ROS 1 record is ``header_len u32, header (fields "name=value", each u32-prefixed), data_len u32,
data``; a chunk record (``op = 0x05``) holds ``compression`` (none, bz2, lz4) and ``size`` (its
uncompressed length, u32). rosbags decompresses a chunk in one call without looking at ``size``,
so a 6 KB bag whose bz2 chunk says ``size=10`` can inflate to gigabytes. :func:`check_ros1` walks
the top-level records (the file is memory-mapped: no length read from it is ever allocated) and
inflates each chunk incrementally (:func:`~seatwin.recording.chunks.inflate_pieces`) against
``size`` and the budgets; every Chunk Info record must point at a chunk it checked.
"""

from __future__ import annotations

import contextlib
import mmap
import struct
from collections.abc import Iterator
from pathlib import Path

from seatwin.errors import InputError
from seatwin.recording.chunks import Inflated, ReadOptions, inflate_pieces

MAGIC = b"#ROSBAG V2.0\n"
OP_MSG, OP_FILE_HEADER, OP_INDEX, OP_CHUNK, OP_CHUNK_INFO, OP_CONN = 0x02, 0x03, 0x04, 0x05, 0x06, 0x07


def fields(header: bytes) -> dict[str, bytes]:
    """A record header's fields (name → raw value); a field running past the header is cut."""
    out: dict[str, bytes] = {}
    i = 0
    while i + 4 <= len(header):
        (n,) = struct.unpack_from("<I", header, i)
        key, _, value = header[i + 4 : i + 4 + n].partition(b"=")
        out[key.decode("ascii", "replace")] = value
        i += 4 + n
    return out


def records(buf: bytes | memoryview | mmap.mmap, start: int = 0) -> Iterator[tuple[dict[str, bytes], memoryview, int]]:
    """ROS 1 records (header fields, data, end offset) in ``buf`` from ``start``; stops at an incomplete record."""
    mv = memoryview(buf)
    i, size = start, len(mv)
    while i + 4 <= size:
        (hl,) = struct.unpack_from("<I", mv, i)
        if i + 8 + hl > size:
            return
        header = bytes(mv[i + 4 : i + 4 + hl])
        (dl,) = struct.unpack_from("<I", mv, i + 4 + hl)
        end = i + 8 + hl + dl
        if end > size:
            return
        yield fields(header), mv[i + 8 + hl : end], end
        i = end


def chunk_size(hdr: dict[str, bytes]) -> int | None:
    """A chunk header's ``size`` (u32), or None when absent or malformed."""
    raw = hdr.get("size")
    return struct.unpack("<I", raw)[0] if raw is not None and len(raw) == 4 else None


def inflate_chunk(
    path: Path, at: int, hdr: dict[str, bytes], body: memoryview, options: ReadOptions
) -> Iterator[bytes | memoryview]:
    """A chunk record's data, inflated in pieces within ``options``' per-chunk budget and its ``size``;
    an :class:`InputError` naming the file and the chunk's byte offset if it does not inflate as declared."""
    comp = hdr.get("compression", b"none").decode("ascii", "replace")
    size = chunk_size(hdr)
    where = f"chunk at byte {at} ({comp})"
    if size is None:
        raise InputError(path, f"corrupt ROS 1 bag: {where}: no 4-byte size field")
    try:
        if comp == "none":
            if len(body) != size:
                raise Inflated(f"holds {len(body)} bytes, but declares {size}")
            if size > options.chunk_bytes:
                raise Inflated(f"declares {size} bytes, over the per-chunk budget of {options.chunk_bytes}")
            yield body  # a view: no copy
            return
        if comp not in ("bz2", "lz4"):
            raise Inflated(f"unknown compression {comp!r}; expected none, bz2 or lz4")
        yield from inflate_pieces(comp, body, size, options.chunk_bytes)
    except Inflated as exc:
        raise InputError(path, f"corrupt ROS 1 bag: {where}: {exc.reason}") from None


def check_ros1(path: Path, options: ReadOptions | None = None) -> None:
    """Inflate every chunk of the bag at ``path`` within the budgets (module docstring); an
    :class:`InputError` for the first chunk that lies about its size or passes a budget."""
    options = options or ReadOptions.from_env()
    try:
        with path.open("rb") as f:
            try:
                data: bytes | mmap.mmap = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
            except ValueError:  # empty file
                data = b""
    except OSError as exc:
        raise InputError(path, f"cannot open ROS 1 bag: {exc.strerror or exc}") from None
    try:
        if data[: len(MAGIC)] != MAGIC:
            raise InputError(path, "not a ROS 1 bag (expected '#ROSBAG V2.0' at the start)")
        chunks: set[int] = set()
        infos: list[tuple[int, int]] = []
        total = 0
        pos = len(MAGIC)
        walk = records(data, pos)
        for hdr, body, end in walk:
            op = hdr.get("op", b"\x00")[:1]
            if op == bytes([OP_CHUNK]):
                chunks.add(pos)
                size = chunk_size(hdr) or 0
                total += size
                if total > options.total_bytes:
                    raise InputError(
                        path,
                        f"corrupt ROS 1 bag: chunk at byte {pos}: the chunks so far inflate to {total} bytes, "
                        f"over the per-file budget of {options.total_bytes}",
                    )
                for _ in inflate_chunk(path, pos, hdr, body, options):
                    pass
            elif op == bytes([OP_CHUNK_INFO]):
                raw = hdr.get("chunk_pos", b"")
                if len(raw) == 8:
                    infos.append((pos, struct.unpack("<Q", raw)[0]))
            pos = end
        for at, target in infos:
            if target not in chunks:
                raise InputError(path, f"corrupt ROS 1 bag: chunk info at byte {at}: chunk_pos {target} is not a chunk record")
        walk.close()
    finally:
        if isinstance(data, mmap.mmap):
            with contextlib.suppress(BufferError):  # a view still held by an exception's frame: the GC closes it
                data.close()
