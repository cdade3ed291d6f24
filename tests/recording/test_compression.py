"""Bag size (issue #23): chunk compression of every format and compressed camera images.

Each format × compression writes the same messages as the uncompressed bag (bytes and log times), which
seatwin, rosbags' AnyReader and (MCAP) the ``mcap`` library with CRC validation read back; JPEG/PNG images go
on ``<topic>/compressed`` as compressed_image_transport names and labels them, and a damaged payload is one
InputError naming the bag, the topic and the message's time. The bags are built here, small.
"""

from __future__ import annotations

import io
import struct
import zlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from recording_helpers import ORIGIN, T0, sweep, vessels

from seatwin.errors import InputError, ParameterError
from seatwin.recording import RecordingWriter, open_bag
from seatwin.recording import messages as M
from seatwin.recording.images import MAX_PIXELS, decode_compressed, encode_image, transport_format

COMBOS = [
    ("mcap", "zstd"),
    ("mcap", "lz4"),
    ("mcap", "none"),
    ("sqlite3", "none"),
    ("sqlite3", "zstd"),
    ("sqlite3", "zstd-file"),
    ("ros1", "lz4"),
    ("ros1", "bz2"),
    ("ros1", "none"),
]
BIG = (160, 200)
"""A camera image of 96 kB: above the writers' 64 kB, so it goes to the file as a chunk of its own."""


def _picture(k: int, shape: tuple[int, int] = BIG) -> np.ndarray:
    """A bgr8 picture of flat 8 × 8 tiles (JPEG keeps it within a few levels) that changes with ``k``."""
    h, w = shape
    yy, xx = np.mgrid[0:h, 0:w] // 8 * 8
    return np.stack([(xx + 3 * k) % 256, (yy * 2) % 256, np.full((h, w), 40 + k)], axis=-1).astype(np.uint8)


def _write(run: Path, fmt: str, compression: str | None = None, image_format: str = "raw", n: int = 12) -> Path:
    with RecordingWriter(run, fmt, origin=ORIGIN, seed=3, compression=compression, image_format=image_format) as w:
        for k in range(n):
            t = T0 + 0.1 * k
            w.write_sweep("/lidar/points", "lidar", t, **sweep(k))
            w.write_ground_truth(t, vessels(k))
            w.write_image("/camera/front/image_raw", "camera_front", t, _picture(k))
            w.write_image("/camera/mono/image_raw", "camera_mono", t, _picture(k, (8, 10))[..., :1], "mono8")
    return run


def _raw(run: Path) -> list[tuple[str, str, int, bytes]]:
    with open_bag(run) as rec:
        return [(t, ty, ts, bytes(d)) for t, ty, ts, d in rec.raw_messages()]


def _anyreader_counts(bag: Path) -> dict[str, int]:
    from rosbags.highlevel import AnyReader

    counts: dict[str, int] = {}
    with AnyReader([bag]) as r:
        for conn, _, data in r.messages():
            r.deserialize(data, conn.msgtype)  # every message decodes
            counts[conn.topic] = counts.get(conn.topic, 0) + 1
    return counts


@pytest.mark.parametrize(("fmt", "compression"), COMBOS)
def test_round_trip_each_format_and_compression(tmp_path: Path, fmt: str, compression: str) -> None:
    plain = _raw(_write(tmp_path / "plain", fmt, "none"))
    run = _write(tmp_path / "run", fmt, compression)
    assert _raw(run) == plain  # the same messages, bytes and log times
    with open_bag(run) as rec:
        assert rec.complete and rec.manifest["compression"] == compression
        bag = rec.bag
        assert len(list(rec.images("/camera/front/image_raw"))) == 12
    n_static = sum(m[0] == "/tf_static" for m in plain)  # the mounts, then each vessel's fixed frames
    assert _anyreader_counts(bag) == {t: 12 for t in {m[0] for m in plain}} | {"/tf_static": n_static}
    size = sum(p.stat().st_size for p in Path(bag).parent.rglob("*") if p.is_file())
    plain_size = sum(p.stat().st_size for p in (tmp_path / "plain").rglob("*") if p.is_file())
    assert (size < plain_size / 2) if compression != "none" else size == pytest.approx(plain_size, rel=0.01)
    if fmt == "mcap":
        from mcap.reader import make_reader

        mcap = next(Path(bag).glob("*.mcap"))
        with mcap.open("rb") as f:
            reader = make_reader(f, validate_crcs=True)
            kinds = {c.compression for c in reader.get_summary().chunk_indexes}
            got = [(ch.topic, m.log_time, bytes(m.data)) for _, ch, m in reader.iter_messages(log_time_order=False)]
        assert kinds == {"" if compression == "none" else compression}
        assert got == [(t, ts, d) for t, _, ts, d in plain]
    elif fmt == "ros1":
        data = Path(bag).read_bytes()
        for kind in ("lz4", "bz2"):
            assert (b"compression=" + kind.encode() in data) == (kind == compression)


