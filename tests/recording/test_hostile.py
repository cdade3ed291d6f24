"""Hostile bags (issue #20): forged PointCloud2 sizes, SQLite3 cells of the wrong type, decompression
bombs, CRC mismatches. Each is one InputError naming the file and the place, within bounded memory;
readers never modify their input. The files are built here, small."""

from __future__ import annotations

import bz2
import hashlib
import sqlite3
import stat
import struct
import subprocess
import sys
import tracemalloc
import zlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from lz4.frame import compress as lz4_compress
from recording_helpers import T0, write_run

from seatwin.errors import InputError
from seatwin.recording import ReadOptions, RecordingWriter, open_bag, unpack
from seatwin.recording.chunks import Inflated, inflate_pieces
from seatwin.recording.mcap_check import check_mcap
from seatwin.recording.messages import header
from seatwin.recording.pointcloud import FLOAT32, Field
from seatwin.recording.ros1_check import check_ros1

MIB = 1 << 20


def _read_all(path: Path, options: ReadOptions | None = None) -> int:
    with open_bag(path, options) as rec:
        n = sum(1 for _ in rec.messages())
        for c in rec.point_clouds():
            c.xyz()
        return n


def _fails(path: Path, *needles: str, options: ReadOptions | None = None, peak_mib: float = 64) -> str:
    tracemalloc.start()
    try:
        with pytest.raises(InputError) as info:
            _read_all(path, options)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    msg = str(info.value)
    assert "\n" not in msg and str(path) in msg, msg
    for n in needles:
        assert n in msg, msg
    assert peak < peak_mib * MIB, peak
    return msg


# ----------------------------------------------------------------------------- 1. PointCloud2 sizes
@pytest.mark.parametrize(
    ("field", "value", "needle"),
    [
        ("point_step", 2**31, "point_step 2147483648"),
        ("point_step", 2**32 - 1, "point_step"),
        ("width", 2**32 - 1, "width·point_step"),
        ("row_step", 2**32 - 1, "data has"),
        ("height", 2**31, "data has"),
    ],
)
def test_forged_point_cloud_sizes(tmp_path: Path, fmt: str, field: str, value: int, needle: str) -> None:
    run = tmp_path / "run"
    with RecordingWriter(run, fmt, seed=1) as w:
        T = w.store.types
        PF = T["sensor_msgs/msg/PointField"]
        sizes = {"point_step": 16, "width": 4, "height": 1, "row_step": 64, field: value}
        if field == "row_step":
            sizes["height"] = 2  # a second row starts row_step bytes in
        msg = T["sensor_msgs/msg/PointCloud2"](
            header=header(w.store, T0, "lidar"),
            fields=[PF(name=n, offset=4 * i, datatype=FLOAT32, count=1) for i, n in enumerate("xyz")],
            is_bigendian=False,
            data=np.zeros(64, np.uint8),
            is_dense=True,
            **sizes,
        )
        w.write("/lidar/points", T0, msg)
    msg = _fails(run, needle, "/lidar/points")
    assert "PointCloud2" not in msg.split(":")[0]  # the bag file leads the message, then the topic


@settings(max_examples=200, deadline=None, derandomize=True, database=None)
@given(
    point_step=st.integers(0, 2**64),
    width=st.integers(0, 2**64),
    height=st.integers(0, 2**32),
    row_step=st.integers(0, 2**64),
    size=st.integers(0, 256),
)
def test_unpack_any_sizes_reads_or_refuses(point_step: int, width: int, height: int, row_step: int, size: int) -> None:
    """Whatever the sizes say, unpack reads the points the data holds or raises InputError."""
    try:
        pts = unpack(np.zeros(size, np.uint8), [Field("x", 0, FLOAT32)], point_step, width, height, row_step)
    except InputError:
        return
    assert pts.size == width * height and pts.size * point_step <= max(size, 0) + (row_step or 0) * height


