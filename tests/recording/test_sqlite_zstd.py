"""rosbag2's zstd compression of SQLite3 bags (issue #23): written as rosbag2 writes it, read within the budgets.

Message mode (``--compression zstd``) and file mode (``zstd-file``): metadata fields and file names as rosbag2's
SequentialCompressionWriter writes them, for every distro's metadata version; rosbags' own reader reads them;
hostile frames (bombs with and without a declared size, corrupt, trailing bytes, not zstd) are one InputError
naming the bag, the topic and the time, and a bomb of a file one naming the file; the input is never written.
The bags are built here, small.
"""

from __future__ import annotations

import hashlib
import shutil
import sqlite3
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from recording_helpers import T0

from seatwin.defaults import ROS_DISTROS
from seatwin.errors import InputError
from seatwin.recording import RecordingWriter, open_bag
from seatwin.recording import messages as M
from seatwin.recording.chunks import MIB, ReadOptions
from seatwin.recording.storage.compression import zstd_module

zstd = zstd_module()
TOPIC = "/chatter"
STRING = "std_msgs/msg/String"


def _cdr(text: str) -> bytes:
    """A std_msgs/String in CDR (little endian)."""
    raw = text.encode() + b"\x00"
    return b"\x00\x01\x00\x00" + len(raw).to_bytes(4, "little") + raw + bytes(-len(raw) % 4)


def _write(run: Path, compression: str, n: int = 6, ros_distro: str = "humble") -> Path:
    with RecordingWriter(run, "sqlite3", compression=compression, ros_distro=ros_distro) as w:
        for k in range(n):
            w.write_raw(TOPIC, STRING, T0 + k, _cdr(f"hello {k} " * (k + 1)))
    return run / "recording"