def test_defaults_are_lz4_for_mcap_and_ros1(tmp_path: Path) -> None:
    from seatwin.recording.info import bag_info, format_info

    for fmt, want in (("mcap", "lz4"), ("ros1", "lz4"), ("sqlite3", "none")):
        with open_bag(_write(tmp_path / fmt, fmt, n=2)) as rec:
            assert rec.manifest["compression"] == want and rec.manifest["image_format"] == "raw"
            files = [rec.bag] if rec.bag.is_file() else [p for p in rec.bag.rglob("*") if p.is_file()]
        info = bag_info(tmp_path / fmt)
        assert info["size_bytes"] == sum(p.stat().st_size for p in files)
        label = "uncompressed" if fmt == "sqlite3" else f"{want} chunks"
        assert f"MB  ({label}, raw images)" in format_info(info)


@pytest.mark.parametrize(
    ("kwargs", "param", "needle"),
    [
        ({"fmt": "mcap", "compression": "bz2"}, "compression", "expected one of lz4, zstd, none"),
        ({"fmt": "ros1", "compression": "zstd"}, "compression", "expected one of lz4, bz2, none"),
        ({"fmt": "sqlite3", "compression": "lz4"}, "compression", "expected one of none, zstd, zstd-file"),
        ({"fmt": "mcap", "compression": "zstd-file"}, "compression", "expected one of lz4, zstd, none"),
        ({"fmt": "mcap", "image_format": "gif"}, "image_format", "expected one of raw, jpeg, png"),
    ],
)
def test_bad_choices_name_the_parameter(tmp_path: Path, kwargs: dict[str, str], param: str, needle: str) -> None:
    with pytest.raises(ParameterError) as info:
        RecordingWriter(tmp_path / "run", **kwargs)
    assert info.value.param == param and needle in str(info.value)
    assert not (tmp_path / "run").exists()


