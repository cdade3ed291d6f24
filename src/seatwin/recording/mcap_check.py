"""Structural pre-check of an MCAP file before any MCAP reader (rosbags, ``mcap``) touches it.

The readers trust the length fields in the file: CPython's ``file.read(n)`` allocates ``n`` bytes
before it reads, so one forged ``u64`` asks for gigabytes (issue #14). This check reads only
fixed-size headers (at most a few dozen bytes per record, with ``seek``) and never allocates from
a length it read; it verifies (https://mcap.dev/spec):

* the magic ``\\x89MCAP0\\r\\n`` at the start;
* every top-level record (opcode u8, length u64, content) of the data section ends before the
  summary section (or the footer, or the end of the file);
* the footer's ``summary_start`` and ``summary_offset_start`` lie inside the file, before the
  footer;
* every summary record ends before the footer; each Chunk Index points inside the data section
  (``chunk_start_offset + chunk_length <= summary_start``), its compressed bytes inside its chunk
  and its ``uncompressed_size`` under :data:`MAX_UNCOMPRESSED`;
* each Chunk record's ``records`` length fits in the record and its ``uncompressed_size`` is under
  the per-chunk budget (:class:`~seatwin.recording.chunks.ReadOptions`, 256 MiB by default: the
  readers allocate it when they decompress the chunk);
* each Chunk's records inflate (incrementally, :func:`~seatwin.recording.chunks.inflate_pieces`)
  to exactly its ``uncompressed_size``, all chunks together stay under the per-file budget, and
  its ``uncompressed_crc``, when not 0 ("not written", as in bags before CRCs were written), is
  the CRC-32 of the records; the Data End record's ``data_section_crc``, when not 0, is the
  CRC-32 of the file up to it. A CRC mismatch is an error, or with ``ignore_crc`` counted in
  :attr:`McapLayout.bad_crc`.

A file without the end magic is unfinished (SIGKILL, full disk): its first record whose header or
content runs past the end of the file (or whose opcode is the invalid 0x00, as a zero-filled tail
has) is the truncation point; :attr:`McapLayout.readable_end` is where the recovery scan stops.
Violations raise ``InputError(path, "corrupt MCAP: <record> at byte <offset>: <field> <value>
exceeds <limit>")``.
"""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

from seatwin.errors import InputError
from seatwin.recording.chunks import PIECE, Inflated, ReadOptions, inflate_pieces

MAGIC = b"\x89MCAP0\r\n"
MAX_UNCOMPRESSED = ReadOptions().chunk_bytes
"""Largest ``uncompressed_size`` of a chunk accepted by default (256 MiB): the readers allocate it
when they decompress; our writer closes chunks far below it (one point cloud is a few MB)."""

_FOOTER_LEN = 9 + 20 + 8  # footer record (opcode, length, content) + end magic
_OP_FOOTER, _OP_CHUNK, _OP_CHUNK_INDEX, _OP_DATA_END = 0x02, 0x06, 0x08, 0x0F
_NAMES = {
    0x01: "Header",
    0x02: "Footer",
    0x03: "Schema",
    0x04: "Channel",
    0x05: "Message",
    0x06: "Chunk",
    0x07: "Message Index",
    0x08: "Chunk Index",
    0x09: "Attachment",
    0x0A: "Attachment Index",
    0x0B: "Statistics",
    0x0C: "Metadata",
    0x0D: "Metadata Index",
    0x0E: "Summary Offset",
    0x0F: "Data End",
}
_U32 = struct.Struct("<I")
_U64 = struct.Struct("<Q")
_HEAD = struct.Struct("<BQ")


@dataclass(frozen=True)
class McapLayout:
    size: int
    finished: bool
    """The file ends in the magic bytes after a well-formed footer."""
    data_end: int
    """End of the data section (``summary_start``, the footer, or the end of an unfinished file)."""
    readable_end: int
    """End of the last complete top-level record (the whole file when finished)."""
    truncated: bool
    """An unfinished file whose last record is cut off (or followed by junk)."""
    bad_crc: int = 0
    """Chunks (and the data section) whose CRC does not match, read anyway (``ignore_crc``)."""


def _name(op: int) -> str:
    return _NAMES.get(op, f"record 0x{op:02x}")


