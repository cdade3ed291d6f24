"""Chunk (and rosbag2 message/file) compression for the writers: zstd (level :data:`~seatwin.defaults.ZSTD_LEVEL`) and lz4 frames.

A chunk is compressed from its pieces (a message record's head and its data) without joining them
first, and every zstd frame carries its content size, as ``ZSTD_compress`` writes it (readers that
size their output from the frame header — rosbag2's zstd plugin, ``zstandard.decompress`` — need it).
The libraries are those the readers already use: ``compression.zstd`` (``backports.zstd`` before
Python 3.14, a rosbags dependency) and ``lz4.frame``.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from seatwin.defaults import ZSTD_LEVEL

PIECE = 1 << 20
"""Bytes read at a time by :func:`compress_file`."""


class ChunkCompressor:
    """Compress chunk records with ``kind`` (``zstd`` or ``lz4``); one instance per writer, reused."""

    def __init__(self, kind: str, level: int | None = None) -> None:
        if kind == "zstd":
            zstd = zstd_module()
            self._zstd = zstd.ZstdCompressor(level=ZSTD_LEVEL if level is None else level)
            self._end = zstd.ZstdCompressor.FLUSH_FRAME
        elif kind == "lz4":
            import lz4.frame  # type: ignore[import-untyped]

            self._lz4 = lz4.frame
            self._level = 0 if level is None else level
        else:
            raise ValueError(f"unknown chunk compression {kind!r}; expected zstd or lz4")
        self.kind = kind

    def compress(self, parts: Sequence[bytes | memoryview], size: int) -> bytes:
        """One frame holding ``parts`` (``size`` bytes together) in order."""
        if self.kind == "zstd":
            z = self._zstd
            z.set_pledged_input_size(size)
            out = [z.compress(p) for p in parts[:-1]]
            out.append(z.compress(parts[-1] if parts else b"", self._end))
            return b"".join(out)
        c = self._lz4.LZ4FrameCompressor(compression_level=self._level)
        out = [c.begin(source_size=size)] + [c.compress(p) for p in parts]
        out.append(c.flush())
        return b"".join(out)


def zstd_module() -> Any:
    """``compression.zstd`` (Python 3.14) or ``backports.zstd`` (a rosbags dependency)."""
    try:
        from compression import zstd  # type: ignore[import-not-found]
    except ImportError:
        from backports import zstd
    return zstd


def compress_file(src: Path, dst: Path, *, level: int | None = None, fsync: bool = False) -> None:
    """``src`` as one zstd frame (declaring its size) in the new file ``dst``, read and written a piece at a time:
    rosbag2's file compression (``<file>.zstd``, level 1 as its zstd plugin)."""
    zstd = zstd_module()
    z = zstd.ZstdCompressor(level=ZSTD_LEVEL if level is None else level)
    z.set_pledged_input_size(src.stat().st_size)
    with src.open("rb") as fin, dst.open("xb") as fout:
        while piece := fin.read(PIECE):
            fout.write(z.compress(piece))
        fout.write(z.flush())
        if fsync:
            fout.flush()
            os.fsync(fout.fileno())
