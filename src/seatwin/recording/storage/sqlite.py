"""SQLite3 (rosbag2 storage ``sqlite3``): rosbags' SQLite3 storage writer; a flush is a commit.

Commits need not wait for the disk (``PRAGMA synchronous=OFF`` unless ``fsync``): a killed
process loses nothing the kernel holds, and the on-disk rollback journal (kept) still undoes an
interrupted transaction.
"""

from __future__ import annotations

from rosbags.rosbag2.storage_sqlite3 import Sqlite3Writer

from seatwin.recording.storage.rosbag2 import Rosbag2Storage


class Sqlite3Storage(Rosbag2Storage):
    """A rosbag2 directory with one ``.db3`` file."""

    format = "sqlite3"
    plugin = Sqlite3Writer

    def open(self) -> None:
        super().open()
        if not self.fsync:
            self.writer.conn.execute("PRAGMA synchronous=OFF")
        self.writer.conn.execute("UPDATE schema SET ros_distro = ?", (self.ros_distro,))  # rosbags writes 'rosbags'

    def flush(self) -> None:
        self.writer.conn.commit()