_CHUNK_OPS = {0x03: "Schema", 0x04: "Channel", 0x05: "Message"}
_MESSAGE_HEAD = 22  # channel id, sequence, log time, publish time


class _ChunkRecords:
    """Walks the records inside a chunk as its bytes arrive in pieces: each must be a Schema, Channel
    or Message (MCAP spec), a Message at least its fixed fields long, and the last one must end with
    the chunk — zeros or junk stop here at once, not after millions of empty records in a reader."""

    def __init__(self) -> None:
        self.head = b""
        self.skip = 0
        self.offset = 0

    def feed(self, piece: bytes) -> None:
        i, n = 0, len(piece)
        while i < n:
            if self.skip:
                take = min(self.skip, n - i)
                self.skip -= take
                i += take
                continue
            part = piece[i : i + 9 - len(self.head)]
            self.head += part
            i += len(part)
            if len(self.head) == 9:
                op, length = _HEAD.unpack(self.head)
                self.head = b""
                if op not in _CHUNK_OPS:
                    raise Inflated(f"record at offset {self.offset} of its records has opcode 0x{op:02x}; expected 0x03–0x05")
                if op == 0x05 and length < _MESSAGE_HEAD:
                    raise Inflated(f"Message at offset {self.offset} of its records has length {length} < {_MESSAGE_HEAD}")
                self.offset += 9 + length
                self.skip = length

    def finish(self) -> None:
        if self.head or self.skip:
            raise Inflated(f"the last record (ending at offset {self.offset}) runs past the end of its records")


