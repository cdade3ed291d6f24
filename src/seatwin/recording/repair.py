"""Repair a killed run's bag: rewrite what the recovery scanners read into a finished bag standard readers open.

A run killed without a chance to finish (SIGKILL, power loss, a crash) leaves its bag readable by
seatwin up to its last flush (:mod:`seatwin.recording.backends`), but not by standard readers: an
MCAP file without summary and footer, a rosbag2 folder without ``metadata.yaml`` (SQLite3 possibly
with a hot journal), a ROS 1 bag without index. :func:`repair_bag` reads it with those scanners and
writes every message again, bytes unchanged, through the same storage classes as the writer
(:mod:`seatwin.recording.storage`), so the result has index, summary, footer and ``metadata.yaml``.

The original is never modified (a SQLite3 bag is read from a copy, so even its journal is left as it
was) unless ``in_place``: then the repaired bag replaces it only once it is complete.
"""

from __future__ import annotations

import datetime as dt
import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from seatwin.errors import InputError
from seatwin.recording.config import TopicConfig, check_compression
from seatwin.recording.manifest import MANIFEST_NAME, check_bag_output, read_manifest, write_manifest
from seatwin.recording.reader import Recording
from seatwin.recording.reader import _find_bag as find_bag  # where a path keeps its bag, without opening it
from seatwin.recording.storage import bag_path, open_storage


@dataclass
class RepairResult:
    """What :func:`repair_bag` wrote."""

    source: Path
    """The run or bag repaired."""
    out: Path
    """The repaired run directory (or bag, when a bare bag was given)."""
    bag: Path
    format: str
    messages: int
    topics: dict[str, int] = field(default_factory=dict)
    was_finished: bool = False
    """The bag was finished already (it is rewritten all the same)."""
    truncated: bool = False
    """The scan stopped at a damaged or cut-off record: the messages after it are lost."""


def default_out(source: Path) -> Path:
    """``RUN.repaired`` beside the run (``NAME.repaired.bag`` for a ROS 1 file, ``NAME.repaired`` for another bag)."""
    source = Path(source)
    if source.is_file() and source.suffix == ".bag":
        return source.with_name(source.stem + ".repaired.bag")
    name = source.stem if source.is_file() else source.name
    return source.with_name(name + ".repaired")


def repair_bag(
    source: str | os.PathLike[str],
    out: str | os.PathLike[str] | None = None,
    in_place: bool = False,
    overwrite: bool = False,
    compression: str | None = None,
) -> RepairResult:
    """Rewrite the bag of ``source`` (a run directory, a rosbag2 folder, or a .mcap, .db3 or .bag file) as a finished bag.

    A run directory is repaired into a new run directory ``out`` (default :func:`default_out`): the
    bag, its other files copied, and the manifest with the repaired bag's counts, ``repaired`` set
    and ``completed`` as it was (a killed run stays incomplete: its end is missing). A bare bag is
    repaired into the bag ``out`` (a rosbag2 folder, or a ``.bag`` file for ROS 1). ``in_place``
    replaces the original instead (``out`` must then be None). An ``out`` that exists is refused unless
    ``overwrite`` (and then only an earlier repair's or run's output is replaced, never an input).
    ``compression``: the new bag's chunks (None: the run manifest's ``compression``, else the format's default).
    """
    source = Path(source)
    if in_place and out is not None:
        raise InputError(source, "give either an output or in-place repair, not both")
    with tempfile.TemporaryDirectory(prefix="seatwin-repair-") as tmp, _reading_copy(source, Path(tmp)) as rec:
        run_dir = rec.run_dir
        if in_place and run_dir is None and rec.bag.is_file() and rec.format != "ros1":
            raise InputError(rec.bag, "in-place repair takes the run or rosbag2 folder, not a storage file in it")
        if in_place:
            target = _staging(run_dir if run_dir is not None else rec.bag)
        else:
            target = Path(out) if out is not None else default_out(run_dir if run_dir is not None else source)
            check_bag_output(target, source, overwrite)
        new_bag = bag_path(target, rec.format) if run_dir is not None else target
        if compression is None:
            compression = (rec.manifest or {}).get("compression")
        compression = check_compression(rec.format, compression)
        result = RepairResult(source, target, new_bag, rec.format, 0, was_finished=not rec.recovered, truncated=rec.truncated)
        try:
            if run_dir is not None:
                target.mkdir(parents=True)
            _rewrite(rec, new_bag, result, compression)
            result.truncated = rec.truncated
            if run_dir is not None:
                _copy_run_files(run_dir, rec.bag, target)
                _write_repaired_manifest(run_dir, target, result, compression)
        except BaseException:
            shutil.rmtree(target, ignore_errors=True) if target.is_dir() else target.unlink(missing_ok=True)
            raise
    if in_place:
        original = run_dir if run_dir is not None else rec.bag
        _swap(target, original)
        result.out = original
        result.bag = bag_path(original, rec.format) if run_dir is not None else original
    return result


