"""rosbag2's zstd compression of SQLite3 bags, read within the reader's budgets (:class:`~seatwin.recording.chunks.ReadOptions`).

rosbag2 compresses a SQLite3 bag per message (``compression_mode: MESSAGE``: each row's CDR bytes one zstd
frame) or per file (``FILE``: each closed ``.db3`` as ``.db3.zstd``). rosbags inflates both without a
bound (``zstd.decompress`` of every message; the whole file into a temporary folder), so a 1 kB message
or file that inflates to many GiB exhausts memory or disk. Here rosbags only ever sees inflated data:

* :func:`bag_compression` reads the mode from ``metadata.yaml`` (``none``, ``message`` or ``file``;
  any other mode or a format other than zstd is an :class:`InputError` naming the field);
* :class:`StagedBag` is a temporary rosbag2 folder holding ``metadata.yaml`` without compression and the
  storage files: file-compressed ones inflated there a piece at a time (:func:`inflate_file`; all of a
  bag's files together within ``total_bytes``, ``SEATWIN_MAX_BAG_BYTES``), message-compressed ones as
  links to the ``.db3`` (or to its rolled-back copy). The input is never written;
* :class:`InflatingBackend` inflates each message's frame within ``chunk_bytes``
  (``SEATWIN_MAX_CHUNK_BYTES``) and its declared size, all messages of one pass together within
  ``total_bytes``; an error names the bag, the topic and the message's time. A ``.db3`` read without
  ``metadata.yaml`` (a killed run) is inflated message by message when the bytes start with zstd's
  magic number (CDR starts with a zero byte, so the two cannot be confused).
"""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path, PurePath
from typing import Any

from seatwin.errors import InputError
from seatwin.recording.backends import Backend, RawMessage
from seatwin.recording.chunks import PIECE, Inflated, ReadOptions, inflate_pieces
from seatwin.recording.storage.compression import zstd_module
from seatwin.recording.storage.metadata_yaml import dump_yaml
from seatwin.safe_yaml import load_yaml

ZSTD_MAGIC = b"\x28\xb5\x2f\xfd"
"""The first four bytes of a zstd frame."""

MODES = ("none", "message", "file")


def _info(bag: Path) -> dict[str, Any] | None:
    """``rosbag2_bagfile_information`` of ``bag``'s ``metadata.yaml`` (None without one)."""
    meta = bag / "metadata.yaml"
    if not meta.is_file():
        return None
    doc = load_yaml(meta, "a rosbag2 metadata.yaml")
    info = doc.get("rosbag2_bagfile_information") if isinstance(doc, dict) else None
    if not isinstance(info, dict):
        raise InputError(meta, "not rosbag2 metadata: expected a mapping rosbag2_bagfile_information")
    return info


def bag_compression(bag: Path) -> str:
    """``none``, ``message`` or ``file``: how the rosbag2 folder ``bag`` is compressed (its ``metadata.yaml``).
    A ``metadata.yaml`` that is no rosbag2 metadata at all says ``none``: the reader then reads the storage files
    without it, as a killed run's (message frames recognised by their magic number)."""
    try:
        info = _info(bag)
    except InputError:
        return "none"
    if info is None:
        return "none"
    meta = bag / "metadata.yaml"
    mode, fmt = info.get("compression_mode") or "", info.get("compression_format") or ""
    if not isinstance(mode, str) or mode.lower() not in ("", *MODES):
        expected = "expected MESSAGE, FILE, NONE or empty"
        raise InputError(meta, f"unknown compression_mode {mode!r}; {expected}", where="compression_mode")
    mode = mode.lower() or "none"
    if mode != "none" and fmt != "zstd":
        raise InputError(meta, f"compression_format {fmt!r} is not readable; expected zstd", where="compression_format")
    return mode


