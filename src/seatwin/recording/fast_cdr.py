"""Direct serialisation of the messages written at every step (byte-identical to rosbags' generic serialisers).

Ground truth — ``geometry_msgs/PoseStamped``, ``nav_msgs/Odometry``, ``sensor_msgs/NavSatFix``
and ``tf2_msgs/TFMessage`` — has a fixed layout once its frame ids are known, so each
(message type, frame ids) gets one precompiled :class:`struct.Struct` and a message is one
``Struct.pack`` call (~1 µs instead of ~50 µs through the typestore). A ``sensor_msgs/PointCloud2``
of a fixed :class:`~seatwin.recording.pointcloud.Layout` is a precomputed prefix (header, fields,
sizes), the points — packed straight into the message buffer, no intermediate copy — and
``is_dense``.

Encodings: rosbag2 — little-endian CDR behind the 4-byte encapsulation header ``00 01 00 00``,
alignment relative to the end of that header, strings ``uint32`` length incl. NUL + bytes + NUL;
ROS 1 — little endian, no alignment, strings ``uint32`` length + bytes, ``Header`` begins with a
``uint32 seq`` (always 0 here, as :func:`seatwin.recording.messages.header` writes).
The values are those of the builders in :mod:`seatwin.recording.messages` (same helper functions),
covariances all zero as there. ``tests/recording/test_fast_cdr.py`` compares the bytes.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.geo import GeodeticOrigin
from seatwin.recording import messages as M
from seatwin.recording.pointcloud import Layout, checked_columns, fill

CDR_HEADER = b"\x00\x01\x00\x00"

POSE_STAMPED = "geometry_msgs/msg/PoseStamped"
ODOMETRY = "nav_msgs/msg/Odometry"
NAV_SAT_FIX = "sensor_msgs/msg/NavSatFix"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
POINT_CLOUD2 = "sensor_msgs/msg/PointCloud2"

VesselFrames = tuple[str, "str | None", str, str]
"""A vessel's frame ids for :meth:`GroundTruthEncoder.step`: (FRD body, GNSS antenna or None for no
NavSatFix, odom, FLU base_link)."""


class _Layout:
    """Builds a ``struct`` format for one message, inserting CDR alignment padding (none for ROS 1)."""

    def __init__(self, ros1: bool) -> None:
        self.ros1 = ros1
        self.parts = ["<"] if ros1 else ["<4s"]  # CDR: the encapsulation header is passed as an argument
        self.pos = 0

    def _align(self, size: int) -> None:
        pad = 0 if self.ros1 else -self.pos % size
        if pad:
            self.parts.append(f"{pad}x")
            self.pos += pad

    def add(self, code: str, count: int = 1) -> _Layout:
        size = struct.calcsize("<" + code)
        self._align(size)
        self.parts.append(f"{count}{code}" if count != 1 else code)
        self.pos += size * count
        return self

    def zeros(self, n_f64: int) -> _Layout:
        """``n_f64`` float64 that are always zero (a covariance): padding bytes, aligned as float64."""
        self._align(8)
        self.parts.append(f"{8 * n_f64}x")
        self.pos += 8 * n_f64
        return self

    def string(self, text: str) -> _Layout:
        """A string field; pass ``len`` (see :meth:`strlen`) and the encoded bytes as arguments."""
        n = len(text.encode()) + (0 if self.ros1 else 1)
        self.add("I")
        self.parts.append(f"{n}s")  # struct pads the missing NUL with a zero byte
        self.pos += n
        return self

    def header(self, frame_id: str) -> _Layout:
        if self.ros1:
            self.add("I")  # seq
        return self.add("i").add("I").string(frame_id)

    def build(self) -> struct.Struct:
        return struct.Struct("".join(self.parts))


class GroundTruthEncoder:
    """Serialise ground-truth messages for a bag format (``mcap``/``sqlite3``: CDR, ``ros1``: ROS 1)."""

    def __init__(self, fmt: str) -> None:
        self.ros1 = fmt == "ros1"
        self._lead: tuple[object, ...] = (0,) if self.ros1 else (CDR_HEADER,)  # ROS 1 seq | CDR header
        self._structs: dict[tuple[str, ...], struct.Struct] = {}
        self._strings: dict[str, tuple[int, bytes]] = {}
        self._middles: dict[tuple[str, ...], bytes] = {}
        self._lead_bytes = bytes(4) if self.ros1 else CDR_HEADER  # ROS 1 seq 0 | CDR header
        T = M.typestore(fmt).types
        nss = T["sensor_msgs/msg/NavSatStatus"]
        self._fix_status = (nss.STATUS_FIX, nss.SERVICE_GPS, T[NAV_SAT_FIX].COVARIANCE_TYPE_KNOWN)

    def _str(self, text: str) -> tuple[int, bytes]:
        s = self._strings.get(text)
        if s is None:
            b = text.encode()
            s = self._strings[text] = (len(b) + (0 if self.ros1 else 1), b)
        return s

    def _struct(self, key: tuple[str, ...]) -> struct.Struct:
        s = self._structs.get(key)
        if s is None:
            kind, names = key[0], key[1:]
            lay = _Layout(self.ros1)
            if kind == "pose":
                lay.header(names[0]).add("d", 7)
            elif kind == "odom":
                lay.header(names[0]).string(names[1]).add("d", 7).zeros(36).add("d", 6).zeros(36)
            elif kind == "fix":
                lay.header(names[0]).add("b").add("H").add("d", 3).zeros(9).add("B")
            else:  # tf: (parent, child) pairs
                lay.add("I")
                for parent, child in zip(names[0::2], names[1::2]):
                    lay.header(parent).string(child).add("d", 7)
            s = self._structs[key] = lay.build()
        return s

    def _middle(self, key: tuple[str, ...], tail: struct.Struct) -> bytes:
        """The constant bytes of message ``key`` between its stamp and its ``tail`` (frame ids, padding)."""
        m = self._middles.get(key)
        if m is None:
            st = self._struct(key)
            strings = [x for name in key[1:] for x in self._str(name)]
            full = st.pack(*self._lead, 0, 0, *strings, *([0.0] * _count_values(tail)))
            m = self._middles[key] = full[12 : len(full) - tail.size]  # lead (4) + stamp (8) … tail
        return m

    def pose_stamped(self, t: float, world_frame: str, v: M.VesselPose) -> bytes:
        """= serialised :func:`messages.pose_stamped`."""
        return self._pose(self._head(M.split_stamp(t)), world_frame, v, M.quaternion_yaw(v.heading))

    def odometry(self, t: float, world_frame: str, body_frame: str, v: M.VesselPose) -> bytes:
        """= serialised :func:`messages.odometry`."""
        return self._odometry(self._head(M.split_stamp(t)), world_frame, body_frame, v, M.quaternion_yaw(v.heading))

    def _head(self, stamp: tuple[int, int]) -> bytes:
        """The first 12 bytes of every header-first message: CDR header (ROS 1: seq 0) and the stamp."""
        return self._lead_bytes + _STAMP.pack(*stamp)

    def nav_sat_fix(self, t: float, frame_id: str, v: M.VesselPose, origin: GeodeticOrigin | None) -> bytes:
        """= serialised :func:`messages.nav_sat_fix` (the pose's ``llh`` if it has one, else converted about ``origin``)."""
        return self._fix(M.split_stamp(t), frame_id, v, origin)

    def tf_message(self, t: float, transforms: Sequence[tuple[str, str, Sequence[float], Sequence[float]]]) -> bytes:
        """= serialised :func:`messages.tf_message` of :func:`messages.transform_stamped` items, all stamped ``t``;
        ``transforms``: (parent, child, translation xyz, rotation xyzw)."""
        return self._tf(M.split_stamp(t), transforms)

    def step(
        self, t: float, world_frame: str, vessels: Sequence[tuple[M.VesselPose, VesselFrames]], origin: GeodeticOrigin | None
    ) -> list[bytes]:
        """One ground-truth step: per vessel its PoseStamped and Odometry (in ``world_frame``, FRD body) and,
        with a GNSS frame, NavSatFix; then one TFMessage of every vessel's FLU ``base_link`` in its ``odom``."""
        stamp = M.split_stamp(t)
        head = self._head(stamp)
        out: list[bytes] = []
        tfs = []
        for v, (body, gnss, odom, base) in vessels:
            q = M.quaternion_yaw(v.heading)
            out.append(self._pose(head, world_frame, v, q))
            out.append(self._odometry(head, world_frame, body, v, q))
            if gnss is not None:
                out.append(self._fix(stamp, gnss, v, origin))
            q_base = M.quaternion_yaw(math.pi / 2 - v.heading)  # = tf_tree.base_link_pose
            tfs.append((odom, base, (v.east, v.north, -v.down), q_base))
        if tfs:
            out.append(self._tf(stamp, tfs))
        return out

    def _pose(self, head: bytes, world_frame: str, v: M.VesselPose, q: Sequence[float]) -> bytes:
        mid = self._middles.get(("pose", world_frame)) or self._middle(("pose", world_frame), _POSE_TAIL)
        return head + mid + _POSE_TAIL.pack(v.north, v.east, v.down, q[0], q[1], q[2], q[3])

    def _odometry(self, head: bytes, world_frame: str, body_frame: str, v: M.VesselPose, q: Sequence[float]) -> bytes:
        key = ("odom", world_frame, body_frame)
        mid = self._middles.get(key) or self._middle(key, _ODOM_TAIL)
        u, w = M.body_velocity(v)
        return head + mid + _ODOM_TAIL.pack(v.north, v.east, v.down, q[0], q[1], q[2], q[3], u, w, 0.0, 0.0, 0.0, v.yaw_rate)

    def _fix(self, stamp: tuple[int, int], frame_id: str, v: M.VesselPose, origin: GeodeticOrigin | None) -> bytes:
        return self._struct(("fix", frame_id)).pack(
            *self._lead, *stamp, *self._str(frame_id), *self._fix_status[:2], *M.vessel_llh(v, origin), self._fix_status[2]
        )

    def _tf(self, stamp: tuple[int, int], transforms: Sequence[tuple[str, str, Sequence[float], Sequence[float]]]) -> bytes:
        key: list[str] = ["tf"]
        args: list[object] = [len(transforms)] if self.ros1 else [CDR_HEADER, len(transforms)]
        for parent, child, p, q in transforms:
            key += (parent, child)
            if self.ros1:
                args.append(0)
            args += (*stamp, *self._str(parent), *self._str(child), p[0], p[1], p[2], q[0], q[1], q[2], q[3])
        return self._struct(tuple(key)).pack(*args)


class _Bytes:
    """A message's bytes built field by field with the format's alignment; :meth:`put` returns the offset."""

    def __init__(self, ros1: bool) -> None:
        self.ros1 = ros1
        self.buf = bytearray() if ros1 else bytearray(CDR_HEADER)

    def put(self, code: str, value: int) -> int:
        size = struct.calcsize("<" + code)
        if not self.ros1:
            self.buf += bytes(-(len(self.buf) - len(CDR_HEADER)) % size)
        at = len(self.buf)
        self.buf += struct.pack("<" + code, value)
        return at

    def string(self, text: str) -> None:
        b = text.encode()
        self.put("I", len(b) + (0 if self.ros1 else 1))
        self.buf += b if self.ros1 else b + b"\0"


class PointCloudEncoder:
    """Serialise ``sensor_msgs/PointCloud2`` of a fixed layout (height 1, little endian) for a bag format.

    = serialised :func:`messages.point_cloud2`; the points are packed into the message itself.
    """

    def __init__(self, fmt: str, row_step_zero: bool = False) -> None:
        self.ros1 = fmt == "ros1"
        self.row_step_zero = row_step_zero
        self._prefixes: dict[tuple[str, int], tuple[Layout, bytes, int, int, int, int]] = {}

    def _prefix(self, frame_id: str, layout: Layout) -> tuple[Layout, bytes, int, int, int, int]:
        """(layout, bytes up to the data, offsets of stamp, width, row_step, data length), cached by layout
        identity (hashing a layout costs more than encoding a small cloud; the entry keeps it alive)."""
        p = self._prefixes.get((frame_id, id(layout)))
        if p is None or p[0] is not layout:
            b = _Bytes(self.ros1)
            if self.ros1:
                b.put("I", 0)  # seq
            stamp = b.put("i", 0)
            b.put("I", 0)
            b.string(frame_id)
            b.put("I", 1)  # height
            width = b.put("I", 0)
            b.put("I", len(layout.fields))
            for f in layout.fields:
                b.string(f.name)
                b.put("I", f.offset)
                b.put("B", f.datatype)
                b.put("I", f.count)
            b.put("B", 0)  # is_bigendian
            b.put("I", layout.point_step)
            row_step = b.put("I", 0)
            size = b.put("I", 0)
            p = self._prefixes[(frame_id, id(layout))] = (layout, bytes(b.buf), stamp, width, row_step, size)
        return p

    def _message(self, t: float, frame_id: str, layout: Layout, n: int, is_dense: bool) -> tuple[bytearray, NDArray[Any]]:
        """A zeroed message for ``n`` points, everything but the points filled in, and a view of its points."""
        _, prefix, at_stamp, at_width, at_row, at_size = self._prefix(frame_id, layout)
        nbytes = n * layout.point_step
        msg = bytearray(len(prefix) + nbytes + 1)
        msg[: len(prefix)] = prefix
        sec, nsec = M.split_stamp(t)
        _II.pack_into(msg, at_stamp, sec & 0xFFFFFFFF, nsec)
        _I.pack_into(msg, at_width, n)
        _I.pack_into(msg, at_row, 0 if self.row_step_zero else nbytes)
        _I.pack_into(msg, at_size, nbytes)
        msg[-1] = 1 if is_dense else 0
        points = np.frombuffer(msg, dtype=layout.dtype, count=n, offset=len(prefix))
        return msg, points

    def encode(
        self, t: float, frame_id: str, layout: Layout, columns: dict[str, ArrayLike | None], is_dense: bool = True
    ) -> bytearray:
        """Columns of ``layout`` (absent ones 0, checked as :func:`pointcloud.pack` checks them) → the message."""
        arrays, n = checked_columns(layout, columns)
        msg, points = self._message(t, frame_id, layout, n, is_dense)
        fill(points, arrays)
        return msg

    def encode_packed(self, t: float, frame_id: str, layout: Layout, data: NDArray[np.uint8], is_dense: bool = True) -> bytearray:
        """Points already packed (:func:`pointcloud.pack`) → the message."""
        raw = np.ascontiguousarray(data).view(np.uint8).reshape(-1)
        if raw.size % layout.point_step:
            raise InputError(
                "point cloud", f"{raw.size} bytes of points are not a whole number of {layout.point_step}-byte points"
            )
        msg, points = self._message(t, frame_id, layout, raw.size // layout.point_step, is_dense)
        points.view(np.uint8)[:] = raw[: points.nbytes]
        return msg


_I = struct.Struct("<I")
_II = struct.Struct("<II")
_STAMP = struct.Struct("<iI")
_POSE_TAIL = struct.Struct("<7d")
"""PoseStamped after its frame id: position, orientation."""
_ODOM_TAIL = struct.Struct("<7d288x6d288x")
"""Odometry after its frame ids: pose, its covariance (zero), twist, its covariance (zero)."""


def _count_values(st: struct.Struct) -> int:
    """How many values ``st`` packs (all ``d`` here)."""
    return len(st.unpack(bytes(st.size)))
