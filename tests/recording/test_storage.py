"""Each format's storage class writes what rosbags' own writers write (MCAP, SQLite3 byte for byte;
ROS 1 the same messages), and bags cut short read back as a prefix in write order."""

from __future__ import annotations

import sqlite3
import struct
from pathlib import Path

import numpy as np
import pytest
from recording_helpers import T0

from seatwin.defaults import ROS_DISTROS
from seatwin.recording import open_bag
from seatwin.recording.messages import typestore
from seatwin.recording.storage import STORAGES, BagStorage, bag_path, open_storage
from seatwin.recording.storage.mcap import LeanMcapWriter
from seatwin.recording.storage.metadata_yaml import _ruamel, dump_yaml
from seatwin.recording.storage.ros1 import LeanRos1Writer
from seatwin.recording.storage.rosbag2 import LATCHED_QOS
from seatwin.rng import frame_rng

TOPICS = [
    ("/a", "std_msgs/msg/String", False),
    ("/b", "std_msgs/msg/UInt8MultiArray", False),
    ("/tf_static", "tf2_msgs/msg/TFMessage", True),
    ("/c", "std_msgs/msg/ByteMultiArray", False),
]


def _script() -> list[tuple[str, int, bytes]]:
    """("add", topic index) / ("write", topic index, time, bytes) / ("flush",) steps: small and large
    messages, out of order across topics, a topic added late whose first message is large."""
    rng = frame_rng(0, "test/storage", 0)
    t = int(T0 * 1e9)
    steps: list = [("add", 0), ("add", 1), ("add", 2), ("write", 2, t - 7, b"\x00\x01\x00\x00" + bytes(4))]
    for k in range(60):
        steps.append(("write", 0, t + k * 1000, bytes(rng.integers(0, 255, int(rng.integers(0, 50)), dtype=np.uint8))))
        steps.append(
            ("write", 1, t + k * 1000 - 500, rng.integers(0, 255, int(rng.integers(0, 200_000)), dtype=np.uint8).tobytes())
        )
        if k % 17 == 0:
            steps.append(("flush",))
        if k == 17:
            steps += [("add", 3), ("write", 3, t + k * 1000 + 1, bytes(300_000))]
    return steps


@pytest.fixture
def as_rosbags(monkeypatch: pytest.MonkeyPatch) -> str:
    """A distribution named as rosbags' writer names every bag (version 9): for byte-for-byte comparisons."""
    monkeypatch.setitem(ROS_DISTROS, "rosbags", 9)
    return "rosbags"


def _ours(fmt: str, path: Path, ros_distro: str = "jazzy", compression: str = "none") -> None:
    st = open_storage(fmt, path, typestore(fmt), ros_distro=ros_distro, compression=compression)
    conns = {}
    for step in _script():
        if step[0] == "add":
            topic, msgtype, latched = TOPICS[step[1]]
            conns[step[1]] = st.add_connection(topic, msgtype, latched=latched)
        elif step[0] == "write":
            st.write(conns[step[1]], step[2], step[3])
        else:
            st.flush()
    st.close()


def _rosbags(fmt: str, path: Path) -> None:
    from rosbags.rosbag2 import StoragePlugin, Writer

    w = Writer(path, version=9, storage_plugin=StoragePlugin.MCAP if fmt == "mcap" else StoragePlugin.SQLITE3)
    w.open()
    conns = {}
    for step in _script():
        if step[0] == "add":
            topic, msgtype, latched = TOPICS[step[1]]
            conns[step[1]] = w.add_connection(
                topic, msgtype, typestore=typestore(fmt), offered_qos_profiles=[LATCHED_QOS] if latched else []
            )
        elif step[0] == "write":
            w.write(conns[step[1]], step[2], step[3])
        elif fmt == "mcap" and w.storage.chunk.msgs:
            w.storage.close_chunk()
        elif fmt == "sqlite3":
            w.storage.conn.commit()
    w.close()


