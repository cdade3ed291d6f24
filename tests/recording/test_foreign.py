"""Reading bags we did not write: other PointCloud2 layouts (Ouster-like, big endian, padded rows),
bags written straight with rosbags in all three formats, images of every supported encoding."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from recording_helpers import T0

from seatwin.errors import InputError
from seatwin.recording import open_bag
from seatwin.recording.images import encode_image
from seatwin.recording.messages import compressed_image, header, typestore
from seatwin.rng import frame_rng

# Ouster os1 driver style: x,y,z float32, 4 bytes padding, intensity float32, t uint32, reflectivity
# uint16, ring uint8, ambient uint16, range uint32; point_step 48 (padding at the end too).
OUSTER = [
    ("x", 0, 7),
    ("y", 4, 7),
    ("z", 8, 7),
    ("intensity", 16, 7),
    ("t", 20, 6),
    ("reflectivity", 24, 4),
    ("ring", 26, 2),
    ("ambient", 28, 4),
    ("range", 32, 6),
]
OUSTER_DTYPE = np.dtype(
    {
        "names": [f[0] for f in OUSTER],
        "formats": ["f4", "f4", "f4", "f4", "u4", "u2", "u1", "u2", "u4"],
        "offsets": [f[1] for f in OUSTER],
        "itemsize": 48,
    }
)


def _ouster_points(n: int, seed: int = 0, big_endian: bool = False) -> np.ndarray:
    rng = frame_rng(seed, "test/ouster", 0)
    dt = OUSTER_DTYPE.newbyteorder(">") if big_endian else OUSTER_DTYPE
    p = np.zeros(n, dt)
    for name in OUSTER_DTYPE.names:
        p[name] = rng.integers(0, 200, n)
    p["x"] = rng.normal(size=n)
    return p


def _cloud(store, points: np.ndarray, height: int, row_pad: int, big_endian: bool):
    T = store.types
    PF = T["sensor_msgs/msg/PointField"]
    width = points.size // height
    rows = points.view(np.uint8).reshape(height, width * 48)
    data = np.concatenate([rows, np.full((height, row_pad), 0xAB, np.uint8)], axis=1).reshape(-1)
    return T["sensor_msgs/msg/PointCloud2"](
        header=header(store, T0, "os_sensor"),
        height=height,
        width=width,
        fields=[PF(name=n, offset=o, datatype=d, count=1) for n, o, d in OUSTER],
        is_bigendian=big_endian,
        point_step=48,
        row_step=width * 48 + row_pad,
        data=data,
        is_dense=False,
    )


def _write_foreign(path: Path, fmt: str, msgs: dict[str, list]) -> None:
    """A bag written directly with rosbags (no manifest): the way real datasets arrive."""
    store = typestore(fmt)
    if fmt == "ros1":
        from rosbags.rosbag1 import Writer

        w = Writer(path)
    else:
        from rosbags.rosbag2 import StoragePlugin, Writer

        w = Writer(path, version=8, storage_plugin=StoragePlugin.MCAP if fmt == "mcap" else StoragePlugin.SQLITE3)
    with w:
        for topic, items in msgs.items():
            conn = w.add_connection(topic, items[0].__msgtype__, typestore=store)
            for k, m in enumerate(items):
                ser = store.serialize_ros1 if fmt == "ros1" else store.serialize_cdr
                w.write(conn, int(T0 * 1e9) + k * 100_000_000, ser(m, m.__msgtype__))


@pytest.mark.parametrize("big_endian", [False, True])
def test_ouster_like_layout_with_padded_rows(tmp_path: Path, fmt: str, big_endian: bool) -> None:
    store = typestore(fmt)
    pts = _ouster_points(2 * 64, big_endian=big_endian)
    path = tmp_path / ("real.bag" if fmt == "ros1" else "real")
    _write_foreign(path, fmt, {"/os_cloud_node/points": [_cloud(store, pts, 2, 16, big_endian)]})
    with open_bag(path) as rec:
        assert rec.complete is None  # a foreign bag: no manifest
        (c,) = list(rec.point_clouds())
        assert (c.height, c.width, c.is_dense, c.frame_id) == (2, 64, False, "os_sensor")
        assert c.points.dtype.names == OUSTER_DTYPE.names
        for name in OUSTER_DTYPE.names:
            np.testing.assert_array_equal(c.points[name], pts[name])
        assert c.xyz().shape == (128, 3)


def test_fields_with_count_and_unknown_datatype() -> None:
    from types import SimpleNamespace as F

    from seatwin.recording import dtype_from_fields, unpack

    dt = dtype_from_fields([F(name="normal", offset=0, datatype=7, count=3), F(name="", offset=12, datatype=7, count=1)], 16)
    assert dt["normal"].shape == (3,)
    p = unpack(np.arange(32, dtype=np.float32).view(np.uint8), [F(name="normal", offset=0, datatype=7, count=3)], 16, 2)
    np.testing.assert_array_equal(p["normal"][1], [4, 5, 6])
    with pytest.raises(InputError, match="unknown datatype 9"):
        dtype_from_fields([F(name="x", offset=0, datatype=9, count=1)], 4)
    with pytest.raises(InputError, match="exceeds point_step"):
        dtype_from_fields([F(name="x", offset=2, datatype=7, count=1)], 4)
    with pytest.raises(InputError, match="data has 8 bytes"):
        unpack(np.zeros(8, np.uint8), [F(name="x", offset=0, datatype=7, count=1)], 4, 3)


def test_images_all_encodings(tmp_path: Path, fmt: str) -> None:
    store = typestore(fmt)
    rng = frame_rng(1, "test/images", 0)
    bgr = rng.integers(0, 255, (5, 7, 3), dtype=np.uint8)
    mono = rng.integers(0, 255, (5, 7), dtype=np.uint8)
    yy, xx = np.mgrid[0:16, 0:16]
    smooth = np.stack([xx * 8, yy * 8, np.full_like(xx, 128)], axis=2).astype(np.uint8)
    T = store.types

    def img(enc: str, a: np.ndarray, pad: int = 0):
        h, w = a.shape[:2]
        rows = a.reshape(h, -1)
        data = np.concatenate([rows, np.zeros((h, pad), np.uint8)], axis=1).reshape(-1)
        return T["sensor_msgs/msg/Image"](
            header=header(store, T0, "cam"), height=h, width=w, encoding=enc, is_bigendian=0, step=rows.shape[1] + pad, data=data
        )

    msgs = {
        "/cam/bgr": [img("bgr8", bgr, pad=3)],
        "/cam/rgb": [img("rgb8", bgr[..., ::-1].copy())],
        "/cam/mono": [img("mono8", mono, pad=1)],
        "/cam/png": [compressed_image(store, T0, "cam", encode_image(bgr, "png", "bgr8"), "png")],
        "/cam/jpeg": [compressed_image(store, T0, "cam", encode_image(smooth, "jpeg", "bgr8", quality=95), "jpeg")],
    }
    path = tmp_path / ("real.bag" if fmt == "ros1" else "real")
    _write_foreign(path, fmt, msgs)
    with open_bag(path) as rec:
        frames = {f.topic: f for f in rec.images()}
    np.testing.assert_array_equal(frames["/cam/bgr"].pixels, bgr)
    np.testing.assert_array_equal(frames["/cam/rgb"].pixels[..., ::-1], bgr)
    np.testing.assert_array_equal(frames["/cam/mono"].pixels[..., 0], mono)
    assert frames["/cam/png"].encoding == "bgr8" and frames["/cam/png"].compressed_format == "png"
    np.testing.assert_array_equal(frames["/cam/png"].pixels, bgr)  # lossless
    assert np.abs(frames["/cam/jpeg"].pixels.astype(int) - smooth).mean() < 3  # lossy, same channel order


def test_compressed_images_written_by_us(tmp_path: Path) -> None:
    from seatwin.recording import RecordingWriter

    a = frame_rng(2, "test/images", 0).integers(0, 255, (4, 6, 3), dtype=np.uint8)
    with RecordingWriter(tmp_path / "run") as w:
        w.write_compressed_image("/cam/image_raw/compressed", "cam", T0, a, fmt="png")
    with open_bag(tmp_path / "run") as rec:
        (f,) = list(rec.images())
    np.testing.assert_array_equal(f.pixels, a)


def test_unsupported_encoding_is_input_error(tmp_path: Path) -> None:
    store = typestore("mcap")
    m = store.types["sensor_msgs/msg/Image"](
        header=header(store, T0, "c"),
        height=1,
        width=1,
        encoding="bayer_rggb8",
        is_bigendian=0,
        step=1,
        data=np.zeros(1, np.uint8),
    )
    _write_foreign(tmp_path / "b", "mcap", {"/c": [m]})
    with pytest.raises(InputError, match="unsupported image encoding 'bayer_rggb8'"):
        list(open_bag(tmp_path / "b").images())


def test_ros1_profile_mcap_with_zstd_chunks(tmp_path: Path) -> None:
    """ROS 1 data in MCAP (as `mcap convert` makes from a .bag), zstd-compressed chunks."""
    from mcap.writer import CompressionType, Writer

    store = typestore("ros1")
    pts = _ouster_points(64)
    msg = _cloud(store, pts, 1, 0, False)
    msgdef, _ = store.generate_msgdef("sensor_msgs/msg/PointCloud2")
    path = tmp_path / "ros1.mcap"
    with path.open("wb") as f:
        w = Writer(f, compression=CompressionType.ZSTD)
        w.start(profile="ros1")
        sid = w.register_schema("sensor_msgs/PointCloud2", "ros1msg", msgdef.encode())
        cid = w.register_channel("/points", "ros1", sid)
        for k in range(3):
            w.add_message(cid, int(T0 * 1e9) + k, bytes(store.serialize_ros1(msg, msg.__msgtype__)), int(T0 * 1e9) + k)
        w.finish()
    with open_bag(path) as rec:
        assert not rec.recovered and rec.topics["/points"].count == 3
        clouds = list(rec.point_clouds("/points"))
    assert len(clouds) == 3
    np.testing.assert_array_equal(clouds[2].points["range"], pts["range"])
