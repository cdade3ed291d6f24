"""The interface every bag format implements: open, add a connection, write serialised messages, flush, close."""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Sequence
from pathlib import Path
from typing import ClassVar

from rosbags.interfaces import Connection
from rosbags.typesys.store import Typestore

from seatwin.defaults import DEFAULT_ROS_DISTRO
from seatwin.recording.config import check_compression, check_ros_distro


class BagStorage(ABC):
    """One bag format's file(s): connections and serialised messages in, a finished bag out.

    ``path`` is the bag (a rosbag2 directory or a ROS 1 ``.bag`` file) and must not exist yet;
    ``store`` gives the message definitions written with each connection. Messages arrive
    serialised in the format's encoding (:attr:`ros1`: ROS 1, else CDR). :meth:`flush` hands
    everything written so far to the operating system, so a process killed after it leaves a bag
    readable up to there; ``fsync`` makes it reach the disk as well (power loss; slower).
    ``compression`` is one of the format's :data:`~seatwin.defaults.COMPRESSIONS` (None: its default).
    """

    format: ClassVar[str]
    """``mcap``, ``sqlite3`` or ``ros1``."""
    ros1: ClassVar[bool] = False
    """Messages are ROS 1 serialised (else CDR)."""

    def __init__(
        self,
        path: Path,
        store: Typestore,
        *,
        fsync: bool = False,
        ros_distro: str = DEFAULT_ROS_DISTRO,
        compression: str | None = None,
    ) -> None:
        self.path = Path(path)
        self.compression = check_compression(self.format, compression)
        """How the bag's chunks are compressed: ``zstd``, ``lz4``, ``bz2`` or ``none``."""
        self.store = store
        self.fsync = fsync
        self.ros_distro = check_ros_distro(ros_distro)
        """The ROS 2 distribution a rosbag2 bag is written for (its metadata version); ROS 1 bags ignore it."""

    @abstractmethod
    def open(self) -> None:
        """Create the bag's file(s); an existing bag is never overwritten."""

    @abstractmethod
    def add_connection(self, topic: str, msgtype: str, *, latched: bool = False) -> Connection:
        """Register ``topic`` carrying ``msgtype``; ``latched``: transient-local / latching (``/tf_static``)."""

    @abstractmethod
    def write(self, connection: Connection, timestamp: int, data: bytes | memoryview) -> None:
        """Write one serialised message with log time ``timestamp`` (ns)."""

    def write_many(self, items: Sequence[tuple[Connection, bytes | memoryview]], timestamp: int) -> None:
        """Write several serialised messages, all with log time ``timestamp`` (ns), in order; the same
        bag as :meth:`write` one by one (a format may do it with less overhead)."""
        for connection, data in items:
            self.write(connection, timestamp, data)

    @abstractmethod
    def flush(self) -> None:
        """Hand everything written so far to the operating system (and the disk with ``fsync``)."""

    @abstractmethod
    def close(self) -> None:
        """Finish the bag (index, summary, metadata)."""

    @abstractmethod
    def abort(self) -> None:
        """Release the file(s) without finishing them: the bag stays readable up to its last flush."""
