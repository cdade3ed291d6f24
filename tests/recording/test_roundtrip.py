"""Write → read in MCAP, SQLite3 and ROS 1: every message type, the manifest and the ground truth."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from recording_helpers import ORIGIN, T0, sweep, vessels, write_run

from seatwin.errors import InputError
from seatwin.geo import ned_to_llh_exact
from seatwin.recording import RecordingWriter, TopicConfig, VesselPose, open_bag
from seatwin.recording.messages import R_ENU_NED, mount_rotation, typestore


def test_roundtrip_all_formats(tmp_path: Path, fmt: str) -> None:
    w = write_run(tmp_path / "run", fmt)
    assert w.timing["total_s"] >= w.timing["write_s"] + w.timing["serialize_s"] > 0
    with open_bag(tmp_path / "run") as rec:
        assert rec.format == fmt
        assert rec.complete is True and not rec.recovered
        assert rec.topics["/lidar/points"].count == 5
        assert rec.topics["/lidar/points"].msgtype == "sensor_msgs/msg/PointCloud2"
        assert rec.topics["/ground_truth/milliAmpere/fix"].msgtype == "sensor_msgs/msg/NavSatFix"
        assert "/ground_truth/Havfruen/fix" not in rec.topics
        assert rec.duration_s == pytest.approx(0.4, abs=1e-6)

        clouds = list(rec.point_clouds("/lidar/points"))
        assert [c.stamp for c in clouds] == pytest.approx([T0 + 0.1 * k for k in range(5)], abs=1e-6)
        for k, c in enumerate(clouds):
            assert c.frame_id == "lidar" and c.is_dense and c.height == 1
            for name, values in sweep(k).items():
                np.testing.assert_array_equal(c.points[name], values)

        frames = list(rec.images())
        assert len(frames) == 5 and frames[2].encoding == "bgr8"
        assert frames[2].pixels.shape == (6, 8, 3) and tuple(frames[2].pixels[0, 0]) == (1, 2, 3)

        radar = list(rec.radar_scans())
        assert len(radar) == 5
        r = radar[0].points
        np.testing.assert_allclose(r["range"], [10.0, 20.0])
        # radar frame is REP-103 (y left): a plot at y = −20 (to starboard) is at bearing +90° clockwise
        np.testing.assert_allclose(r["bearing"], [0.0, math.pi / 2], atol=1e-6)
        np.testing.assert_allclose(r["intensity"], [1.0, 2.0])

        truth = rec.ground_truth()
        assert set(truth) == {"milliAmpere", "Havfruen"}
        own = truth["milliAmpere"]
        assert own.ownship and not truth["Havfruen"].ownship
        np.testing.assert_allclose(own.north, [1.0 + k for k in range(5)])
        np.testing.assert_allclose(own.heading, 0.5, atol=1e-12)
        np.testing.assert_allclose(own.v_north, 1.5, atol=1e-12)  # body twist rotated back to NED
        np.testing.assert_allclose(own.v_east, -0.5, atol=1e-12)
        np.testing.assert_allclose(own.yaw_rate, 0.01)
        np.testing.assert_allclose(truth["Havfruen"].heading, -2.0, atol=1e-12)

        fixes = [m.msg for m in rec.messages("/ground_truth/milliAmpere/fix")]
        lat, lon, alt = ned_to_llh_exact(3.0, 2.0, 0.0, ORIGIN)
        assert fixes[2].latitude == pytest.approx(float(lat), abs=1e-12)
        assert fixes[2].longitude == pytest.approx(float(lon), abs=1e-12)

        statics = {(s.parent, s.child): s for s in rec.static_transforms()}
        fixed = {("map", "world_ned"), ("milliAmpere/base_link_frd", "lidar"), ("milliAmpere/base_link", "milliAmpere/gnss")}
        for v in ("milliAmpere", "Havfruen"):
            fixed |= {("map", f"{v}/odom"), (f"{v}/base_link", f"{v}/base_link_frd")}
        assert set(statics) == fixed  # the ownship's NavSatFix in its GNSS antenna frame
        assert {f.header.frame_id for f in fixes} == {"milliAmpere/gnss"}
        tf = [m.msg for m in rec.messages("/tf")]
        assert [t.child_frame_id for t in tf[0].transforms] == ["milliAmpere/base_link", "Havfruen/base_link"]
        assert [t.header.frame_id for t in tf[0].transforms] == ["milliAmpere/odom", "Havfruen/odom"]

    inner = tmp_path / "run" / ("recording.bag" if fmt == "ros1" else "recording")
    with open_bag(inner) as rec:  # the bag itself, inside its run directory: the manifest is found
        assert rec.run_dir == tmp_path / "run" and rec.complete is True

    manifest = json.loads((tmp_path / "run" / "manifest.json").read_text())
    assert manifest["completed"] is True and manifest["format"] == fmt and manifest["seed"] == 7
    assert manifest["sensors"] == {"lidar": {"model": "VLP-16"}}
    assert manifest["topics"]["/lidar/points"] == {"type": "sensor_msgs/msg/PointCloud2", "count": 5}
    assert manifest["vessels"] == {"milliAmpere": "ownship", "Havfruen": "target"}
    assert manifest["seatwin_version"]
    assert manifest["recording_time_s"]["total_s"] > 0


def test_display_frame_rotation_maps_ned_to_enu() -> None:
    from scipy.spatial.transform import Rotation

    q = mount_rotation("frd")
    assert q == pytest.approx((0, 0, 0, 1))
    np.testing.assert_allclose(R_ENU_NED @ [1.0, 2.0, 3.0], [2.0, 1.0, -3.0])
    from seatwin.recording.messages import quaternion_from_matrix
    from seatwin.recording.writer import ENU_NED_ROTATION

    assert quaternion_from_matrix(R_ENU_NED) == ENU_NED_ROTATION  # written out, the same bytes on /tf_static
    # a lidar (FLU) looking 90° to starboard: its x axis is the body's y (starboard) axis
    r = Rotation.from_quat(mount_rotation("flu", yaw=math.pi / 2)).as_matrix()
    np.testing.assert_allclose(r @ [1, 0, 0], [0, 1, 0], atol=1e-12)
    np.testing.assert_allclose(r @ [0, 0, 1], [0, 0, -1], atol=1e-12)  # z up = −down
    # camera optical frame: z forward, x right (starboard), y down
    r = Rotation.from_quat(mount_rotation("optical")).as_matrix()
    np.testing.assert_allclose(r @ [0, 0, 1], [1, 0, 0], atol=1e-12)
    np.testing.assert_allclose(r @ [1, 0, 0], [0, 1, 0], atol=1e-12)


def test_world_frame_radar_for_imported_data(tmp_path: Path) -> None:
    """Joyride-style plots: detections in the world NED frame, range/bearing from the ownship position."""
    with RecordingWriter(tmp_path / "run") as w:
        w.write_radar("/radar/detections", "world_ned", T0, [110.0, 100.0], [200.0, 230.0], origin=(100.0, 200.0))
        w.write_ground_truth(T0, [VesselPose("Telemetron", 100.0, 200.0, 0.0, ownship=True)])
    with open_bag(tmp_path / "run") as rec:
        (scan,) = list(rec.radar_scans())
        assert scan.frame_id == "world_ned"
        np.testing.assert_allclose(scan.points["range"], [10.0, 30.0])
        np.testing.assert_allclose(scan.points["bearing"], [0.0, math.pi / 2], atol=1e-7)  # true bearing, clockwise
        assert rec.manifest["notes"] == ["no geodetic origin given: the ownship's NavSatFix was not recorded"]


def test_empty_sweep_and_custom_topics(tmp_path: Path) -> None:
    topics = TopicConfig.from_dict({"pose": "/gt/{vessel}/pose", "odom": "/gt/{vessel}/odometry", "display_frame": None})
    with RecordingWriter(tmp_path / "run", "mcap", topics=topics) as w:
        e = np.zeros(0)
        w.write_sweep("/lidar/points", "lidar", T0, e, e, e, e, e, e)
        w.write_ground_truth(T0, vessels(0))
    with open_bag(tmp_path / "run") as rec:
        (c,) = list(rec.point_clouds())
        assert c.width == 0 and c.points.size == 0
        assert "/gt/milliAmpere/odometry" in rec.topics
        parents = {s.parent for s in rec.static_transforms()}  # no display frame: no map above world_ned and odom
        assert parents == {"milliAmpere/base_link", "Havfruen/base_link"}
        assert set(rec.ground_truth()) == {"milliAmpere", "Havfruen"}


def test_bad_inputs(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="unknown bag format"):
        RecordingWriter(tmp_path / "a", "hdf5")
    with pytest.raises(InputError, match="unknown topic setting"):
        TopicConfig.from_dict({"lidr": "/x"})
    write_run(tmp_path / "b", "mcap", n_sweeps=1)
    with pytest.raises(InputError, match="exists here already"):
        RecordingWriter(tmp_path / "b", "mcap")
    with pytest.raises(InputError, match="no topic"):
        list(open_bag(tmp_path / "b").point_clouds("/nope"))
    with pytest.raises(InputError, match="expected sensor_msgs/msg/PointCloud2"):
        list(open_bag(tmp_path / "b").point_clouds("/tf"))
    (tmp_path / "c.txt").write_text("x")
    with pytest.raises(InputError, match="not a bag"):
        open_bag(tmp_path / "c.txt")


def test_exception_inside_run_marks_incomplete(tmp_path: Path) -> None:
    with pytest.raises(RuntimeError), RecordingWriter(tmp_path / "run", "mcap") as w:
        w.write_sweep("/lidar/points", "lidar", T0, **sweep(0))
        raise RuntimeError("simulator crashed")
    with open_bag(tmp_path / "run") as rec:
        assert rec.complete is False and not rec.recovered  # bag finished cleanly, run did not
        assert rec.manifest["error"] == "RuntimeError: simulator crashed"
        assert len(list(rec.point_clouds())) == 1


def test_scenario_file_beside_bag_is_only_located(tmp_path: Path) -> None:
    """A foreign bag without truth topics: no truth from the bag; the scenario file beside it is named
    (reading it is :func:`seatwin.evaluation.truth.recording_truth`'s job, tests/evaluation)."""
    from rosbags.rosbag2 import StoragePlugin, Writer

    bag = tmp_path / "real"
    with Writer(bag, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        w.add_connection("/x", "std_msgs/msg/String", typestore=typestore("mcap"))
    (tmp_path / "scenario.csv").write_text("TimeInSecondsPosix\n")
    with open_bag(bag) as rec:
        assert rec.complete is None
        assert rec.ground_truth() == {}
        assert rec.scenario_file() == tmp_path / "scenario.csv"
    (tmp_path / "other.csv").write_text("")
    with open_bag(bag) as rec:
        assert rec.scenario_file() == tmp_path / "scenario.csv"  # scenario.* first