class _reading_copy:
    """Open ``source`` for reading without touching it: a SQLite3 bag (whose hot journal any SQLite reader
    rolls back into the file) is copied into ``tmp`` first and the copy read; ``run_dir``, ``manifest``
    and ``topic_config`` stay the original run's."""

    def __init__(self, source: Path, tmp: Path) -> None:
        self.source, self.tmp = source, tmp
        self.rec: Recording | None = None

    def __enter__(self) -> Recording:
        bag, fmt, run_dir = find_bag(self.source)
        if fmt != "sqlite3":
            self.rec = Recording(self.source)
            return self.rec
        copy = self.tmp / bag.name
        if bag.is_dir():
            shutil.copytree(bag, copy)
        else:
            for f in bag.parent.glob(bag.name + "*"):  # x.db3 and its -journal / -wal
                shutil.copy2(f, self.tmp / f.name)
        rec = self.rec = Recording(copy)
        rec.bag, rec.run_dir = bag, run_dir
        rec.manifest = read_manifest(run_dir) if run_dir is not None else None
        cfg = (rec.manifest or {}).get("topic_config")
        if cfg:
            rec.topic_config = TopicConfig.from_dict(cfg, source=str(run_dir))
        return rec

    def __exit__(self, *exc: object) -> None:
        if self.rec is not None:
            self.rec.close()


def _rewrite(rec: Recording, new_bag: Path, result: RepairResult, compression: str) -> None:
    """Every message of ``rec`` (bytes unchanged, file order) into a new finished bag at ``new_bag``."""
    storage = open_storage(rec.format, new_bag, rec.store, compression=compression)
    latched = rec.topic_config.tf_static
    conns: dict[str, object] = {}
    counts: dict[str, int] = {}
    try:
        for topic, msgtype, ts, data in rec.raw_messages():
            conn = conns.get(topic)
            if conn is None:
                conn = conns[topic] = storage.add_connection(topic, msgtype, latched=topic == latched)
                counts[topic] = 0
            storage.write(conn, ts, data)  # type: ignore[arg-type]
            counts[topic] += 1
        storage.close()
    except BaseException:
        storage.abort()
        raise
    result.topics = counts
    result.messages = sum(counts.values())


def _copy_run_files(run_dir: Path, bag: Path, target: Path) -> None:
    """The run's other files (scenario, …) beside the new bag; not the bag nor the manifest."""
    for f in sorted(run_dir.iterdir()):
        if f.name == MANIFEST_NAME or f.name.startswith(MANIFEST_NAME) or f.resolve() == bag.resolve():
            continue
        if f.is_file():
            shutil.copy2(f, target / f.name)
        elif f.is_dir():
            shutil.copytree(f, target / f.name)


def _write_repaired_manifest(run_dir: Path, target: Path, result: RepairResult, compression: str) -> None:
    manifest = read_manifest(run_dir) or {}
    manifest["compression"] = compression
    manifest["topics"] = {
        t: {"type": (manifest.get("topics", {}).get(t) or {}).get("type"), "count": n} for t, n in sorted(result.topics.items())
    }
    manifest["message_count"] = result.messages
    manifest["repaired"] = {
        "utc": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
        "from": "a finished bag" if result.was_finished else "a bag that was never finished (read up to its last flush)",
        "truncated": result.truncated,
        "messages": result.messages,
    }
    write_manifest(target, manifest)


def _staging(original: Path) -> Path:
    """A new path beside ``original`` (same file system) to build the repaired copy in."""
    staging = original.with_name(f".{original.name}.repairing-{os.getpid()}")
    if staging.exists():
        raise InputError(staging, "exists: another repair of this run is under way, or one was cut short (remove it)")
    return staging


def _swap(new: Path, original: Path) -> None:
    """Put ``new`` in the place of ``original`` (renames on one file system); the original is removed only after."""
    old = original.with_name(f".{original.name}.replaced-{os.getpid()}")
    os.replace(original, old)
    try:
        os.replace(new, original)
    except BaseException:
        os.replace(old, original)
        raise
    shutil.rmtree(old) if old.is_dir() else old.unlink()