def test_one_interface_per_format() -> None:
    assert set(STORAGES) == {"mcap", "sqlite3", "ros1"}
    for fmt, cls in STORAGES.items():
        assert issubclass(cls, BagStorage) and cls.format == fmt and cls.ros1 == (fmt == "ros1")
    assert bag_path(Path("run"), "ros1") == Path("run/recording.bag")
    assert bag_path(Path("run"), "mcap") == Path("run/recording")


def test_mcap_byte_identical_to_rosbags(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, as_rosbags: str) -> None:
    monkeypatch.setattr(LeanMcapWriter, "DIRECT_BYTES", None)  # the buffered path only
    _ours("mcap", tmp_path / "ours" / "bag", as_rosbags)
    _rosbags("mcap", tmp_path / "theirs" / "bag")
    ours, theirs = ((tmp_path / d / "bag" / "bag.mcap").read_bytes() for d in ("ours", "theirs"))
    assert len(ours) > 5_000_000 and ours != theirs  # rosbags writes no CRCs (0); ours are set …
    assert _without_crcs(ours) == theirs  # … and are the only difference
    from mcap.stream_reader import StreamReader

    n = sum(1 for _ in StreamReader(str(tmp_path / "ours/bag/bag.mcap"), validate_crcs=True).records)
    assert n > 100  # mcap's own reader checks every chunk CRC and the data-section CRC
    assert (tmp_path / "ours/bag/metadata.yaml").read_text() == (tmp_path / "theirs/bag/metadata.yaml").read_text()


def _without_crcs(data: bytes) -> bytes:
    """``data`` (an MCAP file) with every chunk's ``uncompressed_crc`` and the data-section CRC set to 0."""
    out = bytearray(data)
    pos = 8
    while pos < len(out) - 8:
        op, length = struct.unpack_from("<BQ", out, pos)
        if op == 0x06:
            assert struct.unpack_from("<I", out, pos + 9 + 24)[0] != 0
            struct.pack_into("<I", out, pos + 9 + 24, 0)
        elif op == 0x0F:
            assert struct.unpack_from("<I", out, pos + 9)[0] != 0
            struct.pack_into("<I", out, pos + 9, 0)
        elif op == 0x02:
            break
        pos += 9 + length
    return bytes(out)


def test_sqlite3_identical_to_rosbags(tmp_path: Path, as_rosbags: str) -> None:
    _ours("sqlite3", tmp_path / "ours" / "bag", as_rosbags)
    _rosbags("sqlite3", tmp_path / "theirs" / "bag")
    dumps = []
    for d in ("ours", "theirs"):
        con = sqlite3.connect(tmp_path / d / "bag" / "bag.db3")
        dumps.append(list(con.iterdump()))
        con.close()
    assert len(dumps[0]) > 100 and dumps[0] == dumps[1]
    assert (tmp_path / "ours/bag/metadata.yaml").read_text() == (tmp_path / "theirs/bag/metadata.yaml").read_text()


