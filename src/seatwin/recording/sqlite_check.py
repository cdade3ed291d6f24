"""Read-only access to a rosbag2 SQLite3 file, and a check of its cells before rosbags reads them.

Readers never modify an input. :func:`readable_db` gives the file the readers open: the
``.db3`` itself when it has no hot ``-journal`` or ``-wal`` beside it (opened with the URI
``mode=ro&immutable=1``, so nothing is written and read-only media work), else a copy of the
database and its journal in a temporary folder, where SQLite rolls the interrupted transaction
back (a killed run) — the original files are left exactly as they are.

:func:`check_sqlite` refuses what rosbags would misread (SQLite stores any type in any column):

* a ``topics`` cell of the wrong type (``id`` not INTEGER; ``name``, ``type``,
  ``serialization_format``, ``offered_qos_profiles`` not TEXT);
* a ``messages`` cell of the wrong type (``id``, ``topic_id``, ``timestamp`` not INTEGER,
  ``data`` not BLOB), a negative ``timestamp``, a ``topic_id`` no topic has (rosbags would drop
  the message silently);
* duplicated rows: two topics with the same name and type, or two messages with the same topic,
  timestamp and bytes.

Each is an :class:`InputError` naming the file, the table, the column and the row id.
"""

from __future__ import annotations

import shutil
import sqlite3
import tempfile
from pathlib import Path

from seatwin.errors import InputError

TOPIC_TYPES = {"id": "integer", "name": "text", "type": "text", "serialization_format": "text", "offered_qos_profiles": "text"}
MESSAGE_TYPES = {"id": "integer", "topic_id": "integer", "timestamp": "integer", "data": "blob"}
_SIDE_FILES = ("-journal", "-wal")


def hot_side_files(db: Path) -> list[Path]:
    """The non-empty ``-journal`` / ``-wal`` files beside ``db`` (an interrupted or unfinished write)."""
    out = []
    for suffix in _SIDE_FILES:
        side = db.with_name(db.name + suffix)
        try:
            if side.is_file() and side.stat().st_size > 0:
                out.append(side)
        except OSError:
            continue
    return out


class ReadableDb:
    """The database file to read for ``db`` (see the module docstring); close it to remove a copy."""

    def __init__(self, db: Path) -> None:
        self.original = db
        self._tmp: tempfile.TemporaryDirectory[str] | None = None
        side = hot_side_files(db)
        self.copied = bool(side)
        if not side:
            self.path = db
            return
        self._tmp = tempfile.TemporaryDirectory(prefix="seatwin-db3-")
        self.path = Path(self._tmp.name) / db.name
        try:
            shutil.copyfile(db, self.path)
            for s in side:
                shutil.copyfile(s, self.path.with_name(self.path.name + s.name[len(db.name) :]))
            con = sqlite3.connect(self.path)  # the copy: SQLite rolls the hot journal back here
            try:
                con.execute("SELECT count(*) FROM sqlite_master").fetchone()
            finally:
                con.close()
        except OSError as exc:
            self.close()
            raise InputError(db, f"cannot copy the interrupted SQLite3 bag to read it: {exc.strerror or exc}") from None
        except sqlite3.Error as exc:
            self.close()
            raise InputError(db, f"cannot roll back the interrupted SQLite transaction: {' '.join(str(exc).split())}") from None

    def close(self) -> None:
        if self._tmp is not None:
            self._tmp.cleanup()
            self._tmp = None


def connect_ro(db: Path) -> sqlite3.Connection:
    """A read-only connection that never writes (no journal rollback, no lock files)."""
    from urllib.parse import quote

    return sqlite3.connect(f"file:{quote(str(db.resolve()))}?mode=ro&immutable=1", uri=True)


def _fail(source: Path, table: str, column: str, row: object, what: str) -> InputError:
    return InputError(source, what, where=f"table {table}, column {column}, row id {row}")


def _columns(con: sqlite3.Connection, table: str) -> set[str]:
    return {r[1] for r in con.execute(f"PRAGMA table_info({table})")}


def check_sqlite(db: Path, source: Path | None = None) -> None:
    """Check ``db``'s ``topics`` and ``messages`` cells (module docstring); errors name ``source`` (default ``db``)."""
    src = source or db
    try:
        con = connect_ro(db)
    except sqlite3.Error as exc:
        raise InputError(src, f"cannot open SQLite3 bag: {' '.join(str(exc).split())}") from None
    try:
        _check(con, src)
    except sqlite3.Error as exc:
        raise InputError(src, f"unreadable SQLite3 bag: {type(exc).__name__}: {' '.join(str(exc).split())}") from None
    finally:
        con.close()


def _check(con: sqlite3.Connection, src: Path) -> None:
    tables = {r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
    if "topics" not in tables or "messages" not in tables:
        raise InputError(src, f"not a rosbag2 SQLite3 bag: expected tables topics and messages, found {sorted(tables)}")
    for table, want in (("topics", TOPIC_TYPES), ("messages", MESSAGE_TYPES)):
        cols = _columns(con, table)
        for col, typ in want.items():
            if col not in cols:
                if col in ("offered_qos_profiles", "serialization_format"):
                    continue  # older schema versions
                raise InputError(src, f"not a rosbag2 SQLite3 bag: table {table} has no column {col}")
            row = con.execute(f"SELECT rowid, typeof({col}) FROM {table} WHERE typeof({col}) != ? LIMIT 1", (typ,)).fetchone()
            if row is not None:
                raise _fail(src, table, col, row[0], f"a cell of type {row[1].upper()}, expected {typ.upper()}")
    row = con.execute("SELECT id, timestamp FROM messages WHERE timestamp < 0 LIMIT 1").fetchone()
    if row is not None:
        raise _fail(src, "messages", "timestamp", row[0], f"negative timestamp {row[1]} ns; expected ≥ 0")
    row = con.execute(
        "SELECT m.id, m.topic_id FROM messages m LEFT JOIN topics t ON m.topic_id = t.id WHERE t.id IS NULL LIMIT 1"
    ).fetchone()
    if row is not None:
        raise _fail(src, "messages", "topic_id", row[0], f"topic_id {row[1]} names no row of table topics")
    row = con.execute("SELECT min(id), max(id), name FROM topics GROUP BY name, type HAVING count(*) > 1 LIMIT 1").fetchone()
    if row is not None:
        raise _fail(src, "topics", "name", row[1], f"duplicated row: topic {row[2]!r} is also row id {row[0]}")
    # candidates first (topic and time), then their bytes: cheap when, as in any sane bag, there are none
    for topic_id, ts in con.execute(
        "SELECT topic_id, timestamp FROM messages GROUP BY topic_id, timestamp HAVING count(*) > 1"
    ).fetchall():
        row = con.execute(
            "SELECT min(id), max(id) FROM messages WHERE topic_id = ? AND timestamp = ? GROUP BY data HAVING count(*) > 1",
            (topic_id, ts),
        ).fetchone()
        if row is not None:
            what = f"duplicated row: the same message (topic_id {topic_id}, timestamp {ts}) as row id {row[0]}"
            raise _fail(src, "messages", "data", row[1], what)
