"""A copy of a run with more messages in its bag (``seatwin track --out-bag``: the tracks beside the sensors).

The source is never modified. Its messages are copied byte for byte with their log times, in the
same bag format (and ROS 2 distribution), merged by log time with the new messages; a source topic
that the new messages also use is replaced (tracking a run that has tracks already). The bag's
definitions are the source's own, with seatwin's for the new types. A run directory gives a run
directory (its other files copied, the manifest counting the new topics and saying what was
added); a bare bag gives a bare bag. A failure leaves nothing behind.
"""

from __future__ import annotations

import heapq
import shutil
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from seatwin.defaults import DEFAULT_ROS_DISTRO
from seatwin.recording.config import TopicConfig
from seatwin.recording.convert import FLUSH_BYTES, ConvertResult, copy_run_files
from seatwin.recording.manifest import check_bag_output, write_manifest
from seatwin.recording.storage import bag_path, open_storage

Message = tuple[str, str, int, bytes]
"""(topic, type, log time ns, bytes serialised for the bag's format)."""


def copy_with_messages(
    src: str | Path,
    out: str | Path,
    messages: Iterable[Message],
    *,
    added: dict[str, Any] | None = None,
    overwrite: bool = False,
    param: str = "out",
) -> ConvertResult:
    """Write ``src`` (run directory or bag) to the new ``out`` with ``messages`` (time-ordered, in ``src``'s bag
    format: see :func:`bag_format`) merged in; ``added`` goes into the manifest's ``added`` list; errors about
    ``out`` name ``param``."""
    from rosbags.typesys import Stores, get_typestore

    from seatwin.recording.messages import typestore
    from seatwin.recording.reader import open_bag

    out = Path(out)
    check_bag_output(out, src, overwrite, param)
    with open_bag(src) as rec:
        fmt = rec.format
        manifest = rec.manifest or {}
        run_dir = rec.run_dir if rec.manifest is not None else None
        bag = bag_path(out, fmt) if run_dir is not None else out
        ros_distro = None if fmt == "ros1" else str(manifest.get("ros_distro") or DEFAULT_ROS_DISTRO)
        defs = dict(typestore(fmt).fielddefs)
        defs.update(rec.store.fielddefs)  # the source's own definitions where it has them
        store = get_typestore(Stores.EMPTY)
        store.register(defs)
        extra = list(messages)
        replaced = {m[0] for m in extra}
        latched = {TopicConfig().tf_static, rec.topic_config.tf_static}
        source = ((t, mt, ts, d) for t, mt, ts, d in rec.raw_messages() if t not in replaced)
        bag.parent.mkdir(parents=True, exist_ok=True)
        made = out if run_dir is not None else bag
        storage = open_storage(fmt, bag, store, ros_distro=ros_distro or DEFAULT_ROS_DISTRO)
        conns: dict[str, Any] = {}
        counts: dict[str, int] = {}
        types: dict[str, str] = {}
        pending = 0
        try:
            for topic, msgtype, ts, data in heapq.merge(source, extra, key=lambda m: m[2]):
                conn = conns.get(topic)
                if conn is None:
                    conn = conns[topic] = storage.add_connection(topic, msgtype, latched=topic in latched)
                    counts[topic], types[topic] = 0, msgtype
                storage.write(conn, ts, data)
                counts[topic] += 1
                pending += len(data)
                if pending > FLUSH_BYTES:
                    storage.flush()
                    pending = 0
            storage.close()
            if run_dir is not None:
                copy_run_files(run_dir, rec.bag, out)
                m = dict(manifest)
                m["topics"] = {t: {"type": types[t], "count": counts[t]} for t in sorted(counts)}
                m["message_count"] = sum(counts.values())
                m["added"] = [*m.get("added", []), {**(added or {}), "from": str(Path(src)), "topics": sorted(replaced)}]
                write_manifest(out, m)
        except BaseException:
            storage.abort()
            if made.is_dir():  # a half-written copy is of no use: nothing of it is left behind
                shutil.rmtree(made)
            else:
                made.unlink(missing_ok=True)
            raise
    return ConvertResult(out if run_dir is not None else bag, bag, fmt, ros_distro, counts)


def bag_format(src: str | Path) -> str:
    """The bag format (``mcap``, ``sqlite3``, ``ros1``) of a run or bag: what :func:`copy_with_messages` wants."""
    from seatwin.recording.reader import open_bag

    with open_bag(src) as rec:
        return str(rec.format)