def test_mcap_large_messages_in_own_chunks_read_back(tmp_path: Path) -> None:
    """With the direct path on, rosbags' indexed reader, mcap's own reader and a cut copy all agree."""
    from mcap.reader import make_reader
    from rosbags.rosbag2 import Reader

    _ours("mcap", tmp_path / "bag")
    _rosbags("mcap", tmp_path / "ref")
    with Reader(tmp_path / "ref") as ref:
        want = [(c.topic, t, bytes(d)) for c, t, d in ref.messages()]
    with Reader(tmp_path / "bag") as r:
        got = [(c.topic, t, bytes(d)) for c, t, d in r.messages()]
    assert got == want and len(got) == 122
    with (tmp_path / "bag" / "bag.mcap").open("rb") as f:
        reader = make_reader(f)
        assert sum(1 for _ in reader.iter_messages()) == 122
        assert reader.get_summary().statistics.message_count == 122
    data = (tmp_path / "bag" / "bag.mcap").read_bytes()
    (tmp_path / "cut.mcap").write_bytes(data[: len(data) // 2])
    with open_bag(tmp_path / "cut.mcap") as rec:
        assert rec.recovered
        cut = [(topic, ts) for topic, _, ts, _ in rec.raw_messages()]  # raw: the payloads are not all CDR
    assert 0 < len(cut) < 122
    assert cut == _write_order()[: len(cut)]


def _write_order() -> list[tuple[str, int]]:
    return [(TOPICS[s[1]][0], s[2]) for s in _script() if s[0] == "write"]


def _ros1(cls, path: Path) -> list[tuple[str, int]]:
    """78 messages, 1 in 3 of the large ones ≥ 64 kB; (topic, time) in write order."""
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


def test_ros1_same_messages_as_rosbags(tmp_path: Path) -> None:
    from rosbags.rosbag1 import Reader, Writer

    order = _ros1(LeanRos1Writer, tmp_path / "ours.bag")
    _ros1(Writer, tmp_path / "ref.bag")
    rows = {}
    for name in ("ours", "ref"):
        with Reader(tmp_path / f"{name}.bag") as r:
            rows[name] = [(c.topic, c.msgtype, t, bytes(d)) for c, t, d in r.messages()]
    assert len(rows["ours"]) == 78 and rows["ours"] == rows["ref"]

    data = (tmp_path / "ours.bag").read_bytes()
    (tmp_path / "cut.bag").write_bytes(data[: len(data) * 2 // 3])
    with open_bag(tmp_path / "cut.bag") as rec:
        assert rec.recovered
        cut = [(topic, ts) for topic, _, ts, _ in rec.raw_messages()]  # raw: the payloads are random bytes
    assert 20 < len(cut) < 78
    assert cut == order[: len(cut)]  # a prefix, in write order


def test_ros1_storage_latches_tf_static(tmp_path: Path) -> None:
    from rosbags.rosbag1 import Reader

    _ours("ros1", tmp_path / "x.bag")
    with Reader(tmp_path / "x.bag") as r:
        latching = {c.topic: c.ext.latching for c in r.connections}
        got = [(c.topic, t) for c, t, _ in r.messages()]
    assert latching == {"/a": None, "/b": None, "/tf_static": 1, "/c": None}
    assert sorted(got, key=lambda x: x[1]) == sorted(_write_order(), key=lambda x: x[1])


YAML_CASES = [
    {},
    [],
    {"a": []},
    {"a": {}},
    [{"x": 1, "b": [True, None, "s"]}],
    {"k" * 40: "v" * 37, "k" * 41: "v" * 37, "q": "v" * 78},  # around the 80-column wrap
    {"outer": {"inner": {"deep": "h" * 70}}},
    {"s": ["a" * 78, "b" * 79, "c" * 90]},  # long sequence items: ruamel's own rule
    {"e": "", "n": None, "t": "true", "y": "yes", "num": "12", "colon": "a: b", "sp": "a b", "dash": "-x", "u": "ø"},
]


@pytest.mark.parametrize("data", YAML_CASES)
def test_metadata_yaml_as_ruamel_writes_it(data) -> None:
    assert dump_yaml(data) == _ruamel(data)


def test_metadata_yaml_random_documents() -> None:
    rng = frame_rng(0, "test/yaml", 0)
    alphabet = list("abcXYZ019_/.-")

    def text() -> str:
        n = int(rng.choice([0, 1, 8, 30, 50, 60, 70, 76, 79, 85]))
        return "".join(rng.choice(alphabet, n)) if n else ""

    def value(depth: int):
        r = rng.random()
        if depth < 3 and r < 0.3:
            return {text() or "k": value(depth + 1) for _ in range(int(rng.integers(0, 4)))}
        if depth < 3 and r < 0.45:
            return [value(depth + 1) for _ in range(int(rng.integers(0, 3)))]
        if r < 0.6:
            return int(rng.integers(-5, 2**62))
        return text()

    for _ in range(300):
        doc = {text() or "k": value(0) for _ in range(4)}
        assert dump_yaml(doc) == _ruamel(doc)


@pytest.mark.parametrize("fmt", ["mcap", "sqlite3", "ros1"])
def test_write_many_same_bag_as_one_by_one(tmp_path: Path, fmt: str) -> None:
    """Batches of messages with one log time (small and large mixed, crossing chunk limits) give the same
    file as writing them one by one."""
    rng = frame_rng(0, "test/write_many", 0)
    t = int(T0 * 1e9)
    batches = []
    for k in range(40):
        sizes = rng.choice([3, 200, 30_000, 70_000, 400_000], int(rng.integers(1, 6)))
        batches.append((t + k * 1000, [(int(rng.integers(0, 3)), bytes(rng.integers(0, 255, n, dtype=np.uint8))) for n in sizes]))
    files = []
    for mode in ("one", "many"):
        path = tmp_path / mode / ("bag.bag" if fmt == "ros1" else "bag")
        path.parent.mkdir()
        st = open_storage(fmt, path, typestore(fmt))
        conns = [st.add_connection(topic, msgtype, latched=latched) for topic, msgtype, latched in TOPICS[:3]]
        for k, (ts, items) in enumerate(batches):
            pairs = [(conns[i], d) for i, d in items]
            if mode == "many":
                st.write_many(pairs, ts)
            else:
                for c, d in pairs:
                    st.write(c, ts, d)
            if k % 9 == 8:
                st.flush()
        st.close()
        data = path.read_bytes() if fmt == "ros1" else (path / f"bag.{'mcap' if fmt == 'mcap' else 'db3'}").read_bytes()
        files.append(data)
    assert len(files[0]) > 1_000_000 and files[0] == files[1]


# what each ROS 2 distribution's rosbag2 decodes (yaml.hpp on the humble, iron and jazzy branches)
_REQUIRED = {"version", "storage_identifier", "duration", "starting_time", "message_count", "topics_with_message_count"}
_SINCE = {"relative_file_paths": 0, "compression_format": 3, "compression_mode": 3, "files": 5, "custom_data": 6, "ros_distro": 8}


@pytest.mark.parametrize(("distro", "version"), [("humble", 5), ("iron", 7), ("jazzy", 9), ("kilted", 9)])
@pytest.mark.parametrize("fmt", ["mcap", "sqlite3"])
def test_metadata_in_the_distros_version(tmp_path: Path, fmt: str, distro: str, version: int) -> None:
    """Each version has the fields rosbag2 decodes for it; QoS a string of numeric enums below 9 (what Humble's
    ``as<std::string>()`` and its QoS parser read), a list from 9; the bag says which distro it is for."""
    import yaml
    from rosbags.highlevel import AnyReader

    _ours(fmt, tmp_path / "bag", distro)
    info = yaml.safe_load((tmp_path / "bag" / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    assert info["version"] == version and info["ros_distro"] == distro
    assert set(info) >= _REQUIRED and all(k in info for k, v in _SINCE.items() if v <= version)
    assert ("custom_data" in info) == (version >= 6)
    for t in info["topics_with_message_count"]:
        meta = t["topic_metadata"]
        assert ("type_description_hash" in meta) == (version >= 7)
        qos = meta["offered_qos_profiles"]
        if version >= 9:
            assert isinstance(qos, list)
        else:
            assert isinstance(qos, str)
            if meta["name"] == "/tf_static":
                (profile,) = yaml.safe_load(qos)
                assert profile["durability"] == 1 and profile["reliability"] == 1 and profile["depth"] == 1  # transient local
    if fmt == "sqlite3":
        con = sqlite3.connect(tmp_path / "bag" / "bag.db3")
        assert con.execute("SELECT ros_distro FROM schema").fetchall() == [(distro,)]
        con.close()
    with AnyReader([tmp_path / "bag"]) as r:
        assert r.message_count == 122
        latched = [c for c in r.connections if c.topic == "/tf_static"]
        assert latched[0].ext.offered_qos_profiles[0].durability.name == "TRANSIENT_LOCAL"


def test_unknown_distro_is_refused(tmp_path: Path) -> None:
    from seatwin.errors import ParameterError

    with pytest.raises(ParameterError) as exc:
        open_storage("mcap", tmp_path / "bag", typestore("mcap"), ros_distro="rolling")
    assert exc.value.param == "ros_distro" and "humble" in str(exc.value)
    assert not (tmp_path / "bag").exists()
