"""PointCloud2 exactly as thesis Table 4.2 / ch. 4.2.5."""

from __future__ import annotations

import struct

import numpy as np
from recording_helpers import T0, sweep

from seatwin.recording import VLP16_LAYOUT, pack, unpack
from seatwin.recording.messages import point_cloud2, split_stamp, typestore

TABLE_4_2 = [("x", 0, 7, 1), ("y", 4, 7, 1), ("z", 8, 7, 1), ("intensity", 12, 7, 1), ("ring", 16, 4, 1), ("time", 18, 7, 1)]


def test_vlp16_layout_is_table_4_2() -> None:
    assert [(f.name, f.offset, f.datatype, f.count) for f in VLP16_LAYOUT.fields] == TABLE_4_2
    assert VLP16_LAYOUT.point_step == 24
    assert VLP16_LAYOUT.dtype.itemsize == 24


def test_pointcloud2_message_fields() -> None:
    s = sweep(1, n=10)
    store = typestore("mcap")
    msg = point_cloud2(store, T0, "lidar", VLP16_LAYOUT, pack(VLP16_LAYOUT, **s))
    assert [(f.name, f.offset, f.datatype, f.count) for f in msg.fields] == TABLE_4_2
    assert (msg.height, msg.width, msg.point_step, msg.row_step) == (1, 10, 24, 240)
    assert msg.is_bigendian is False and msg.is_dense is True
    assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (1_600_000_000, 250_000_000)
    assert msg.header.frame_id == "lidar"
    assert point_cloud2(store, T0, "lidar", VLP16_LAYOUT, pack(VLP16_LAYOUT, **s), row_step_zero=True).row_step == 0


def test_point_bytes_little_endian_at_table_offsets() -> None:
    s = {"x": [1.5], "y": [-2.0], "z": [3.25], "intensity": [0.5], "ring": [15], "time": [0.0625]}
    raw = pack(VLP16_LAYOUT, **s).tobytes()
    assert len(raw) == 24
    assert struct.unpack_from("<ffff", raw, 0) == (1.5, -2.0, 3.25, 0.5)
    assert struct.unpack_from("<H", raw, 16) == (15,)
    assert struct.unpack_from("<f", raw, 18) == (0.0625,)
    assert raw[22:24] == b"\0\0"


def test_cdr_payload_is_the_packed_points() -> None:
    """The serialised message carries the packed points verbatim, then is_dense = 1 last."""
    s = sweep(2, n=7)
    data = pack(VLP16_LAYOUT, **s)
    store = typestore("mcap")
    cdr = bytes(store.serialize_cdr(point_cloud2(store, T0, "lidar", VLP16_LAYOUT, data), "sensor_msgs/msg/PointCloud2"))
    assert cdr[:4] == b"\x00\x01\x00\x00"  # CDR little endian
    i = cdr.index(data.tobytes())
    assert struct.unpack_from("<I", cdr, i - 4) == (7 * 24,)
    assert cdr[i + 7 * 24] == 1
    ros1 = typestore("ros1")
    b1 = bytes(ros1.serialize_ros1(point_cloud2(ros1, T0, "lidar", VLP16_LAYOUT, data), "sensor_msgs/msg/PointCloud2"))
    assert b1.endswith(data.tobytes() + b"\x01")


def test_unpack_roundtrip() -> None:
    s = sweep(3, n=50)
    pts = unpack(pack(VLP16_LAYOUT, **s), VLP16_LAYOUT.fields, 24, 50)
    for k, v in s.items():
        np.testing.assert_array_equal(pts[k], v)


def test_split_stamp_rounding() -> None:
    assert split_stamp(1.9999999999) == (2, 0)
    assert split_stamp(-0.5) == (-1, 500_000_000)


def test_bad_columns_are_input_errors() -> None:
    import pytest

    from seatwin.errors import InputError

    s = sweep(4, n=5)
    with pytest.raises(InputError, match=r"'ring' \(uint16\) needs values in \[0, 65535\], got \[-1"):
        pack(VLP16_LAYOUT, **{**s, "ring": [-1, 0, 1, 2, 3]})
    with pytest.raises(InputError, match="columns differ in length"):
        pack(VLP16_LAYOUT, **{**s, "x": [1.0]})
    with pytest.raises(InputError, match="unknown field"):
        pack(VLP16_LAYOUT, rgb=[1])
    with pytest.raises(InputError, match="finite"):
        split_stamp(float("nan"))
