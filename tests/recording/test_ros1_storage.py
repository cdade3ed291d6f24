"""The lean ROS 1 writer stores the same messages as rosbags' writer, readable indexed and cut."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from recording_helpers import T0

from seatwin.recording import open_bag
from seatwin.recording.messages import typestore
from seatwin.recording.ros1_storage import LeanRos1Writer
from seatwin.rng import frame_rng


def _write(cls, path: Path) -> list[tuple[str, int]]:
    """Write 78 messages, 1 in 3 of the large ones ≥ 64 kB; return (topic, time) in write order."""
    order = []
    store = typestore("ros1")
    rng = frame_rng(0, "test/ros1", 0)
    t = int(T0 * 1e9)
    with cls(path) as w:
        a = w.add_connection("/a", "std_msgs/msg/String", typestore=store)
        c = w.add_connection("/c", "std_msgs/msg/ByteMultiArray", typestore=store)
        w.write(c, t - 1, bytes(100_000))  # large first message: the connection records open its chunk
        order.append(("/c", t - 1))
        for k in range(40):
            if k == 3:
                b = w.add_connection("/b", "std_msgs/msg/UInt8MultiArray", typestore=store)
            w.write(a, t + k * 1000, rng.integers(0, 255, int(rng.integers(0, 50)), dtype=np.uint8).tobytes())
            order.append(("/a", t + k * 1000))
            if k >= 3:
                n = int(rng.choice([10, 70_000, 300_000]))
                w.write(b, t + k * 1000 - 500, rng.integers(0, 255, n, dtype=np.uint8).tobytes())
                order.append(("/b", t + k * 1000 - 500))
    return order


def test_lean_ros1_same_messages_as_rosbags(tmp_path: Path) -> None:
    from rosbags.rosbag1 import Reader, Writer

    order = _write(LeanRos1Writer, tmp_path / "ours.bag")
    _write(Writer, tmp_path / "ref.bag")
    rows = {}
    for name in ("ours", "ref"):
        with Reader(tmp_path / f"{name}.bag") as r:
            rows[name] = [(c.topic, c.msgtype, t, bytes(d)) for c, t, d in r.messages()]
    assert len(rows["ours"]) == 78 and rows["ours"] == rows["ref"]

    data = (tmp_path / "ours.bag").read_bytes()
    (tmp_path / "cut.bag").write_bytes(data[: len(data) * 2 // 3])
    with open_bag(tmp_path / "cut.bag") as rec:
        assert rec.recovered
        cut = [(topic, ts) for topic, _, ts, _ in rec._b.messages(None)]  # raw: the payloads are random bytes
    assert 20 < len(cut) < 78
    assert cut == order[: len(cut)]  # a prefix, in write order
