"""MCAP structural pre-check (issue #14): a forged length field gives one InputError naming the file
and the byte offset, before any reader allocates from it; unfinished bags still open up to their cut."""

from __future__ import annotations

import shutil
import struct
import tracemalloc
from pathlib import Path

import pytest

from seatwin.errors import InputError
from seatwin.recording import open_bag
from seatwin.recording.mcap_check import MAX_UNCOMPRESSED, check_mcap

FORGED = 2**62


def _records(data: bytes) -> list[tuple[int, int, int]]:
    """(offset, opcode, length) of every top-level record of an intact file (test side: reads it all)."""
    out, pos = [], 8
    while pos < len(data) - 8:
        op, length = struct.unpack_from("<BQ", data, pos)
        out.append((pos, op, length))
        if op == 0x02:
            break
        pos += 9 + length
    return out


@pytest.fixture(scope="module")
def seed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from seatwin.pipeline import simulate_run

    run = tmp_path_factory.mktemp("run")
    simulate_run("ferry_crossing", run, duration=1.0, progress=False, sensors=("lidar",))
    return next((run / "recording").glob("*.mcap"))


def _first(data: bytes, op: int) -> int:
    return next(pos for pos, o, _ in _records(data) if o == op)


def _patch(seed: Path, out: Path, at: int, value: int, fmt: str = "<Q") -> Path:
    data = bytearray(seed.read_bytes())
    struct.pack_into(fmt, data, at, value)
    out.write_bytes(bytes(data))
    return out


def _open_fails(path: Path) -> str:
    tracemalloc.start()
    try:
        with pytest.raises(InputError) as info, open_bag(path):
            pass
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 8 * 2**20, peak  # far below the forged 2**62 (and below the file's own size × 30)
    msg = str(info.value)
    assert str(path) in msg and "corrupt MCAP" in msg and "\n" not in msg
    return msg


def test_intact_file_passes(seed: Path) -> None:
    layout = check_mcap(seed)
    assert layout.finished and not layout.truncated and layout.readable_end == seed.stat().st_size
    assert layout.data_end == _first(seed.read_bytes(), 0x03)  # the summary starts with the schemas


def test_chunk_record_length(seed: Path, tmp_path: Path) -> None:
    at = _first(seed.read_bytes(), 0x06)
    msg = _open_fails(_patch(seed, tmp_path / "a.mcap", at + 1, FORGED))
    assert f"Chunk at byte {at}: length {FORGED} exceeds" in msg


def test_chunk_index_chunk_length(seed: Path, tmp_path: Path) -> None:
    at = _first(seed.read_bytes(), 0x08)
    msg = _open_fails(_patch(seed, tmp_path / "a.mcap", at + 9 + 24, FORGED))
    assert f"Chunk Index at byte {at}: chunk_start_offset + chunk_length" in msg and "exceeds" in msg


def test_footer_summary_start(seed: Path, tmp_path: Path) -> None:
    at = _first(seed.read_bytes(), 0x02)
    msg = _open_fails(_patch(seed, tmp_path / "a.mcap", at + 9, FORGED))
    assert f"Footer at byte {at}: summary_start {FORGED} exceeds {at}" in msg


def test_chunk_uncompressed_size(seed: Path, tmp_path: Path) -> None:
    at = _first(seed.read_bytes(), 0x06)
    msg = _open_fails(_patch(seed, tmp_path / "a.mcap", at + 9 + 16, FORGED))
    assert f"Chunk at byte {at}: uncompressed_size {FORGED} exceeds {MAX_UNCOMPRESSED}" in msg


def test_chunk_records_length(seed: Path, tmp_path: Path) -> None:
    data = seed.read_bytes()
    at = _first(data, 0x06)
    (clen,) = struct.unpack_from("<I", data, at + 9 + 28)
    msg = _open_fails(_patch(seed, tmp_path / "a.mcap", at + 9 + 32 + clen, FORGED))
    assert f"Chunk at byte {at}: records length {FORGED} exceeds" in msg


def test_unfinished_bag_stops_at_forged_length(seed: Path, tmp_path: Path) -> None:
    """Without footer a record running past the end is the cut: everything before it is read."""
    data = seed.read_bytes()
    summary = _first(data, 0x03)
    unfinished = bytearray(data[:summary])  # no summary, no footer: as SIGKILL leaves it
    msg_index = _first(data, 0x07)
    struct.pack_into("<Q", unfinished, msg_index + 1, FORGED)
    path = tmp_path / "cut.mcap"
    path.write_bytes(bytes(unfinished))
    layout = check_mcap(path)
    assert not layout.finished and layout.truncated and layout.readable_end == msg_index
    with open_bag(seed) as rec:
        want = sum(i.count for i in rec.topics.values())
    tracemalloc.start()
    try:
        with open_bag(path) as rec:
            assert rec.recovered and rec.truncated and rec.complete is False
            got = sum(1 for _ in rec.messages())
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert got == want > 0  # the one chunk before the forged record is read in full
    assert peak < 32 * 2**20, peak


def test_unfinished_bag_forged_chunk_is_the_cut(seed: Path, tmp_path: Path) -> None:
    data = seed.read_bytes()
    at = _first(data, 0x06)
    cut = _patch(seed, tmp_path / "x.mcap", at + 1, FORGED)
    path = tmp_path / "cut.mcap"
    path.write_bytes(cut.read_bytes()[: _first(data, 0x03)])
    with open_bag(path) as rec:
        assert rec.recovered and rec.truncated
        assert list(rec.messages()) == []


def test_zero_filled_tail_is_the_cut(seed: Path, tmp_path: Path) -> None:
    data = seed.read_bytes()
    end = _first(data, 0x03)
    path = tmp_path / "zeros.mcap"
    path.write_bytes(data[:end] + bytes(4096))
    layout = check_mcap(path)
    assert layout.truncated and layout.readable_end == end
    with open_bag(path) as rec:
        assert rec.recovered and rec.truncated and len(list(rec.messages())) > 0


def test_cli_exits_2_with_one_line(seed: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from seatwin.cli.main import run

    at = _first(seed.read_bytes(), 0x06)
    bad = _patch(seed, tmp_path / "bad.mcap", at + 1, FORGED)
    assert run(["bag", "info", str(bad)]) == 2
    err = capsys.readouterr().err.strip()
    assert "corrupt MCAP" in err and str(at) in err and len(err.splitlines()) == 1


def test_run_directory_is_checked_too(seed: Path, tmp_path: Path) -> None:
    """A rosbag2 directory with metadata.yaml goes through the same check."""
    bag = tmp_path / "recording"
    shutil.copytree(seed.parent, bag)
    at = _first(seed.read_bytes(), 0x06)
    _patch(seed, bag / seed.name, at + 9 + 16, FORGED)
    msg = _open_fails(bag)
    assert f"at byte {at}" in msg