# ----------------------------------------------------------------------------- 2. SQLite3
def _sqlite_run(tmp_path: Path, sql: str, *args: object) -> Path:
    run = tmp_path / "run"
    write_run(run, "sqlite3", n_sweeps=2)
    db = next((run / "recording").glob("*.db3"))
    con = sqlite3.connect(db)
    con.execute(sql, args)
    con.commit()
    con.close()
    return run


@pytest.mark.parametrize(
    ("sql", "needles"),
    [
        ("UPDATE topics SET name = CAST(name AS BLOB) WHERE id = 2", ("table topics, column name, row id 2", "BLOB", "TEXT")),
        ("UPDATE topics SET type = X'07' WHERE id = 1", ("table topics, column type, row id 1", "BLOB")),
        ("UPDATE messages SET timestamp = 1.5e300 WHERE id = 3", ("table messages, column timestamp, row id 3", "REAL")),
        ("UPDATE messages SET timestamp = 'soon' WHERE id = 4", ("table messages, column timestamp, row id 4", "TEXT")),
        ("UPDATE messages SET data = 'text' WHERE id = 5", ("table messages, column data, row id 5", "TEXT", "BLOB")),
        ("UPDATE messages SET timestamp = -1 WHERE id = 6", ("row id 6", "negative timestamp -1")),
        ("UPDATE messages SET timestamp = -9223372036854775808 WHERE id = 6", ("negative timestamp -9223372036854775808",)),
        ("UPDATE messages SET topic_id = 99 WHERE id = 7", ("column topic_id, row id 7", "topic_id 99 names no row")),
        (
            "INSERT INTO messages (topic_id, timestamp, data) SELECT topic_id, timestamp, data FROM messages WHERE id = 8",
            ("duplicated row", "as row id 8", "table messages"),
        ),
        (
            "INSERT INTO topics (name, type, serialization_format, offered_qos_profiles, type_description_hash) "
            "SELECT name, type, serialization_format, offered_qos_profiles, type_description_hash FROM topics WHERE id = 1",
            ("duplicated row", "table topics"),
        ),
    ],
)
def test_sqlite_cells_refused(tmp_path: Path, sql: str, needles: tuple[str, ...]) -> None:
    run = _sqlite_run(tmp_path, sql)
    db = next((run / "recording").glob("*.db3"))
    msg = _fails(run, *needles)
    assert str(db) in msg


def test_sqlite_bad_cell_cli_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from seatwin.cli.main import run as cli

    run = _sqlite_run(tmp_path, "UPDATE topics SET name = CAST(name AS BLOB) WHERE id = 2")
    for argv in (["bag", "info", str(run)], ["track", str(run), "--out", str(tmp_path / "t.csv"), "--no-progress"]):
        assert cli(argv) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "column name" in err


_HOT_JOURNAL = """
import os, sqlite3, sys
con = sqlite3.connect(sys.argv[1], isolation_level=None)
con.execute("PRAGMA cache_size = 1")  # spill the uncommitted pages into the .db3
con.execute("BEGIN")
con.execute("UPDATE messages SET data = zeroblob(length(data))")
con.execute("DELETE FROM messages WHERE id % 2 = 0")
os._exit(0)  # killed: no commit, no rollback; the hot journal stays
"""


def _digest(folder: Path) -> dict[str, str]:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.iterdir())}


def test_sqlite_hot_journal_read_without_touching_the_input(tmp_path: Path) -> None:
    run = tmp_path / "run"
    write_run(run, "sqlite3", n_sweeps=4)
    with open_bag(run) as rec:
        want = [(t, ts, bytes(d)) for t, _, ts, d in rec.raw_messages()]
    bag = run / "recording"
    db = next(bag.glob("*.db3"))
    subprocess.run([sys.executable, "-c", _HOT_JOURNAL, str(db)], check=True)
    journal = db.with_name(db.name + "-journal")
    assert journal.stat().st_size > 0
    before = _digest(bag)
    modes = {p: p.stat().st_mode for p in [*bag.iterdir(), bag]}
    for p in modes:  # read-only media: no file and no folder may be written
        p.chmod(stat.S_IMODE(modes[p]) & ~0o222)
    try:
        with open_bag(run) as rec:
            assert rec.recovered and rec.complete is False
            got = [(t, ts, bytes(d)) for t, _, ts, d in rec.raw_messages()]
    finally:
        for p, m in modes.items():
            p.chmod(stat.S_IMODE(m))
    assert sorted(got) == sorted(want)  # the interrupted transaction is rolled back (in a copy)
    assert _digest(bag) == before  # the .db3 and its journal are as they were


