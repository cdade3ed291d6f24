"""The direct serialisers (ground truth, PointCloud2) are byte-identical to rosbags' generic ones (CDR and ROS 1)."""

from __future__ import annotations

from dataclasses import astuple
from pathlib import Path

import numpy as np
import pytest
from recording_helpers import ORIGIN  # noqa: E402  (conftest puts the folder on sys.path)

from seatwin.recording import RecordingWriter, VesselPose, open_bag
from seatwin.recording import messages as M
from seatwin.recording.fast_cdr import GroundTruthEncoder
from seatwin.recording.tf_tree import base_link_pose, vessel_transforms
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sim.poses import poses_from_scenario

NAMES = ["a", "ab", "abc", "abcd", "abcde", "milliAmpere", "Havfruen_2", "bøye"]  # lengths 1..11, non-ASCII
TIMES = [1_600_000_000.123456789, 0.5, 12.0, 1_700_000_000.9999999999]
VALUES = [(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (-1234.5, 1e7, -2.1, -3.5, 4.25, -0.02), (3e5, -7e-9, 7.0, 1e3, -1e-3, 5.0)]


def _serializer(fmt: str):
    store = M.typestore(fmt)
    return store, (store.serialize_ros1 if fmt == "ros1" else store.serialize_cdr)


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
def test_messages_byte_exact(fmt: str) -> None:
    store, ser = _serializer(fmt)
    enc = GroundTruthEncoder(fmt)
    for i, name in enumerate(NAMES):
        world, body = "w" * (i + 1), f"{name}/base_link"
        for t in TIMES:
            for north, east, heading, vn, ve, r in VALUES:
                v = VesselPose(name, north, east, heading, down=-0.5 * i, v_north=vn, v_east=ve, yaw_rate=r, ownship=True)
                assert enc.pose_stamped(t, world, v) == bytes(
                    ser(M.pose_stamped(store, t, world, v), "geometry_msgs/msg/PoseStamped")
                )
                assert enc.odometry(t, world, body, v) == bytes(
                    ser(M.odometry(store, t, world, body, v), "nav_msgs/msg/Odometry")
                )
                assert enc.nav_sat_fix(t, body, v, ORIGIN) == bytes(
                    ser(M.nav_sat_fix(store, t, body, v, ORIGIN), "sensor_msgs/msg/NavSatFix")
                )
                tfs = [
                    (world, body, (north, east, v.down), M.quaternion_yaw(heading)),
                    (NAMES[-1 - i], name, (east, -north, 1e9), (0.1, -0.2, 0.3, 0.9)),
                ][: 1 + i % 2]
                generic = M.tf_message(store, [M.transform_stamped(store, t, *x) for x in tfs])
                assert enc.tf_message(t, tfs) == bytes(ser(generic, "tf2_msgs/msg/TFMessage"))
    assert enc.tf_message(1.0, []) == bytes(ser(M.tf_message(store, []), "tf2_msgs/msg/TFMessage"))


def _generic_ground_truth(w: RecordingWriter, t: float, vessels: list[VesselPose]) -> None:
    """The former typestore path of :meth:`RecordingWriter.write_ground_truth` (reference)."""
    tp, tfs = w.topics, []
    if not w._static_written:
        _generic_static(w, t, [])
    if not w.vessels:  # each vessel's fixed frames, when it first appears
        fixed = [s for v in vessels for s in vessel_transforms(tp, v.name, gnss=v.ownship and w.origin is not None)]
        w.write(tp.tf_static, t, M.tf_message(w.store, [M.transform_stamped(w.store, t, *astuple(s)) for s in fixed]))
    for v in vessels:
        w.vessels[v.name] = "ownship" if v.ownship else "target"
        body = tp.body(v.name)
        w.write(tp.topic("pose", vessel=v.name), t, M.pose_stamped(w.store, t, tp.world_frame, v))
        w.write(tp.topic("odom", vessel=v.name), t, M.odometry(w.store, t, tp.world_frame, body, v))
        if v.ownship and w.origin is not None:
            w.write(tp.topic("fix", vessel=v.name), t, M.nav_sat_fix(w.store, t, tp.frame("gnss_frame", v.name), v, w.origin))
        odom, base = tp.frame("odom_frame", v.name), tp.frame("base_frame", v.name)
        tfs.append(M.transform_stamped(w.store, t, odom, base, *base_link_pose(v)))
    w.write(tp.tf, t, M.tf_message(w.store, tfs))


def _generic_static(w: RecordingWriter, t: float, mounts: list[M.StaticTransform]) -> None:
    """The former typestore path of :meth:`RecordingWriter.write_static_transforms` (reference)."""
    tp = w.topics
    items = list(mounts)
    if not w._static_written:
        items.insert(
            0, M.StaticTransform(tp.display_frame, tp.world_frame, (0.0, 0.0, 0.0), M.quaternion_from_matrix(M.R_ENU_NED))
        )
    msgs = [M.transform_stamped(w.store, t, s.parent, s.child, s.translation, s.rotation) for s in items]
    w.write(tp.tf_static, t, M.tf_message(w.store, msgs))
    w._static_written = True


def test_static_transforms_byte_exact(tmp_path: Path, fmt: str) -> None:
    mounts = [
        M.StaticTransform("milliAmpere/base_link_frd", "lidar", (0.5, -0.25, -2.0), M.mount_rotation("flu", 0.01, -0.02, 0.3)),
        M.StaticTransform("milliAmpere/base_link_frd", "camera_optical", (1.0, 0.0, -1.5), M.mount_rotation("optical")),
    ]
    raw = {}
    for kind in ("fast", "generic"):
        with RecordingWriter(tmp_path / kind, fmt) as w:
            if kind == "fast":
                w.write_static_transforms(ORIGIN_T, mounts)
                w.write_static_transforms(ORIGIN_T + 1, mounts[:1])
            else:
                _generic_static(w, ORIGIN_T, mounts)
                _generic_static(w, ORIGIN_T + 1, mounts[:1])
        with open_bag(tmp_path / kind) as rec:
            raw[kind] = [(topic, ts, bytes(data)) for topic, _, ts, data in rec.raw_messages()]
    assert len(raw["fast"]) == 2 and raw["fast"] == raw["generic"]


ORIGIN_T = 1_600_000_000.5


def test_simulated_ground_truth_reads_back_identically(tmp_path: Path, fmt: str) -> None:
    sc = builtin_scenario("ferry_crossing")
    steps = [(sc.start + 0.1 * k, poses_from_scenario(sc, sc.start + 0.1 * k)) for k in range(25)]
    raw = {}
    for kind in ("fast", "generic"):
        with RecordingWriter(tmp_path / kind, fmt, origin=ORIGIN, flush_interval_s=0.5) as w:
            for t, vessels in steps:
                if kind == "fast":
                    w.write_ground_truth(t, vessels)
                else:
                    _generic_ground_truth(w, t, vessels)
        with open_bag(tmp_path / kind) as rec:
            raw[kind] = sorted((topic, ts, msgtype, bytes(data)) for topic, msgtype, ts, data in rec.raw_messages())
        assert w.counts[w.topics.tf] == len(steps)
    assert raw["fast"] == raw["generic"]
    assert len({r[0] for r in raw["fast"]}) == 2 * len(sc.vessels) + 3  # pose+odom each, fix, /tf, /tf_static
    with open_bag(tmp_path / "fast") as rec:
        truth = rec.ground_truth()
    assert set(truth) == {v.name for v in steps[0][1]}
    for v in steps[-1][1]:
        vt = truth[v.name]
        assert len(vt.time) == len(steps)
        assert (vt.north[-1], vt.east[-1], vt.heading[-1]) == pytest.approx((v.north, v.east, v.heading), abs=1e-12)


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
@pytest.mark.parametrize("row_step_zero", [False, True])
def test_point_cloud2_byte_exact(fmt: str, row_step_zero: bool) -> None:
    """The direct PointCloud2 (points packed into the message) = rosbags' serialiser on messages.point_cloud2."""
    from seatwin.recording import RADAR_LAYOUT, VLP16_LAYOUT, pack
    from seatwin.recording.fast_cdr import POINT_CLOUD2, PointCloudEncoder
    from seatwin.rng import frame_rng

    store, ser = _serializer(fmt)
    enc = PointCloudEncoder(fmt, row_step_zero=row_step_zero)
    rng = frame_rng(0, "test/cloud", 0)
    for i, frame in enumerate(["", "l", "li", "lid", "lidar", "velodyne_top", "bøye/radar"]):
        for layout in (VLP16_LAYOUT, RADAR_LAYOUT):
            for n in (0, 1, 3, 1000):
                cols = {f.name: rng.normal(size=n) for f in layout.fields}
                if "ring" in cols:
                    cols["ring"] = rng.integers(0, 16, n)
                t = TIMES[(i + n) % len(TIMES)]
                data = pack(layout, **cols)
                for dense in (True, False):
                    want = bytes(
                        ser(
                            M.point_cloud2(store, t, frame, layout, data, is_dense=dense, row_step_zero=row_step_zero),
                            POINT_CLOUD2,
                        )
                    )
                    assert bytes(enc.encode(t, frame, layout, cols, is_dense=dense)) == want
                    assert bytes(enc.encode_packed(t, frame, layout, data, is_dense=dense)) == want


def test_point_cloud2_checks_columns_as_pack_does() -> None:
    from seatwin.errors import InputError
    from seatwin.recording import VLP16_LAYOUT
    from seatwin.recording.fast_cdr import PointCloudEncoder

    enc = PointCloudEncoder("mcap")
    with pytest.raises(InputError, match="needs values in"):
        enc.encode(1.0, "lidar", VLP16_LAYOUT, {"x": [0.0, 1.0], "ring": [0, 70_000]})
    with pytest.raises(InputError, match="columns differ in length"):
        enc.encode(1.0, "lidar", VLP16_LAYOUT, {"x": [0.0, 1.0], "y": [0.0]})
    with pytest.raises(InputError, match="whole number"):
        enc.encode_packed(1.0, "lidar", VLP16_LAYOUT, np.zeros(25, np.uint8))


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
def test_nav_sat_fix_takes_a_converted_position(fmt: str) -> None:
    """A pose carrying its WGS-84 position (converted for a whole run at once) is written as given."""
    from dataclasses import replace

    enc = GroundTruthEncoder(fmt)
    v = VesselPose("own", 120.0, -40.0, 0.3, down=-1.0, ownship=True)
    llh = M.vessel_llh(v, ORIGIN)
    assert enc.nav_sat_fix(5.0, "own/base_link", replace(v, llh=llh), None) == enc.nav_sat_fix(5.0, "own/base_link", v, ORIGIN)
    store, ser = _serializer(fmt)
    moved = replace(v, llh=(63.0, 10.0, 5.0))
    assert enc.nav_sat_fix(5.0, "b", moved, ORIGIN) == bytes(
        ser(M.nav_sat_fix(store, 5.0, "b", moved, ORIGIN), "sensor_msgs/msg/NavSatFix")
    )
