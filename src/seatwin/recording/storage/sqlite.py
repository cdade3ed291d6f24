"""SQLite3 (rosbag2 storage ``sqlite3``): rosbags' SQLite3 storage writer; a flush is a commit.

Commits need not wait for the disk (``PRAGMA synchronous=OFF`` unless ``fsync``): a killed
process loses nothing the kernel holds, and the on-disk rollback journal (kept) still undoes an
interrupted transaction.

Compression is rosbag2's own (``rosbag2_compression``, zstd level 1 as its ``rosbag2_compression_zstd``
plugin), written as ``ros2 bag record --compression-format zstd`` writes it:

* ``zstd`` (``--compression-mode message``): each message's CDR bytes are one zstd frame in the
  ``messages`` table; ``metadata.yaml`` says ``compression_format: zstd``, ``compression_mode: MESSAGE``.
  A killed run leaves a ``.db3`` of compressed messages (readable up to its last commit).
* ``zstd-file`` (``--compression-mode file``): the ``.db3`` is written uncompressed, and on close
  compressed to ``<name>.db3.zstd`` (the ``.db3`` removed once ``metadata.yaml`` is written);
  ``relative_file_paths`` names the ``.zstd`` file, ``files[].path`` keeps the ``.db3`` name (rosbag2's
  SequentialCompressionWriter changes only the former), ``compression_mode: FILE``. A killed run leaves
  the plain ``.db3``.

Every metadata version seatwin writes (Humble's 5 and later) has both fields (since version 3).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

from rosbags.interfaces import Connection
from rosbags.rosbag2.storage_sqlite3 import Sqlite3Writer

from seatwin.recording.storage.compression import ChunkCompressor, compress_file
from seatwin.recording.storage.rosbag2 import Rosbag2Storage

MODES = {"none": "", "zstd": "MESSAGE", "zstd-file": "FILE"}
"""seatwin's compression name → rosbag2's ``compression_mode``."""


class Sqlite3Storage(Rosbag2Storage):
    """A rosbag2 directory with one ``.db3`` file (or, with ``zstd-file``, one ``.db3.zstd``)."""

    format = "sqlite3"
    plugin = Sqlite3Writer

    def open(self) -> None:
        self.compression_mode = MODES[self.compression]
        self.compression_format = "zstd" if self.compression_mode else ""
        self._zstd = ChunkCompressor("zstd") if self.compression_mode == "MESSAGE" else None
        super().open()
        self._db = self.writer.path
        if not self.fsync:
            self.writer.conn.execute("PRAGMA synchronous=OFF")
        self.writer.conn.execute("UPDATE schema SET ros_distro = ?", (self.ros_distro,))  # rosbags writes 'rosbags'

    def _write_records(self, items: Sequence[tuple[Connection, bytes | memoryview]], timestamp: int) -> None:
        z = self._zstd
        if z is None:
            super()._write_records(items, timestamp)
            return
        write = self.writer.write
        for connection, data in items:
            write(connection, timestamp, z.compress((data,), len(data)))

    def metadata(self) -> dict[str, Any]:
        info = super().metadata()
        if self.compression_mode == "FILE":
            info["relative_file_paths"] = [p + ".zstd" for p in info["relative_file_paths"]]
        return info

    def _finish_files(self) -> None:
        if self.compression_mode != "FILE":
            return
        dst = self._db.with_name(self._db.name + ".zstd")
        tmp = dst.with_name(dst.name + ".tmp")
        try:
            compress_file(self._db, tmp, fsync=self.fsync)
            os.replace(tmp, dst)
        except BaseException:
            tmp.unlink(missing_ok=True)  # the .db3 stays, readable
            raise

    def close(self) -> None:
        """Finish the bag; in file mode the plain ``.db3`` is removed only once ``metadata.yaml`` names the
        ``.zstd`` (a process killed before leaves a ``.db3`` the reader recovers)."""
        super().close()
        if self.compression_mode == "FILE":
            for name in (self._db.name, self._db.name + "-journal", self._db.name + "-wal"):
                self._db.with_name(name).unlink(missing_ok=True)

    def flush(self) -> None:
        self.writer.conn.commit()