def test_sqlite_read_only_folder_without_journal(tmp_path: Path) -> None:
    run = tmp_path / "run"
    write_run(run, "sqlite3", n_sweeps=2)
    bag = run / "recording"
    before = _digest(bag)
    bag.chmod(0o555)
    try:
        assert _read_all(run) > 0
    finally:
        bag.chmod(0o755)
    assert _digest(bag) == before and not any(p.name.endswith(("-journal", "-wal", "-shm")) for p in bag.iterdir())


# ----------------------------------------------------------------------------- 3. decompression bombs
def _zstd_bomb(size: int) -> bytes:
    from backports import zstd

    c = zstd.ZstdCompressor()
    zeros = bytes(MIB)
    return b"".join(c.compress(zeros) for _ in range(size // MIB)) + c.flush()


def _lz4_bomb(size: int) -> bytes:
    from lz4.frame import LZ4FrameCompressor

    c = LZ4FrameCompressor()
    zeros = bytes(MIB)
    return c.begin() + b"".join(c.compress(zeros) for _ in range(size // MIB)) + c.flush()


def _bz2_bomb(size: int) -> bytes:
    c = bz2.BZ2Compressor(1)
    zeros = bytes(MIB)
    return b"".join(c.compress(zeros) for _ in range(size // MIB)) + c.flush()


def _record(op: int, body: bytes) -> bytes:
    return struct.pack("<BQ", op, len(body)) + body


def _mcap_with_chunk(path: Path, compression: str, records: bytes, declared: int, crc: int = 0) -> Path:
    """A finished MCAP (header, one chunk, data end, footer without summary)."""
    comp = compression.encode()
    chunk = struct.pack("<QQQI", 0, 0, declared, crc) + struct.pack("<I", len(comp)) + comp + struct.pack("<Q", len(records))
    head = _record(0x01, struct.pack("<I", 4) + b"ros2" + struct.pack("<I", 0))
    body = b"\x89MCAP0\r\n" + head + _record(0x06, chunk + records) + _record(0x0F, struct.pack("<I", 0))
    path.write_bytes(body + _record(0x02, struct.pack("<QQI", 0, 0, 0)) + b"\x89MCAP0\r\n")
    return path


@pytest.mark.parametrize(("kind", "bomb"), [("zstd", _zstd_bomb), ("lz4", _lz4_bomb)])
def test_mcap_chunk_inflating_beyond_its_size(tmp_path: Path, kind: str, bomb) -> None:
    path = _mcap_with_chunk(tmp_path / "bomb.mcap", kind, bomb(64 * MIB), declared=4096)
    assert path.stat().st_size < 600_000
    msg = _fails(path, "Chunk at byte 29", f"({kind})", "inflates beyond the 4096 bytes it declares", peak_mib=8)
    assert "corrupt MCAP" in msg


def test_mcap_one_gib_bomb_refused_in_bounded_memory(tmp_path: Path) -> None:
    """The issue's case: a ~33 KB MCAP whose zstd chunk inflates to 1 GiB, declared honestly or not."""
    data = _zstd_bomb(1024 * MIB)
    for declared in (100, 1024 * MIB):
        path = _mcap_with_chunk(tmp_path / f"bomb{declared}.mcap", "zstd", data, declared=declared)
        assert path.stat().st_size < 100_000
        _fails(path, "Chunk at byte 29", peak_mib=8)


def test_mcap_budgets_are_settings(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    records = _record(0x05, bytes(3 * MIB))  # an honest chunk of 3 MiB
    path = _mcap_with_chunk(tmp_path / "a.mcap", "zstd", _zstd_c(records), declared=len(records))
    check_mcap(path)  # within the default budgets
    with pytest.raises(InputError, match=r"uncompressed_size \d+ exceeds 2097152"):
        check_mcap(path, ReadOptions(chunk_bytes=2 * MIB))
    monkeypatch.setenv("SEATWIN_MAX_CHUNK_BYTES", str(2 * MIB))
    with pytest.raises(InputError, match="exceeds 2097152"):
        check_mcap(path)
    monkeypatch.delenv("SEATWIN_MAX_CHUNK_BYTES")
    monkeypatch.setenv("SEATWIN_MAX_BAG_BYTES", str(MIB))
    with pytest.raises(InputError, match="over the per-file budget of 1048576"):
        check_mcap(path)
    monkeypatch.setenv("SEATWIN_MAX_BAG_BYTES", "lots")
    with pytest.raises(InputError, match="SEATWIN_MAX_BAG_BYTES"):
        ReadOptions.from_env()


def _zstd_c(data: bytes) -> bytes:
    from backports import zstd

    return zstd.compress(data)


def test_mcap_chunk_shorter_than_declared_and_corrupt(tmp_path: Path) -> None:
    records = _record(0x05, bytes(1000))
    short = _mcap_with_chunk(tmp_path / "short.mcap", "lz4", lz4_compress(records), declared=5000)
    _fails(short, "inflates to 1009 bytes, but declares 5000")
    junk = _mcap_with_chunk(tmp_path / "junk.mcap", "zstd", b"\x28\xb5\x2f\xfd" + bytes(50), declared=1000)
    _fails(junk, "Chunk at byte 29 (zstd)")


def _ros1_bag(path: Path, compression: str, data: bytes, size: int) -> Path:
    """An unindexed ROS 1 bag: the version line, a file header record, one chunk."""

    def rec(fields: dict[str, bytes], body: bytes) -> bytes:
        hdr = b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k.encode() + b"=" + v for k, v in fields.items())
        return struct.pack("<I", len(hdr)) + hdr + struct.pack("<I", len(body)) + body

    fh = rec({"op": b"\x03", "index_pos": bytes(8), "conn_count": bytes(4), "chunk_count": bytes(4)}, b" " * 4000)
    chunk = rec({"op": b"\x05", "compression": compression.encode(), "size": struct.pack("<I", size)}, data)
    path.write_bytes(b"#ROSBAG V2.0\n" + fh + chunk)
    return path


@pytest.mark.parametrize(("kind", "bomb"), [("bz2", _bz2_bomb), ("lz4", _lz4_bomb)])
def test_ros1_chunk_inflating_beyond_its_size(tmp_path: Path, kind: str, bomb) -> None:
    path = _ros1_bag(tmp_path / "bomb.bag", kind, bomb(64 * MIB), size=10)
    at = path.read_bytes().index(b"compression=") - 16  # the record: header length, op field (length, "op=\x05"), field length
    msg = _fails(path, f"chunk at byte {at} ({kind})", "inflates beyond the 10 bytes it declares", peak_mib=8)
    assert "corrupt ROS 1 bag" in msg


def test_ros1_chunk_over_budget_and_unknown_compression(tmp_path: Path) -> None:
    path = _ros1_bag(tmp_path / "big.bag", "bz2", _bz2_bomb(4 * MIB), size=4 * MIB)
    check_ros1(path)  # honest and within the default budget
    with pytest.raises(InputError, match="over the per-chunk budget of 1048576"):
        check_ros1(path, ReadOptions(chunk_bytes=MIB))
    with pytest.raises(InputError, match="over the per-file budget"):
        check_ros1(path, ReadOptions(total_bytes=MIB))
    _fails(_ros1_bag(tmp_path / "x.bag", "xz", b"abc", size=3), "unknown compression 'xz'")


@pytest.mark.parametrize("kind", ["bz2", "lz4"])
def test_ros1_compressed_bags_still_read(tmp_path: Path, kind: str) -> None:
    from rosbags.rosbag1 import Writer

    from seatwin.recording.messages import typestore

    store = typestore("ros1")
    path = tmp_path / "c.bag"
    w = Writer(path)
    w.set_compression(Writer.CompressionFormat.BZ2 if kind == "bz2" else Writer.CompressionFormat.LZ4)
    with w:
        conn = w.add_connection("/n", "std_msgs/msg/String", typestore=store)
        for k in range(50):
            w.write(conn, 1000 + k, store.serialize_ros1(store.types["std_msgs/msg/String"](data=f"m{k}" * 100), conn.msgtype))
    check_ros1(path)
    assert _read_all(path) == 50


def test_mcap_zstd_bag_written_by_rosbags_reads(tmp_path: Path) -> None:
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.rosbag2.enums import CompressionFormat, CompressionMode

    from seatwin.recording.messages import typestore

    store = typestore("mcap")
    w = Writer(tmp_path / "z", version=9, storage_plugin=StoragePlugin.MCAP)
    w.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    with w:
        conn = w.add_connection("/n", "std_msgs/msg/String", typestore=store)
        for k in range(50):
            w.write(conn, 1000 + k, store.serialize_cdr(store.types["std_msgs/msg/String"](data="x" * 5000), conn.msgtype))
    assert _read_all(tmp_path / "z") == 50


@settings(max_examples=60, deadline=None, derandomize=True, database=None)
@given(payload=st.binary(max_size=3000), declared=st.integers(0, 1 << 40), kind=st.sampled_from(["bz2", "lz4", "zstd"]))
def test_inflate_never_exceeds_what_is_declared(payload: bytes, declared: int, kind: str) -> None:
    """Honest data inflates to itself; any declared size other than the true one is refused."""
    packed = {"bz2": bz2.compress, "zstd": _zstd_c, "lz4": lz4_compress}[kind](payload)
    assert b"".join(inflate_pieces(kind, packed, len(payload), 1 << 30)) == payload
    if declared != len(payload):
        with pytest.raises(Inflated):
            b"".join(inflate_pieces(kind, packed, declared, 1 << 30))


# ----------------------------------------------------------------------------- 4. CRCs
def _mcap_run(tmp_path: Path, compression: str = "none") -> tuple[Path, Path]:
    run = tmp_path / "run"
    write_run(run, "mcap", n_sweeps=35, compression=compression)  # a flush (a closed chunk) every second of recorded time
    return run, next((run / "recording").glob("*.mcap"))


def _inflate(kind: str, payload: bytes) -> bytes:
    if kind == "":
        return payload
    if kind == "lz4":
        from lz4.frame import decompress

        return decompress(payload)
    import zstandard

    return zstandard.ZstdDecompressor().decompress(payload)  # needs the content size in the frame header


def _chunks(data: bytes) -> list[int]:
    out, pos = [], 8
    while True:
        op, length = struct.unpack_from("<BQ", data, pos)
        if op == 0x06:
            out.append(pos)
        if op in (0x02, 0x0F):
            return out
        pos += 9 + length


@pytest.mark.parametrize("compression", ["none", "zstd", "lz4"])
def test_written_crcs_are_right(tmp_path: Path, compression: str) -> None:
    from mcap.reader import make_reader

    run, mcap = _mcap_run(tmp_path, compression)
    data = mcap.read_bytes()
    chunks = _chunks(data)
    assert len(chunks) >= 3
    for at in chunks:
        usize, crc = struct.unpack_from("<QI", data, at + 9 + 16)
        (clen,) = struct.unpack_from("<I", data, at + 9 + 28)
        kind = data[at + 9 + 32 : at + 9 + 32 + clen].decode()
        assert kind == ("" if compression == "none" else compression)
        (rlen,) = struct.unpack_from("<Q", data, at + 9 + 32 + clen)
        start = at + 9 + 32 + clen + 8
        records = _inflate(kind, data[start : start + rlen])
        assert len(records) == usize and crc != 0 and crc == zlib.crc32(records)
    assert check_mcap(mcap).bad_crc == 0
    with mcap.open("rb") as f:  # the mcap library's own reader, every chunk's CRC checked
        reader = make_reader(f, validate_crcs=True)
        got = [(ch.topic, m.log_time, bytes(m.data)) for _, ch, m in reader.iter_messages(log_time_order=False)]
    with open_bag(run) as rec:
        assert got == [(t, ts, bytes(d)) for t, _, ts, d in rec.raw_messages()]


@pytest.mark.parametrize("compression", ["zstd", "lz4"])
def test_flipped_byte_in_a_compressed_chunk_is_caught(tmp_path: Path, compression: str) -> None:
    run, mcap = _mcap_run(tmp_path, compression)
    data = bytearray(mcap.read_bytes())
    at = _chunks(bytes(data))[1]
    (clen,) = struct.unpack_from("<I", data, at + 9 + 28)
    (rlen,) = struct.unpack_from("<Q", data, at + 9 + 32 + clen)
    data[at + 9 + 32 + clen + 8 + rlen // 2] ^= 0x10  # inside the compressed records
    mcap.write_bytes(bytes(data))
    _fails(run, "corrupt MCAP", f"Chunk at byte {at}")


def test_flipped_byte_in_a_chunk_is_caught(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from seatwin.cli.main import run as cli

    run, mcap = _mcap_run(tmp_path)
    data = bytearray(mcap.read_bytes())
    at = _chunks(bytes(data))[1]
    with open_bag(run) as rec:
        want = sum(1 for _ in rec.raw_messages())
    data[at + 9 + 60] ^= 0x10  # inside the chunk's records: a message's bytes
    mcap.write_bytes(bytes(data))
    _fails(run, f"Chunk at byte {at}", "CRC-32", "does not match")
    with open_bag(run, ReadOptions(ignore_crc=True)) as rec:
        assert rec.bad_crc == 2  # the chunk and the data section
        assert sum(1 for _ in rec.raw_messages()) == want
    assert cli(["bag", "info", str(run)]) == 2
    assert "does not match" in capsys.readouterr().err
    assert cli(["bag", "info", "--ignore-crc", str(run)]) == 0
    err = capsys.readouterr().err
    assert "2 CRC mismatch(es) ignored" in err
    assert cli(["track", str(run), "--out", str(tmp_path / "t.csv"), "--no-progress", "--ignore-crc", "--sensors", "lidar"]) == 0
    assert "2 CRC mismatch(es) ignored" in capsys.readouterr().err


def test_old_bags_without_crcs_still_read(tmp_path: Path) -> None:
    run, mcap = _mcap_run(tmp_path)
    data = bytearray(mcap.read_bytes())
    pos = 8
    while True:  # CRC 0 means "not written" (MCAP spec): bags written before CRCs
        op, length = struct.unpack_from("<BQ", data, pos)
        if op == 0x06:
            struct.pack_into("<I", data, pos + 9 + 24, 0)
        elif op == 0x0F:
            struct.pack_into("<I", data, pos + 9, 0)
            break
        pos += 9 + length
    mcap.write_bytes(bytes(data))
    assert check_mcap(mcap).bad_crc == 0 and _read_all(run) > 0


def test_env_and_options_validated() -> None:
    from seatwin.errors import ParameterError

    with pytest.raises(ParameterError, match="chunk_bytes"):
        ReadOptions(chunk_bytes=0)
    with pytest.raises(ParameterError, match="total_bytes"):
        ReadOptions(total_bytes=-1)
