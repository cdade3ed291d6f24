"""Bag storage, one small class per format behind one interface (:class:`BagStorage`), as rosbags does.

:class:`~seatwin.recording.storage.mcap.McapStorage` and
:class:`~seatwin.recording.storage.sqlite.Sqlite3Storage` write rosbag2 directories
(:mod:`~seatwin.recording.storage.rosbag2`), :class:`~seatwin.recording.storage.ros1.Ros1Storage`
a ROS 1 ``.bag``. :func:`open_storage` picks one by format name.
"""

from __future__ import annotations

from pathlib import Path

from rosbags.typesys.store import Typestore

from seatwin.defaults import DEFAULT_ROS_DISTRO
from seatwin.recording.config import check_format
from seatwin.recording.storage.base import BagStorage
from seatwin.recording.storage.mcap import McapStorage
from seatwin.recording.storage.ros1 import Ros1Storage
from seatwin.recording.storage.sqlite import Sqlite3Storage

STORAGES: dict[str, type[BagStorage]] = {"mcap": McapStorage, "sqlite3": Sqlite3Storage, "ros1": Ros1Storage}
"""Format name → storage class."""

BAG_STEM = "recording"


def bag_path(run_dir: Path, fmt: str) -> Path:
    """Where a run directory keeps its bag for ``fmt``: ``recording/`` (rosbag2) or ``recording.bag``."""
    return Path(run_dir) / (f"{BAG_STEM}.bag" if fmt == "ros1" else BAG_STEM)


def open_storage(
    fmt: str,
    path: Path,
    store: Typestore,
    *,
    fsync: bool = False,
    ros_distro: str = DEFAULT_ROS_DISTRO,
    compression: str | None = None,
) -> BagStorage:
    """A new, opened bag of format ``fmt`` at ``path`` (a rosbag2 bag in ``ros_distro``'s metadata version), its
    chunks compressed with ``compression`` (None: the format's :data:`~seatwin.defaults.DEFAULT_COMPRESSION`)."""
    storage = STORAGES[check_format(fmt)](path, store, fsync=fsync, ros_distro=ros_distro, compression=compression)
    storage.open()
    return storage


__all__ = ["BAG_STEM", "STORAGES", "BagStorage", "McapStorage", "Ros1Storage", "Sqlite3Storage", "bag_path", "open_storage"]
