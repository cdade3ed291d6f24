"""``seatwin bag convert``: a bag in another format (MCAP, SQLite3, ROS 1) or for another ROS 2 distribution.

The source is read with :func:`~seatwin.recording.reader.open_bag` (any bag seatwin reads, recovered
ones included) and written with the recording's storage classes
(:func:`~seatwin.recording.storage.open_storage`), message by message in the reader's order with
the same log times. Messages are copied as bytes between the two rosbag2 formats and converted
at the byte level between CDR and ROS 1 (rosbags' ``cdr_to_ros1``/``ros1_to_cdr``, which add or
drop ``std_msgs/Header.seq``). Messages keep their layout, so the new bag's definitions are the source
bag's own (with the target ROS version's ``std_msgs/Header``): a ROS 2 Humble ``visualization_msgs/Marker``
(texture and mesh fields) stays one in a ROS 1 bag, self-described by its definition. ``/tf_static``
(the recording's latched topic) is written latched.

A run directory converts into a run directory: its other files (scenario, notes) are copied and
its manifest is rewritten naming the new bag, format and distribution, so every seatwin command
reads the copy as it read the original. Any other bag converts into a bare bag: a rosbag2
directory, or a ROS 1 ``.bag`` file.
"""

from __future__ import annotations

import shutil
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from seatwin.defaults import DEFAULT_ROS_DISTRO
from seatwin.errors import InputError
from seatwin.recording.config import TopicConfig, check_compression, check_format, check_ros_distro
from seatwin.recording.manifest import MANIFEST_NAME, check_bag_output, write_manifest
from seatwin.recording.storage import bag_path, open_storage

FLUSH_BYTES = 64 << 20
"""Flush the target every this many bytes (a crash leaves a readable prefix, as while recording)."""


@dataclass
class ConvertResult:
    """What :func:`convert_bag` wrote."""

    path: Path
    """The new run directory, or the bag itself."""
    bag: Path
    format: str
    ros_distro: str | None
    """None for a ROS 1 bag."""
    counts: dict[str, int]
    """Messages per topic written."""


HEADER = "std_msgs/msg/Header"


def _with_header(source_store: Any, ros1: bool) -> Any:
    """The source bag's own definitions with ROS 1's ``std_msgs/Header`` (``seq`` first) or ROS 2's."""
    from rosbags.typesys import Stores, get_typestore

    from seatwin.recording.messages import typestore

    defs = dict(source_store.fielddefs)
    defs[HEADER] = typestore("ros1" if ros1 else "mcap").fielddefs[HEADER]
    store = get_typestore(Stores.EMPTY)
    store.register(defs)
    return store