class _Checker:
    def __init__(self, path: Path, f: BinaryIO, size: int, options: ReadOptions) -> None:
        self.path, self.f, self.size, self.options = path, f, size, options
        self.inflated = 0
        self.bad_crc = 0
        self.pending: list[tuple[int, int, int, int]] = []
        """Uncompressed chunks with a CRC: (record offset, records offset, length, stored CRC)."""
        self.data_crc: tuple[int, int, int] | None = None
        """(stored, computed, Data End offset) once the Data End record is read, if it holds a CRC."""

    def fail(self, what: str, at: int, field: str, value: int, limit: int) -> InputError:
        return InputError(self.path, f"corrupt MCAP: {what} at byte {at}: {field} {value} exceeds {limit}")

    def read(self, at: int, n: int) -> bytes:
        """Exactly ``n`` bytes (a small constant) at ``at``; short only at the end of the file."""
        self.f.seek(at)
        return self.f.read(n)

    def head(self, at: int) -> tuple[int, int] | None:
        raw = self.read(at, 9)
        return _HEAD.unpack(raw) if len(raw) == 9 else None

    def chunk(self, at: int, length: int) -> None:
        """A Chunk record's fixed fields against its record length."""
        body = at + 9
        fixed = self.read(body, 32)  # start, end, uncompressed_size, crc, compression length
        if len(fixed) < 32 or length < 40:
            raise self.fail("Chunk", at, "fixed fields of", 40, length)
        (usize,) = _U64.unpack_from(fixed, 16)
        (clen,) = _U32.unpack_from(fixed, 28)
        if clen > length - 40:
            raise self.fail("Chunk", at, "compression length", clen, length - 40)
        raw = self.read(body + 32 + clen, 8)
        (rlen,) = _U64.unpack(raw)
        if rlen > length - 40 - clen:
            raise self.fail("Chunk", at, "records length", rlen, length - 40 - clen)
        if usize > self.options.chunk_bytes:
            raise self.fail("Chunk", at, "uncompressed_size", usize, self.options.chunk_bytes)
        (crc,) = _U32.unpack_from(fixed, 24)
        comp = self.read(body + 32, clen).decode("utf-8", "replace")
        self.chunk_records(at, comp, body + 32 + clen + 8, rlen, usize, crc)

    def chunk_records(self, at: int, comp: str, start: int, rlen: int, usize: int, crc: int) -> None:
        """Inflate a chunk's records within the budgets; compare their size and CRC with the stored ones."""
        self.inflated += usize
        if self.inflated > self.options.total_bytes:
            raise InputError(
                self.path,
                f"corrupt MCAP: Chunk at byte {at}: the chunks so far inflate to {self.inflated} bytes, "
                f"over the per-file budget of {self.options.total_bytes}",
            )
        value = 0
        walk = _ChunkRecords()
        try:
            if comp == "":
                if rlen != usize:
                    raise Inflated(f"holds {rlen} bytes, but declares {usize}")
                self.plain_records(start, rlen)  # headers only (seek); the CRC waits for the data section's
                if crc:
                    self.pending.append((at, start, rlen, crc))
                return
            else:
                if comp not in ("zstd", "lz4"):
                    raise Inflated(f"unknown compression {comp!r}; expected zstd, lz4 or none")
                if rlen > self.options.chunk_bytes + PIECE:
                    raise Inflated(f"holds {rlen} compressed bytes, over the per-chunk budget of {self.options.chunk_bytes}")
                for piece in inflate_pieces(comp, self.read(start, rlen), usize, self.options.chunk_bytes):
                    walk.feed(piece)
                    if crc:
                        value = zlib.crc32(piece, value)
            walk.finish()
        except Inflated as exc:
            raise InputError(self.path, f"corrupt MCAP: Chunk at byte {at} ({comp or 'uncompressed'}): {exc.reason}") from None
        if crc and value != crc:
            self.crc_mismatch(f"Chunk at byte {at}", crc, value)

    def plain_records(self, start: int, rlen: int) -> None:
        """The records of an uncompressed chunk, header by header (:class:`_ChunkRecords`' rules)."""
        pos, end = start, start + rlen
        while pos < end:
            raw = self.read(pos, 9)
            if len(raw) < 9 or pos + 9 > end:
                raise Inflated(f"the record at offset {pos - start} runs past the end of its records")
            op, length = _HEAD.unpack(raw)
            if op not in _CHUNK_OPS:
                raise Inflated(f"record at offset {pos - start} of its records has opcode 0x{op:02x}; expected 0x03–0x05")
            if op == 0x05 and length < _MESSAGE_HEAD:
                raise Inflated(f"Message at offset {pos - start} of its records has length {length} < {_MESSAGE_HEAD}")
            if length > end - pos - 9:
                raise Inflated(f"the record at offset {pos - start} runs past the end of its records")
            pos += 9 + length

    def finish_crcs(self) -> None:
        """The CRCs of the uncompressed chunks — read only when the data section's CRC is absent or does
        not match (one pass over the file, not two) — then the data section's own."""
        if self.data_crc is None or self.data_crc[0] != self.data_crc[1]:
            for at, start, rlen, crc in self.pending:
                self.f.seek(start)
                value, left = 0, rlen
                while left:
                    piece = self.f.read(min(left, PIECE))
                    left -= len(piece)
                    value = zlib.crc32(piece, value)
                if value != crc:
                    self.crc_mismatch(f"Chunk at byte {at}", crc, value)
        if self.data_crc is not None and self.data_crc[0] != self.data_crc[1]:
            at, stored, value = self.data_crc[2], self.data_crc[0], self.data_crc[1]
            self.crc_mismatch(f"Data End at byte {at} (data section)", stored, value)

    def crc_mismatch(self, what: str, stored: int, computed: int) -> None:
        if not self.options.ignore_crc:
            raise InputError(self.path, f"corrupt MCAP: {what}: CRC-32 0x{computed:08x} does not match the stored 0x{stored:08x}")
        self.bad_crc += 1

    def data_end(self, at: int, length: int) -> None:
        """The Data End record: the CRC-32 of every byte before it, when stored."""
        if length < 4:
            raise self.fail("Data End", at, "length", length, 4)
        (stored,) = _U32.unpack(self.read(at + 9, 4))
        if not stored:
            return
        self.f.seek(0)
        value, left = 0, at
        while left:
            piece = self.f.read(min(left, PIECE))
            left -= len(piece)
            value = zlib.crc32(piece, value)
        self.data_crc = (stored, value, at)

    def chunk_index(self, at: int, length: int, data_end: int) -> None:
        body, end = at + 9, at + 9 + length
        fixed = self.read(body, 36)  # times, chunk_start_offset, chunk_length, map byte length
        if len(fixed) < 36 or length < 36:
            raise self.fail("Chunk Index", at, "fixed fields of", 36, length)
        _, _, start, clength, maplen = struct.unpack("<QQQQI", fixed)
        if start > data_end:
            raise self.fail("Chunk Index", at, "chunk_start_offset", start, data_end)
        if start + clength > data_end:
            raise self.fail("Chunk Index", at, "chunk_start_offset + chunk_length", start + clength, data_end)
        pos = body + 36 + maplen
        if pos + 12 > end:
            raise self.fail("Chunk Index", at, "message_index_offsets length", maplen, max(end - body - 48, 0))
        raw = self.read(pos, 12)  # message_index_length, compression length
        (comp_len,) = _U32.unpack_from(raw, 8)
        pos += 12 + comp_len
        if pos + 16 > end:
            raise self.fail("Chunk Index", at, "compression length", comp_len, max(end - pos + comp_len - 16, 0))
        csize, usize = struct.unpack("<QQ", self.read(pos, 16))
        room = max(clength - 9 - 40 - comp_len, 0)
        if csize > room:
            raise self.fail("Chunk Index", at, "compressed_size", csize, room)
        if usize > self.options.chunk_bytes:
            raise self.fail("Chunk Index", at, "uncompressed_size", usize, self.options.chunk_bytes)

    def walk(self, start: int, end: int, unfinished: bool, data_end: int) -> tuple[int, bool]:
        """Top-level records in ``[start, end)``; (end of the last complete record, truncated)."""
        pos = start
        while pos < end:
            h = self.head(pos)
            if h is None or pos + 9 > end:
                if unfinished:
                    return pos, True
                raise self.fail("record header", pos, "end", pos + 9, end)
            op, length = h
            if unfinished and op == 0:
                return pos, True
            if length > end - pos - 9:
                if unfinished:
                    return pos, True
                raise self.fail(_name(op), pos, "length", length, end - pos - 9)
            if op == _OP_CHUNK:
                self.chunk(pos, length)
            elif op == _OP_CHUNK_INDEX:
                self.chunk_index(pos, length, data_end)
            elif op == _OP_DATA_END and not unfinished:
                self.data_end(pos, length)
            pos += 9 + length
        return pos, False


