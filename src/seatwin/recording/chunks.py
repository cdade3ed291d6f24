"""Bounded chunk inflation for the bag readers, and the reader's budgets (:class:`ReadOptions`).

A compressed chunk (MCAP zstd/lz4, ROS 1 bz2/lz4) says how large it inflates to; a hostile one
lies (a 33 KB MCAP whose zstd chunk inflates to 1 GiB). :func:`inflate_pieces` decompresses
incrementally, at most :data:`PIECE` bytes at a time, and stops as soon as the output passes
what the chunk declares or the per-chunk budget — memory stays bounded whatever the input.
The checks (``mcap_check``, ``ros1_check``) run it over every chunk before rosbags or ``mcap``
decompress one, so those libraries only ever inflate chunks whose size is verified.

Budgets (:class:`ReadOptions`): ``chunk_bytes`` (default 256 MiB; environment
``SEATWIN_MAX_CHUNK_BYTES``) per chunk, ``total_bytes`` (default 64 GiB; ``SEATWIN_MAX_BAG_BYTES``)
for all chunks of one file together; ``ignore_crc`` turns a CRC mismatch into a counted warning.
"""

from __future__ import annotations

import bz2
import os
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from seatwin.errors import InputError, ParameterError

MIB = 1 << 20
PIECE = MIB
"""Largest piece of output produced at once."""


@dataclass(frozen=True)
class ReadOptions:
    """How much a bag reader inflates, and whether a CRC mismatch is an error."""

    chunk_bytes: int = 256 * MIB
    total_bytes: int = 64 * 1024 * MIB
    ignore_crc: bool = False

    def __post_init__(self) -> None:
        for name in ("chunk_bytes", "total_bytes"):
            if getattr(self, name) < 1:
                raise ParameterError(name, f"must be a positive number of bytes, got {getattr(self, name)}")

    @classmethod
    def from_env(cls, ignore_crc: bool = False) -> ReadOptions:
        """Defaults, or the budgets in ``SEATWIN_MAX_CHUNK_BYTES`` / ``SEATWIN_MAX_BAG_BYTES``."""
        values = {}
        for name, var in (("chunk_bytes", "SEATWIN_MAX_CHUNK_BYTES"), ("total_bytes", "SEATWIN_MAX_BAG_BYTES")):
            text = os.environ.get(var)
            if text:
                try:
                    values[name] = int(text)
                except ValueError:
                    raise InputError(var, f"expected a whole number of bytes, got {text!r}") from None
                if values[name] < 1:
                    raise InputError(var, f"expected a positive number of bytes, got {text!r}")
        return cls(ignore_crc=ignore_crc, **values)


class Inflated(Exception):
    """A chunk that does not inflate as declared; ``reason`` says how (the caller names file and chunk)."""

    def __init__(self, reason: str) -> None:
        self.reason = reason
        super().__init__(reason)


def _decompressor(kind: str) -> Any:
    if kind == "bz2":
        return bz2.BZ2Decompressor()
    if kind == "zstd":
        try:
            from compression import zstd  # type: ignore[import-not-found]
        except ImportError:
            from backports import zstd
        return zstd.ZstdDecompressor()
    if kind == "lz4":
        from lz4.frame import LZ4FrameDecompressor

        return LZ4FrameDecompressor()
    raise Inflated(f"unknown compression {kind!r}; expected bz2, lz4 or zstd")


def inflate_pieces(
    kind: str, data: bytes | memoryview, declared: int | None, budget: int, unit: str = "chunk"
) -> Iterator[bytes]:
    """The output of ``data`` (compressed with ``kind``) in pieces of at most :data:`PIECE` bytes.

    Raises :class:`Inflated` as soon as the output passes ``declared`` or ``budget`` bytes, when it
    ends short of ``declared``, or when the stream is corrupt. ``declared`` None: the data do not say
    their size (a zstd frame without content size), only ``budget`` bounds them. ``unit`` names what
    ``budget`` is per (a chunk, a message, a file) in the messages.
    """
    if declared is not None and declared > budget:
        raise Inflated(f"declares {declared} bytes uncompressed, over the per-{unit} budget of {budget}")
    limit = budget if declared is None else declared
    d = _decompressor(kind)
    total = 0
    feed: bytes | memoryview = data
    try:
        while True:
            piece = d.decompress(feed, PIECE)
            feed = b""
            total += len(piece)
            if total > limit:
                if declared is None:
                    raise Inflated(f"inflates beyond the per-{unit} budget of {budget} bytes")
                raise Inflated(f"inflates beyond the {declared} bytes it declares")
            if piece:
                yield piece
            if d.eof:
                break
            if not piece and d.needs_input:
                raise Inflated(f"compressed stream ends early ({total} of {declared if declared is not None else '?'} bytes)")
    except Inflated:
        raise
    except (OSError, ValueError, EOFError, RuntimeError, MemoryError) as exc:  # bz2/zstd/lz4 on corrupt input
        raise Inflated(f"corrupt {kind} data: {type(exc).__name__}: {' '.join(str(exc).split())[:200]}") from None
    if declared is not None and total != declared:
        raise Inflated(f"inflates to {total} bytes, but declares {declared}")