def _meta(bag: Path) -> dict:
    return yaml.safe_load((bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]


def _raw(path: Path, options: ReadOptions | None = None) -> list[tuple[str, str, int, bytes]]:
    with open_bag(path, options) as rec:
        return [(t, ty, ts, bytes(d)) for t, ty, ts, d in rec.raw_messages()]


def _digest(folder: Path) -> dict[str, str]:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("distro", sorted(ROS_DISTROS))
@pytest.mark.parametrize(("compression", "mode"), [("zstd", "MESSAGE"), ("zstd-file", "FILE")])
def test_metadata_and_files_as_rosbag2_writes_them(tmp_path: Path, distro: str, compression: str, mode: str) -> None:
    bag = _write(tmp_path / "run", compression, ros_distro=distro)
    info = _meta(bag)
    assert info["version"] == ROS_DISTROS[distro] >= 3  # compression fields exist since version 3
    assert (info["compression_format"], info["compression_mode"]) == ("zstd", mode)
    stored = "recording.db3.zstd" if mode == "FILE" else "recording.db3"
    assert info["relative_file_paths"] == [stored]
    assert [f["path"] for f in info["files"]] == ["recording.db3"]  # rosbag2 renames only relative_file_paths
    assert sorted(p.name for p in bag.iterdir()) == sorted(["metadata.yaml", stored])
    if mode == "FILE":
        data = (bag / stored).read_bytes()
        assert data[:4] == b"\x28\xb5\x2f\xfd" and zstd.get_frame_size(data) == len(data)
        assert zstd.get_frame_info(data).decompressed_size == len(zstd.decompress(data))
    else:
        con = sqlite3.connect(f"file:{bag / stored}?mode=ro", uri=True)
        rows = [bytes(r[0]) for r in con.execute("SELECT data FROM messages ORDER BY id")]
        con.close()
        assert [zstd.decompress(r) for r in rows] == [_cdr(f"hello {k} " * (k + 1)) for k in range(6)]
        assert all(zstd.get_frame_info(r).decompressed_size is not None for r in rows)  # as ZSTD_compressCCtx


@pytest.mark.parametrize("compression", ["zstd", "zstd-file"])
def test_round_trip_seatwin_and_rosbags_read_the_same_bytes(tmp_path: Path, compression: str) -> None:
    from rosbags.rosbag2 import Reader

    plain = _raw(_write(tmp_path / "plain", "none"))
    bag = _write(tmp_path / "run", compression)
    before = _digest(bag)
    assert _raw(tmp_path / "run") == _raw(bag) == plain
    with Reader(bag) as r:
        assert r.compression_mode == ("file" if compression == "zstd-file" else "message")
        assert [(c.topic, c.msgtype, ts, bytes(d)) for c, ts, d in r.messages()] == plain
    with open_bag(tmp_path / "run") as rec:
        assert [m.msg.data for m in rec.messages()] == [f"hello {k} " * (k + 1) for k in range(6)]
    assert _digest(bag) == before  # never written, and (file mode) inflated elsewhere


def test_killed_message_compressed_run_is_read_to_its_last_commit(tmp_path: Path) -> None:
    """No metadata.yaml (the writer never closed): the frames are recognised by zstd's magic number."""
    w = RecordingWriter(tmp_path / "run", "sqlite3", compression="zstd")
    for k in range(4):
        w.write_raw(TOPIC, STRING, T0 + k, _cdr(f"m{k}"))
    w.flush()
    w.storage.abort()  # as a SIGKILL: the .db3 so far, no metadata.yaml
    bag = tmp_path / "run" / "recording"
    assert not (bag / "metadata.yaml").exists()
    with open_bag(bag) as rec:
        assert rec.recovered and [m.msg.data for m in rec.messages()] == [f"m{k}" for k in range(4)]


def test_killed_compressed_run_is_repaired_compressed(tmp_path: Path) -> None:
    from seatwin.recording.repair import repair_bag

    w = RecordingWriter(tmp_path / "run", "sqlite3", compression="zstd")
    for k in range(3):
        w.write_raw(TOPIC, STRING, T0 + k, _cdr(f"m{k}"))
    w.flush()
    w.storage.abort()
    res = repair_bag(tmp_path / "run", tmp_path / "fixed")  # the manifest's compression, unless told
    assert _meta(res.bag)["compression_mode"] == "MESSAGE"
    assert _raw(tmp_path / "fixed") == _raw(tmp_path / "run")


def test_file_mode_failing_at_its_metadata_leaves_the_plain_db3(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The .db3 is removed only after metadata.yaml names the .zstd: a close that fails in between (a full disk)
    leaves a bag the reader recovers, and the run says it did not complete."""
    import seatwin.recording.storage.rosbag2 as r2

    def full(*_: object) -> None:
        raise OSError(28, "No space left on device")

    w = RecordingWriter(tmp_path / "run", "sqlite3", compression="zstd-file")
    for k in range(3):
        w.write_raw(TOPIC, STRING, T0 + k, _cdr(f"m{k}"))
    monkeypatch.setattr(r2.os, "replace", full)
    with pytest.raises(InputError, match="No space left"):
        w.close()
    monkeypatch.undo()
    bag = tmp_path / "run" / "recording"
    assert (bag / "recording.db3").is_file() and not (bag / "metadata.yaml").exists()
    with open_bag(tmp_path / "run") as rec:
        assert rec.recovered and not rec.complete
        assert [m.msg.data for m in rec.messages()] == ["m0", "m1", "m2"]


def test_a_db3_zstd_file_opens_through_its_folder(tmp_path: Path) -> None:
    bag = _write(tmp_path / "run", "zstd-file")
    assert _raw(bag / "recording.db3.zstd") == _raw(bag)


@pytest.mark.parametrize(("compression", "label"), [("zstd", "zstd per message"), ("zstd-file", "zstd file")])
def test_bag_info_names_a_foreign_bags_compression(tmp_path: Path, compression: str, label: str) -> None:
    from seatwin.recording.info import bag_info, format_info

    foreign = tmp_path / "foreign"
    shutil.copytree(_write(tmp_path / "run", compression), foreign)  # no seatwin manifest beside it
    info = bag_info(foreign)
    assert info["compression"] == compression and info["message_count"] == 6 and info["complete"] is None
    assert f"({label})" in format_info(info)


def test_ground_truth_of_a_file_compressed_run(tmp_path: Path) -> None:
    """evaluate/report take ground truth from a recording path; a ``.db3.zstd`` file is one."""
    from recording_helpers import write_run

    from seatwin.evaluation.truth import load_truth

    write_run(tmp_path / "run", "sqlite3", compression="zstd-file")
    db = tmp_path / "run" / "recording" / "recording.db3.zstd"
    assert db.is_file()
    want = load_truth(tmp_path / "run")
    got = load_truth(db)
    assert sorted(got.targets) == sorted(want.targets) and got.targets
    for name, track in want.targets.items():
        assert list(got.targets[name].time) == list(track.time) and list(got.targets[name].north) == list(track.north)


def test_convert_between_compressions_and_formats(tmp_path: Path) -> None:
    from seatwin.recording.convert import convert_bag

    src = _write(tmp_path / "src", "zstd").parent
    want = _raw(src)
    filed = convert_bag(src, tmp_path / "file", fmt="sqlite3", compression="zstd-file")
    assert _meta(filed.bag)["compression_mode"] == "FILE" and _raw(tmp_path / "file") == want
    mcap = convert_bag(tmp_path / "file", tmp_path / "mcap", fmt="mcap", compression="zstd")
    back = convert_bag(mcap.path, tmp_path / "back", fmt="sqlite3", compression="zstd")
    assert _meta(back.bag)["compression_mode"] == "MESSAGE" and _raw(tmp_path / "back") == want


def test_cli_refuses_what_rosbag2_cannot_write(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from seatwin.cli.main import run as cli

    src = _write(tmp_path / "src", "zstd").parent
    for fmt, comp in (("sqlite3", "lz4"), ("mcap", "zstd-file"), ("ros1", "zstd-file")):
        assert cli(["bag", "convert", str(src), "--out", str(tmp_path / fmt), "--format", fmt, "--compression", comp]) == 2
        err = capsys.readouterr().err.strip()
        assert "\n" not in err and "--compression" in err and fmt in err, err
        assert not (tmp_path / fmt).exists()
    args = ["bag", "convert", str(src), "--out", str(tmp_path / "ok"), "--format", "sqlite3", "--compression", "zstd-file"]
    assert cli(args) == 0
    assert (tmp_path / "ok" / "recording" / "recording.db3.zstd").is_file()


# ----------------------------------------------------------------------------- hostile compressed messages
def _with_message(tmp_path: Path, data: bytes, k: int = 2) -> Path:
    """A message-compressed bag whose message ``k`` holds ``data`` (the file's bytes replaced, in a copy)."""
    bag = _write(tmp_path / "run", "zstd")
    con = sqlite3.connect(bag / "recording.db3")
    con.execute("UPDATE messages SET data = ? WHERE id = ?", (data, k + 1))
    con.commit()
    con.close()
    return bag


def _unsized(data: bytes) -> bytes:
    """``data`` as one zstd frame that does not declare its size (a streaming compressor's)."""
    c = zstd.ZstdCompressor()
    out = c.compress(data) + c.flush()
    assert zstd.get_frame_info(out).decompressed_size is None
    return out


def _error(bag: Path, options: ReadOptions | None = None) -> str:
    with pytest.raises(InputError) as info:
        _raw(bag, options)
    msg = str(info.value)
    assert "\n" not in msg and str(bag) in msg and TOPIC in msg, msg
    return msg


SMALL = ReadOptions(chunk_bytes=MIB, total_bytes=64 * MIB)


@pytest.mark.parametrize(
    ("payload", "needle"),
    [
        (zstd.compress(bytes(2 * MIB)), "over the per-message budget"),  # declares 2 MiB, budget 1 MiB
        (_unsized(bytes(2 * MIB)), "inflates beyond the per-message budget"),  # declares nothing
        (_cdr("plain"), "is not a zstd frame"),  # MESSAGE mode: every message is a frame
        (zstd.compress(_cdr("x")) + b"tail", "4 bytes after its zstd frame"),
        (zstd.compress(_cdr("x" * 100))[:-5], "corrupt zstd"),
        (b"", "is not a zstd frame"),
    ],
    ids=["declared-bomb", "unsized-bomb", "plain-cdr", "trailing", "cut", "empty"],
)
def test_hostile_message_is_one_error_naming_bag_topic_time(tmp_path: Path, payload: bytes, needle: str) -> None:
    bag = _with_message(tmp_path, payload)
    msg = _error(bag, SMALL)
    assert needle in msg and f"message at {M.stamp_ns(T0 + 2)} ns" in msg, msg


def test_bag_budget_bounds_all_messages_of_a_pass(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    bag = _write(tmp_path / "run", "zstd", n=8)
    assert len(_raw(bag)) == 8
    monkeypatch.setenv("SEATWIN_MAX_BAG_BYTES", "200")  # the first few messages fit, the rest do not
    assert "SEATWIN_MAX_BAG_BYTES left" in _error(bag)


def test_bomb_is_refused_within_the_budget_of_memory(tmp_path: Path) -> None:
    """64 MiB of zeros in a frame that does not declare its size: refused once 4 MiB (the budget) are out."""
    import tracemalloc

    c = zstd.ZstdCompressor()
    frame = b"".join(c.compress(bytes(MIB)) for _ in range(64)) + c.flush()
    assert len(frame) < 64 * 1024
    bag = _with_message(tmp_path, frame)
    tracemalloc.start()
    try:
        msg = _error(bag, ReadOptions(chunk_bytes=4 * MIB))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert "inflates beyond the per-message budget of 4194304 bytes" in msg
    assert peak < 12 * MIB, peak


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    flips=st.lists(st.tuples(st.integers(0, 10_000), st.integers(1, 255)), min_size=1, max_size=6),
    cut=st.integers(0, 60),
    text=st.text(max_size=200),
)
def test_damaged_frames_read_exactly_or_fail_cleanly(
    tmp_path_factory: pytest.TempPathFactory, flips: list[tuple[int, int]], cut: int, text: str
) -> None:
    """A message's frame with flipped bytes or cut short: its exact bytes (a flip zstd cannot see is not possible
    to tell apart) decode, or one InputError naming the bag, the topic and the time; never another exception."""
    frame = bytearray(zstd.compress(_cdr(text)))
    for at, mask in flips:
        frame[at % len(frame)] ^= mask
    frame = frame[: max(len(frame) - cut, 0)]
    bag = _with_message(tmp_path_factory.mktemp("h"), bytes(frame))
    try:
        got = _raw(bag, SMALL)
    except InputError:
        _error(bag, SMALL)
    else:
        assert got[2][3] == zstd.decompress(bytes(frame))


# ----------------------------------------------------------------------------- hostile compressed files
def _with_file(tmp_path: Path, data: bytes) -> Path:
    bag = _write(tmp_path / "run", "zstd-file")
    (bag / "recording.db3.zstd").write_bytes(data)
    return bag


@pytest.mark.parametrize(
    ("make", "needle"),
    [
        (lambda db: zstd.compress(db + bytes(3 * MIB)), "declares"),  # over SEATWIN_MAX_BAG_BYTES (2 MiB)
        (lambda db: _unsized(db + bytes(3 * MIB)), "inflates beyond the budget"),
        (lambda db: zstd.compress(db)[:-10], "ends early"),
        (lambda db: zstd.compress(db) + b"more", "after its zstd frame"),
        (lambda db: db, "is not zstd data"),
        (lambda db: zstd.compress(b"not sqlite" * 100), "SQLite3"),
    ],
    ids=["declared-bomb", "unsized-bomb", "cut", "trailing", "not-zstd", "not-sqlite"],
)
def test_hostile_file_is_one_error_naming_it(tmp_path: Path, make, needle: str) -> None:
    db = zstd.decompress((_write(tmp_path / "seed", "zstd-file") / "recording.db3.zstd").read_bytes())
    bag = _with_file(tmp_path, make(db))
    before = _digest(bag)
    with pytest.raises(InputError) as info:
        _raw(bag, ReadOptions(chunk_bytes=MIB, total_bytes=2 * MIB))
    msg = str(info.value)
    assert "\n" not in msg and "recording.db3.zstd" in msg and needle in msg, msg
    assert _digest(bag) == before


def test_file_larger_than_the_free_disk_is_refused_before_inflating(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import collections

    import seatwin.recording.sqlite_zstd as sz

    bag = _write(tmp_path / "run", "zstd-file")
    usage = collections.namedtuple("usage", "total used free")
    monkeypatch.setattr(sz.shutil, "disk_usage", lambda _p: usage(10**6, 10**6 - 100, 100))
    with pytest.raises(InputError) as info:
        _raw(bag)
    msg = str(info.value)
    assert "recording.db3.zstd" in msg and "more than the 100 bytes free" in msg, msg


@pytest.mark.parametrize(
    ("field", "value", "needle"),
    [("compression_format", "lz4", "compression_format 'lz4' is not readable"), ("compression_mode", "CHUNK", "unknown")],
)
def test_unreadable_compression_metadata_names_the_field(tmp_path: Path, field: str, value: str, needle: str) -> None:
    bag = _write(tmp_path / "run", "zstd")
    meta = bag / "metadata.yaml"
    doc = yaml.safe_load(meta.read_text())
    doc["rosbag2_bagfile_information"][field] = value
    meta.write_text(yaml.safe_dump(doc))
    with pytest.raises(InputError) as info:
        open_bag(bag)
    assert needle in str(info.value) and "metadata.yaml" in str(info.value) and field in str(info.value)


def test_broken_metadata_falls_back_to_the_storage_file(tmp_path: Path) -> None:
    """A metadata.yaml that does not parse: the .db3 is read as a killed run's, its frames inflated."""
    bag = _write(tmp_path / "run", "zstd")
    want = _raw(bag)
    (bag / "metadata.yaml").write_text("rosbag2_bagfile_information: [unclosed")
    with open_bag(bag) as rec:
        assert rec.recovered and [(t, ty, ts, bytes(d)) for t, ty, ts, d in rec.raw_messages()] == want


def test_staged_folder_is_removed_on_close(tmp_path: Path) -> None:
    bag = _write(tmp_path / "run", "zstd-file")
    rec = open_bag(bag)
    staged = [d.path for d in rec._dbs if hasattr(d, "files")]
    assert staged and staged[0].is_dir() and (staged[0] / "recording.db3").is_file()
    rec.close()
    assert not staged[0].exists()
    shutil.rmtree(tmp_path / "run")