def inflate_file(src: Path, dst: Path, budget: int) -> int:
    """Inflate the one zstd frame in ``src`` into the new file ``dst``, a piece at a time; its size.

    Raises :class:`Inflated` when the output passes ``budget`` or the size the frame declares, when that size is
    more than the disk holds free, when it ends short of it, when the data are corrupt or when bytes follow the frame."""
    zstd = zstd_module()
    with src.open("rb") as fin, dst.open("xb") as fout:
        head = fin.read(18)  # a frame header's largest size
        if head[:4] != ZSTD_MAGIC:
            raise Inflated("is not zstd data (no zstd magic number at its start)")
        try:
            declared = zstd.get_frame_info(head).decompressed_size
        except zstd.ZstdError as exc:
            raise Inflated(f"corrupt zstd frame header: {exc}") from None
        if declared is not None and declared > budget:
            raise Inflated(f"declares {declared} bytes uncompressed, over the budget of {budget}")
        free = shutil.disk_usage(dst.parent).free
        if declared is not None and declared > free:
            raise Inflated(f"declares {declared} bytes uncompressed, more than the {free} bytes free in {dst.parent.parent}")
        limit = budget if declared is None else declared
        d = zstd.ZstdDecompressor()
        feed, total = head, 0
        try:
            while not d.eof:
                if not feed and d.needs_input:
                    feed = fin.read(PIECE)
                    if not feed:
                        raise Inflated(f"compressed stream ends early ({total} bytes inflated)")
                piece = d.decompress(feed, PIECE)
                feed = b""
                total += len(piece)
                if total > limit:
                    what = f"the {declared} bytes it declares" if declared is not None else f"the budget of {budget} bytes"
                    raise Inflated(f"inflates beyond {what}")
                fout.write(piece)
        except zstd.ZstdError as exc:
            raise Inflated(f"corrupt zstd data: {' '.join(str(exc).split())[:200]}") from None
        if d.unused_data or fin.read(1):
            raise Inflated("holds more data after its zstd frame (rosbag2 writes one frame)")
    if declared is not None and total != declared:
        raise Inflated(f"inflates to {total} bytes, but declares {declared}")
    return total


def inflate_message(data: bytes | memoryview, budget: int) -> bytes:
    """One message's zstd frame, inflated (at most ``budget`` bytes and the size it declares)."""
    zstd = zstd_module()
    if bytes(data[:4]) != ZSTD_MAGIC:
        raise Inflated("is not a zstd frame (no zstd magic number)")
    try:
        size = zstd.get_frame_size(data)
        declared = zstd.get_frame_info(data).decompressed_size
    except zstd.ZstdError as exc:
        raise Inflated(f"corrupt zstd frame: {' '.join(str(exc).split())[:200]}") from None
    if size != len(data):
        raise Inflated(f"holds {len(data) - size} bytes after its zstd frame")
    if declared is None:  # only the budget bounds it: a piece at a time
        return b"".join(inflate_pieces("zstd", data, None, budget, unit="message"))
    if declared > budget:
        raise Inflated(f"declares {declared} bytes uncompressed, over the per-message budget of {budget}")
    d = zstd.ZstdDecompressor()  # one buffer of at most declared + 1 bytes: a frame that lies shows in its length
    try:
        out = d.decompress(data, declared + 1)
    except zstd.ZstdError as exc:
        raise Inflated(f"corrupt zstd data: {' '.join(str(exc).split())[:200]}") from None
    if len(out) > declared:
        raise Inflated(f"inflates beyond the {declared} bytes it declares")
    if not d.eof:
        raise Inflated(f"compressed stream ends early ({len(out)} of {declared} bytes)")
    if len(out) != declared:
        raise Inflated(f"inflates to {len(out)} bytes, but declares {declared}")
    return out