def check_mcap(path: str | Path, options: ReadOptions | None = None) -> McapLayout:
    """Check ``path``'s record structure and chunks (see the module docstring) within ``options``'
    budgets (default :meth:`ReadOptions.from_env`); raise :class:`InputError` if broken."""
    path = Path(path)
    options = options or ReadOptions.from_env()
    try:
        size = path.stat().st_size
        f = path.open("rb")
    except OSError as exc:
        raise InputError(path, f"cannot open MCAP file: {exc.strerror or exc}") from None
    with f:
        if f.read(8) != MAGIC:
            raise InputError(path, "not an MCAP file (bad magic bytes)")
        c = _Checker(path, f, size, options)
        footer_at = size - _FOOTER_LEN
        finished = footer_at >= 8 and c.read(size - 8, 8) == MAGIC
        if not finished:
            end, truncated = c.walk(8, size, True, size)
            c.finish_crcs()
            return McapLayout(size, False, size, end, truncated, c.bad_crc)
        raw = c.read(footer_at, 29)
        op, length, summary_start, summary_offset_start = struct.unpack_from("<BQQQ", raw)
        if op != _OP_FOOTER:
            raise InputError(path, f"corrupt MCAP: Footer at byte {footer_at}: opcode 0x{op:02x} is not 0x02")
        if length != 20:
            raise c.fail("Footer", footer_at, "length", length, 20)
        if summary_start > footer_at:
            raise c.fail("Footer", footer_at, "summary_start", summary_start, footer_at)
        if summary_offset_start > footer_at:
            raise c.fail("Footer", footer_at, "summary_offset_start", summary_offset_start, footer_at)
        if summary_start and summary_start < 8:
            raise InputError(path, f"corrupt MCAP: Footer at byte {footer_at}: summary_start {summary_start} < 8")
        data_end = summary_start or footer_at
        c.walk(8, data_end, False, data_end)
        if summary_start:
            c.walk(summary_start, footer_at, False, data_end)
        c.finish_crcs()
        return McapLayout(size, True, data_end, size, False, c.bad_crc)
