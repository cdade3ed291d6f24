"""The lean MCAP storage writes exactly the bytes rosbags' own MCAP writer writes."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from recording_helpers import T0

from seatwin.recording.mcap_storage import LeanMcapWriter, LeanWriter
from seatwin.recording.messages import typestore
from seatwin.rng import frame_rng


def _write(cls, path: Path) -> bytes:
    from rosbags.rosbag2 import StoragePlugin

    store = typestore("mcap")
    w = cls(path, version=9, storage_plugin=StoragePlugin.MCAP)
    w.open()
    a = w.add_connection("/a", "std_msgs/msg/String", typestore=store)
    b = w.add_connection("/b", "std_msgs/msg/UInt8MultiArray", typestore=store)
    rng = frame_rng(0, "test/mcap", 0)
    t = int(T0 * 1e9)
    for k in range(60):
        n = int(rng.integers(0, 200_000))
        w.write(a, t + k * 1000, bytes(rng.integers(0, 255, int(rng.integers(0, 50)), dtype=np.uint8)))
        w.write(b, t + k * 1000 - 500, rng.integers(0, 255, n, dtype=np.uint8).tobytes())  # out of order across topics
        if k % 17 == 0:
            w.storage.close_chunk()  # a flush, as RecordingWriter does
        if k == 17:  # a new topic whose first message is large: its schema/channel precede it
            c = w.add_connection("/c", "std_msgs/msg/ByteMultiArray", typestore=store)
            w.write(c, t + k * 1000 + 1, bytes(300_000))
    w.close()
    return (path / f"{path.name}.mcap").read_bytes()


def test_lean_mcap_is_byte_identical_to_rosbags(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from rosbags.rosbag2 import Writer

    monkeypatch.setattr(LeanMcapWriter, "DIRECT_BYTES", None)  # the buffered path only
    ours = _write(LeanWriter, tmp_path / "ours" / "bag")
    theirs = _write(Writer, tmp_path / "theirs" / "bag")
    assert len(ours) > 5_000_000
    assert ours == theirs


def test_large_messages_in_own_chunks_read_back(tmp_path: Path) -> None:
    """With the direct path on, rosbags' indexed reader, mcap's own reader and a cut copy all agree."""
    from mcap.reader import make_reader
    from rosbags.rosbag2 import Reader, Writer

    from seatwin.recording import open_bag

    _write(LeanWriter, tmp_path / "bag")
    _write(Writer, tmp_path / "ref")
    with Reader(tmp_path / "ref") as ref:
        want = [(c.topic, t, bytes(d)) for c, t, d in ref.messages()]
    with Reader(tmp_path / "bag") as r:
        got = [(c.topic, t, bytes(d)) for c, t, d in r.messages()]
    assert got == want and len(got) == 121
    with (tmp_path / "bag" / "bag.mcap").open("rb") as f:
        reader = make_reader(f)
        assert sum(1 for _ in reader.iter_messages()) == 121
        assert reader.get_summary().statistics.message_count == 121
    data = (tmp_path / "bag" / "bag.mcap").read_bytes()
    (tmp_path / "cut.mcap").write_bytes(data[: len(data) // 2])
    with open_bag(tmp_path / "cut.mcap") as rec:
        assert rec.recovered
        cut = [(topic, ts) for topic, _, ts, _ in rec._b.messages(None)]  # raw: the payloads are not CDR
    assert 0 < len(cut) < 121
    assert cut == _file_order(tmp_path)[: len(cut)]


def _file_order(tmp_path: Path) -> list[tuple[str, int]]:
    from mcap.stream_reader import StreamReader
    from mcap.records import Channel, Message

    out, topics = [], {}
    with (tmp_path / "bag" / "bag.mcap").open("rb") as f:
        for rec in StreamReader(f).records:
            if isinstance(rec, Channel):
                topics[rec.id] = rec.topic
            elif isinstance(rec, Message):
                out.append((topics[rec.channel_id], rec.log_time))
    return out