class StagedBag:
    """A temporary rosbag2 folder that rosbags reads without decompressing (see the module docstring).

    ``mode`` ``file``: each ``.db3.zstd`` of ``bag`` inflated here; ``message``: ``dbs`` maps each storage
    file's name to the file to read (the ``.db3`` or its rolled-back copy), linked here. :attr:`files` lists
    (file here, the input file it stands for). Close it to remove the folder."""

    def __init__(self, bag: Path, mode: str, options: ReadOptions, dbs: dict[str, Path] | None = None) -> None:
        info = _info(bag)
        if info is None:
            raise InputError(bag, "a compressed rosbag2 folder without metadata.yaml")
        names = info.get("relative_file_paths")
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            raise InputError(bag / "metadata.yaml", "expected a list of file names", where="relative_file_paths")
        self._tmp: tempfile.TemporaryDirectory[str] | None = tempfile.TemporaryDirectory(prefix="seatwin-rosbag2-")
        self.path = Path(self._tmp.name)
        self.copied = False
        self.files: list[tuple[Path, Path]] = []
        try:
            self._stage(bag, mode, options, [PurePath(n).name for n in names], dbs or {})
            paths = [f.name for f, _ in self.files]
            info = {**info, "compression_format": "", "compression_mode": "", "relative_file_paths": paths}
            (self.path / "metadata.yaml").write_text(dump_yaml({"rosbag2_bagfile_information": info}), "utf8")
        except BaseException:
            self.close()
            raise

    def _stage(self, bag: Path, mode: str, options: ReadOptions, names: list[str], dbs: dict[str, Path]) -> None:
        left = options.total_bytes
        for name in names:
            src = bag / name
            if not src.is_file():
                raise InputError(bag / "metadata.yaml", f"names {name!r}, which is missing", where="relative_file_paths")
            if mode == "message":
                here = self.path / name
                here.symlink_to(dbs.get(name, src).resolve())
            else:
                if not name.endswith(".zstd"):
                    raise InputError(src, "expected a .zstd file in a file-compressed rosbag2 (compression_mode FILE)")
                here = self.path / name.removesuffix(".zstd")
                try:
                    left -= inflate_file(src, here, left)
                except Inflated as exc:
                    what = f"zstd-compressed storage file {exc.reason} (SEATWIN_MAX_BAG_BYTES: {options.total_bytes})"
                    raise InputError(src, what) from None
                except OSError as exc:
                    raise InputError(src, f"cannot inflate the zstd-compressed storage file: {exc.strerror or exc}") from None
            self.files.append((here, src))

    def close(self) -> None:
        if self._tmp is not None:
            self._tmp.cleanup()
            self._tmp = None


class InflatingBackend(Backend):
    """``inner``'s messages with each zstd frame inflated (``strict``: every message must be one; else only
    those that start with zstd's magic number). Errors name ``source``, the topic and the time."""

    def __init__(self, inner: Backend, source: Path, options: ReadOptions, strict: bool = True) -> None:
        super().__init__(
            path=source,
            format=inner.format,
            ros1=inner.ros1,
            recovered=inner.recovered,
            truncated=inner.truncated,
            topics=inner.topics,
            start_ns=inner.start_ns,
            end_ns=inner.end_ns,
        )
        self.inner, self.options, self.strict = inner, options, strict

    def messages(self, topics: set[str] | None = None) -> Iterator[RawMessage]:
        per, left = self.options.chunk_bytes, self.options.total_bytes
        for topic, msgtype, ts, data in self.inner.messages(topics):
            if self.strict or data[:4] == ZSTD_MAGIC:
                try:
                    data = inflate_message(data, min(per, left))
                except Inflated as exc:
                    budgets = f"SEATWIN_MAX_CHUNK_BYTES: {per}, SEATWIN_MAX_BAG_BYTES left: {left}"
                    what = f"the zstd-compressed message at {ts} ns {exc.reason} ({budgets})"
                    raise InputError(self.path, what, where=topic) from None
                left -= len(data)
            yield topic, msgtype, ts, data

    def close(self) -> None:
        self.inner.close()


__all__ = ["ZSTD_MAGIC", "InflatingBackend", "StagedBag", "bag_compression", "inflate_file", "inflate_message"]