def convert_bag(
    src: str | Path,
    out: str | Path,
    *,
    fmt: str = "mcap",
    ros_distro: str = DEFAULT_ROS_DISTRO,
    overwrite: bool = False,
    compression: str | None = None,
) -> ConvertResult:
    """Write the bag (or run directory) ``src`` as a new ``fmt`` bag for ``ros_distro`` at ``out`` (an existing
    ``out`` only with ``overwrite``, and never an input), its chunks compressed with ``compression`` (None: the
    format's default, :data:`~seatwin.defaults.DEFAULT_COMPRESSION`)."""
    from seatwin.recording.reader import open_bag

    fmt = check_format(fmt, "fmt")
    ros_distro = check_ros_distro(ros_distro)
    compression = check_compression(fmt, compression)
    out = Path(out)
    check_bag_output(out, src, overwrite)
    with open_bag(src) as rec:
        run_dir = rec.run_dir if rec.manifest is not None else None
        if run_dir is not None:
            bag = bag_path(out, fmt)
        else:
            bag = out.with_suffix(".bag") if fmt == "ros1" and out.suffix != ".bag" else out
        # the messages keep their layout (a Humble Marker stays one in a ROS 1 bag, and the other way round), so
        # the target's definitions are the source's; only the Header is each ROS version's own
        store = _with_header(rec.store, ros1=fmt == "ros1")
        convert = _converter(rec.format, fmt, _with_header(rec.store, ros1=False))
        latched = {TopicConfig().tf_static, rec.topic_config.tf_static}
        bag.parent.mkdir(parents=True, exist_ok=True)
        made = out if run_dir is not None else bag
        storage = open_storage(fmt, bag, store, ros_distro=ros_distro, compression=compression)
        conns: dict[str, Any] = {}
        counts: dict[str, int] = {}
        pending = 0
        try:
            for topic, msgtype, ts, data in rec.raw_messages():
                conn = conns.get(topic)
                if conn is None:
                    conn = conns[topic] = storage.add_connection(topic, msgtype, latched=topic in latched)
                    counts[topic] = 0
                try:
                    payload = convert(data, msgtype)
                except Exception as exc:  # noqa: BLE001 - rosbags' serde: one clear line naming the topic
                    raise InputError(rec.bag, f"cannot convert a {msgtype} message at {ts} ns: {exc}", where=topic) from None
                storage.write(conn, ts, payload)
                counts[topic] += 1
                pending += len(payload)
                if pending > FLUSH_BYTES:
                    storage.flush()
                    pending = 0
        except BaseException:
            storage.abort()
            if made.is_dir():  # a half-converted bag is of no use: nothing of it is left behind
                shutil.rmtree(made)
            else:
                made.unlink(missing_ok=True)
            raise
        storage.close()
        if run_dir is not None:
            _copy_run(run_dir, rec.bag, {**(rec.manifest or {}), "compression": compression}, out, bag, fmt, ros_distro)
    return ConvertResult(out if run_dir is not None else bag, bag, fmt, None if fmt == "ros1" else ros_distro, counts)


def cdr_converter(rec: Any) -> tuple[Any, Any]:
    """(ROS 2 type store of the open recording ``rec``'s own definitions, bytes, msgtype → CDR bytes)."""
    return cdr_converter_for(rec.store, rec.format)


def cdr_converter_for(store: Any, fmt: str) -> tuple[Any, Any]:
    """:func:`cdr_converter` for messages of bag format ``fmt`` built from type store ``store`` (a writer's)."""
    ros2 = _with_header(store, ros1=False)
    return ros2, _converter(fmt, "mcap", ros2)


def _converter(src_fmt: str, fmt: str, ros2_store: Any) -> Any:
    """bytes, msgtype → bytes in the target's serialisation. rosbags converts with ROS 2 definitions
    (``std_msgs/Header`` without ``seq``, which it adds or drops itself)."""
    if src_fmt == "ros1" and fmt != "ros1":
        return ros2_store.ros1_to_cdr
    if src_fmt != "ros1" and fmt == "ros1":
        return ros2_store.cdr_to_ros1
    return lambda data, _msgtype: data


def _copy_run(run_dir: Path, old_bag: Path, manifest: dict[str, Any], out: Path, bag: Path, fmt: str, ros_distro: str) -> None:
    """The run directory's other files, and its manifest naming the new bag."""
    copy_run_files(run_dir, old_bag, out)
    m = dict(manifest)
    m.update(format=fmt, bag=bag.name, converted_from={"format": manifest.get("format"), "bag": manifest.get("bag")})
    m.pop("ros_distro", None)
    if fmt != "ros1":
        m["ros_distro"] = ros_distro
    write_manifest(out, m)


def copy_run_files(run_dir: Path, old_bag: Path, out: Path) -> None:
    """Copy a run directory's files but its bag and manifest (scenario, notes, …) into ``out``."""
    for item in run_dir.iterdir():
        if item.resolve() == old_bag.resolve() or item.name == MANIFEST_NAME:
            continue
        if item.is_dir():
            shutil.copytree(item, out / item.name)
        else:
            shutil.copy2(item, out / item.name)