def test_cli_flag_named_in_the_error(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from seatwin.cli.main import run as cli

    assert cli(["simulate", "ferry_crossing", "--out", str(tmp_path / "r"), "--format", "ros1", "--compression", "zstd"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--compression" in err and "ros1" in err
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
@pytest.mark.parametrize("image_format", ["jpeg", "png"])
def test_compressed_images_as_image_transport_writes_them(tmp_path: Path, fmt: str, image_format: str) -> None:
    run = _write(tmp_path / "run", fmt, image_format=image_format, n=4)
    with open_bag(run) as rec:
        types = {t: i.msgtype for t, i in rec.topics.items() if "camera" in t}
        assert types == {
            "/camera/front/image_raw/compressed": "sensor_msgs/msg/CompressedImage",
            "/camera/mono/image_raw/compressed": "sensor_msgs/msg/CompressedImage",
        }
        assert rec.camera_image_topics() == sorted(types)
        formats = {m.topic: m.msg.format for m in rec.messages(sorted(types))}
        assert formats == {
            "/camera/front/image_raw/compressed": f"bgr8; {image_format} compressed bgr8",
            "/camera/mono/image_raw/compressed": f"mono8; {image_format} compressed mono8",
        }
        frames = list(rec.images("/camera/front/image_raw/compressed"))
        mono = list(rec.images("/camera/mono/image_raw/compressed"))
    assert [f.encoding for f in frames] == ["bgr8"] * 4 and [f.encoding for f in mono] == ["mono8"] * 4
    for k, f in enumerate(frames):
        err = np.abs(f.pixels.astype(int) - _picture(k).astype(int))
        assert f.pixels.shape == (*BIG, 3) and f.frame_id == "camera_front"
        assert err.max() == 0 if image_format == "png" else err.mean() < 3
    if image_format == "png":
        assert all(np.array_equal(f.pixels, _picture(k, (8, 10))[..., :1]) for k, f in enumerate(mono))


def test_coco_export_reads_compressed_images(tmp_path: Path) -> None:
    import json

    from PIL import Image

    from seatwin.pipeline.labels import export_coco

    run = tmp_path / "run"
    with RecordingWriter(run, "mcap", image_format="png") as w:
        for k in range(3):
            w.write_image("/camera/front/image_raw", "camera_front", T0 + k, _picture(k))
            w.write_labels("/camera/front/labels", "camera_front", T0 + k, [M.Box2D("Finn", 50.0, 40.0, 20.0, 10.0)])
    res = export_coco(run, tmp_path / "coco")
    doc = json.loads(res.annotations_file.read_text())
    assert [i["camera"] for i in doc["images"]] == ["camera_front"] * 3 and len(doc["annotations"]) == 3
    first = doc["images"][0]
    assert (first["width"], first["height"]) == (BIG[1], BIG[0])
    png = np.asarray(Image.open(tmp_path / "coco" / first["file_name"]))
    assert np.array_equal(png[..., ::-1], _picture(0))


def test_convert_and_repair_choose_the_compression(tmp_path: Path) -> None:
    from mcap.reader import make_reader

    from seatwin.recording.convert import convert_bag
    from seatwin.recording.repair import repair_bag

    src = _write(tmp_path / "src", "mcap", "zstd", n=4)
    want = _raw(src)
    ros1 = convert_bag(src, tmp_path / "ros1", fmt="ros1", compression="bz2")
    assert b"compression=bz2" in ros1.bag.read_bytes()
    back = convert_bag(tmp_path / "ros1", tmp_path / "back", fmt="mcap", compression="lz4")
    assert _raw(tmp_path / "back") == want
    repaired = repair_bag(src, tmp_path / "rep")  # the run's own compression (manifest), unless told
    plain = repair_bag(src, tmp_path / "plain", compression="none")
    for bag, kind in ((back.bag, "lz4"), (repaired.bag, "zstd"), (plain.bag, "")):
        with next(Path(bag).glob("*.mcap")).open("rb") as f:
            assert {c.compression for c in make_reader(f, validate_crcs=True).get_summary().chunk_indexes} == {kind}
    assert _raw(tmp_path / "rep") == _raw(tmp_path / "plain") == want


# ----------------------------------------------------------------------------- damaged compressed images
def _bag_with(tmp_path: Path, payloads: list[bytes], fmt: str = "jpeg") -> Path:
    run = tmp_path / "bad"
    with RecordingWriter(run, "mcap") as w:
        for k, p in enumerate(payloads):
            w.write("/camera/front/image_raw/compressed", T0 + k, M.compressed_image(w.store, T0 + k, "cam", p, fmt))
    return run


def _png_header(width: int, height: int) -> bytes:
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    chunk = struct.pack(">I", 13) + b"IHDR" + ihdr + struct.pack(">I", zlib.crc32(b"IHDR" + ihdr))
    idat = zlib.compress(b"\x00" * 64)
    body = struct.pack(">I", len(idat)) + b"IDAT" + idat + struct.pack(">I", zlib.crc32(b"IDAT" + idat))
    return b"\x89PNG\r\n\x1a\n" + chunk + body + struct.pack(">I", 0) + b"IEND" + struct.pack(">I", zlib.crc32(b"IEND"))


_GOOD = {kind: encode_image(_picture(1, (24, 32)), kind) for kind in ("jpeg", "png")}


def _one_error(run: Path, k: int) -> str:
    with open_bag(run) as rec, pytest.raises(InputError) as info:
        list(rec.images())
    msg = str(info.value)
    assert "\n" not in msg and str(rec.bag) in msg and "/camera/front/image_raw/compressed" in msg, msg
    assert f"(message at {M.stamp_ns(T0 + k)} ns)" in msg, msg
    return msg


@pytest.mark.parametrize(
    ("payload", "needle"),
    [
        (b"", "cannot decode"),
        (b"not an image at all", "cannot decode"),
        (_GOOD["jpeg"][: len(_GOOD["jpeg"]) // 2], "cannot decode"),
        (_GOOD["png"][:-30], "cannot decode"),
        (b"GIF89a" + bytes(40), "cannot decode"),  # a format Pillow reads, but not JPEG or PNG
        (_png_header(9000, 9000), f"exceeds the {MAX_PIXELS}"),  # 81 M pixels, below Pillow's own warning
        (_png_header(2**31 - 1, 2**31 - 1), "cannot decode"),  # Pillow's bomb error, as one line
    ],
)
def test_damaged_payload_is_one_error(tmp_path: Path, payload: bytes, needle: str) -> None:
    run = _bag_with(tmp_path, [_GOOD["jpeg"], payload])
    assert needle in _one_error(run, 1)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    kind=st.sampled_from(["jpeg", "png"]),
    cut=st.integers(0, 10_000),
    flips=st.lists(st.tuples(st.integers(0, 10_000), st.integers(1, 255)), max_size=6),
)
def test_corrupt_compressed_images_decode_or_fail_cleanly(
    tmp_path_factory: pytest.TempPathFactory, kind: str, cut: int, flips: list[tuple[int, int]]
) -> None:
    """A damaged JPEG/PNG payload decodes to an image (JPEG hides many flipped bytes) or is one InputError naming
    the bag, the topic and the time; never another exception."""
    data = bytearray(_GOOD[kind])
    for at, mask in flips:
        data[at % len(data)] ^= mask
    data = data[: len(data) - cut % len(data)] if cut % 3 == 0 else data
    run = _bag_with(tmp_path_factory.mktemp("h"), [bytes(data)], kind)
    try:
        with open_bag(run) as rec:
            frames = list(rec.images())
    except InputError:
        _one_error(run, 0)
    else:
        assert frames[0].pixels.ndim == 3 and frames[0].pixels.dtype == np.uint8


def test_decode_accepts_only_jpeg_and_png() -> None:
    from PIL import Image

    bio = io.BytesIO()
    Image.new("RGB", (4, 4)).save(bio, format="BMP")
    msg = M.compressed_image(M.typestore("mcap"), T0, "cam", bio.getvalue(), "bmp")
    with pytest.raises(InputError, match="cannot decode the 'bmp' image"):
        decode_compressed(msg)
    assert transport_format("jpg", "rgb8") == "rgb8; jpeg compressed bgr8"


def test_serve_cosim_and_record_stream_take_the_same_options(tmp_path: Path) -> None:
    from seatwin.api.lockstep import LockstepSettings
    from seatwin.api.streaming import record_stream
    from seatwin.settings import validated

    s = validated(LockstepSettings, {"fmt": "ros1", "compression": "bz2", "image_format": "jpeg"})
    assert s.writer_options() == {"compression": "bz2", "image_format": "jpeg"}
    with pytest.raises(ParameterError, match="not a compression of ros1 bags"):
        validated(LockstepSettings, {"fmt": "ros1", "compression": "zstd"})
    with pytest.raises(ParameterError, match="not a compression of mcap bags"):
        record_stream(tmp_path / "r", port=0, compression="bz2")
    assert not (tmp_path / "r").exists()


_SEED_BAGS: dict[tuple[str, str], bytes] = {}


def _seed_bag(tmp: Path, fmt: str, compression: str) -> bytes:
    """The bytes of a small compressed bag (built once per format and compression)."""
    key = (fmt, compression)
    if key not in _SEED_BAGS:
        run = _write(tmp / f"seed-{fmt}-{compression}", fmt, compression, n=6)
        _SEED_BAGS[key] = next(p for p in run.rglob("*") if p.suffix in (".mcap", ".bag")).read_bytes()
    return _SEED_BAGS[key]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    combo=st.sampled_from([("mcap", "zstd"), ("mcap", "lz4"), ("ros1", "lz4"), ("ros1", "bz2")]),
    flips=st.lists(st.tuples(st.floats(0, 1), st.integers(1, 255)), min_size=1, max_size=8),
    cut=st.one_of(st.none(), st.floats(0.05, 1)),
)
def test_damaged_compressed_bags_read_or_fail_cleanly(
    tmp_path_factory: pytest.TempPathFactory, combo: tuple[str, str], flips: list[tuple[float, int]], cut: float | None
) -> None:
    """Bytes flipped anywhere in a compressed bag (chunk payloads, their headers, the index), and the bag cut
    short: reading every message and image either works or is one InputError naming the bag."""
    fmt, compression = combo
    data = bytearray(_seed_bag(tmp_path_factory.getbasetemp(), fmt, compression))
    for where, mask in flips:
        data[min(int(where * len(data)), len(data) - 1)] ^= mask
    if cut is not None:
        data = data[: int(cut * len(data))]
    path = tmp_path_factory.mktemp("m") / ("bag.mcap" if fmt == "mcap" else "bag.bag")
    path.write_bytes(bytes(data))
    try:
        with open_bag(path) as rec:
            for _ in rec.messages():
                pass
            for _ in rec.images():
                pass
    except InputError as exc:
        assert "\n" not in str(exc) and str(path.name) in str(exc), str(exc)
