"""REP-103/105 frames: one tf tree (map → odom → base_link → sensors) beside the thesis's FRD frames."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.geo.frames import FLU_TO_FRD, NED_TO_ENU, mount_matrix, yaw_matrix
from seatwin.recording import StaticTransform, TopicConfig, open_bag
from seatwin.recording.messages import quaternion_from_matrix
from seatwin.recording.tf_tree import TfTree, Transform, body_mounts, sensor_mount

OWN = "milliAmpere"


@pytest.fixture(scope="module", params=["mcap", "ros1"])
def run(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Path:
    from seatwin.pipeline.simulate import simulate_run

    out = tmp_path_factory.mktemp("frames") / request.param
    sensors = ("lidar", "radar", "camera")
    simulate_run("ferry_crossing", out, duration=0.3, start_offset=30.0, sensors=sensors, fmt=request.param, progress=False)
    return out


def _tree_at(rec: object, log_time_ns: int) -> TfTree:
    """/tf_static plus the /tf message logged at ``log_time_ns``."""
    tree = TfTree(rec.static_transforms())  # type: ignore[attr-defined]
    (tf,) = [m for m in rec.messages("/tf") if m.log_time_ns == log_time_ns]  # type: ignore[attr-defined]
    for t in tf.msg.transforms:
        tt, q = t.transform.translation, t.transform.rotation
        tree.add(t.header.frame_id, t.child_frame_id, (tt.x, tt.y, tt.z), (q.x, q.y, q.z, q.w))
    return tree


def test_one_tree_rooted_at_map(run: Path) -> None:
    with open_bag(run) as rec:
        tree = _tree_at(rec, next(rec.messages("/tf")).log_time_ns)
        vessels = rec.manifest["vessels"]
    for v in vessels:
        assert tree.chain(f"{v}/base_link_frd") == [f"{v}/base_link_frd", f"{v}/base_link", f"{v}/odom", "map"]
    assert tree.chain("world_ned") == ["world_ned", "map"]
    for sensor in ("radar", "camera_front_optical_frame", "camera_left_optical_frame", "gnss"):
        assert tree.chain(f"{OWN}/{sensor}")[1:] == [f"{OWN}/base_link", f"{OWN}/odom", "map"]
    # the VLP-16 hangs upside down (thesis 3.2.1) and the tree says so: rolled 180° below an upright mount
    assert tree.chain(f"{OWN}/lidar")[:3] == [f"{OWN}/lidar", f"{OWN}/lidar_upright", f"{OWN}/base_link"]
    z_up = tree.lookup("map", f"{OWN}/lidar_upright").rotation @ [0, 0, 1]
    z_lidar = tree.lookup("map", f"{OWN}/lidar").rotation @ [0, 0, 1]
    assert z_up == pytest.approx([0, 0, 1]) and z_lidar == pytest.approx([0, 0, -1])  # map is ENU: z up


def test_lidar_points_through_the_tree_are_the_simulators_world_points(run: Path) -> None:
    from dataclasses import replace

    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sensors.lidar import LidarSweep, lidar_for_scenario, sweep_to_world
    from seatwin.sensors.lidar_config import lidar_preset
    from seatwin.sim.settings import SimulationSettings

    lidar = lidar_for_scenario(builtin_scenario("ferry_crossing"), config=lidar_preset(SimulationSettings().lidar_preset))
    with open_bag(run) as rec:
        clouds = list(rec.point_clouds("/lidar/points"))
        assert len(clouds) == 3
        for cloud in clouds:
            assert cloud.frame_id == f"{OWN}/lidar"
            xyz = cloud.xyz().astype(np.float64)
            tree_point = _tree_at(rec, cloud.log_time_ns).lookup("map", cloud.frame_id).apply(xyz)
            n = len(xyz)
            zeros = np.zeros(n, np.float32)
            sweep = LidarSweep(cloud.stamp, 0, *cloud.xyz().T, zeros, np.zeros(n, np.uint16), zeros, np.zeros(n, np.int32))
            world_ned = sweep_to_world(lidar, replace(sweep, time=np.zeros(n, np.float32)))  # posed at the sweep start
            assert n > 100
            np.testing.assert_allclose(tree_point, world_ned @ NED_TO_ENU.T, atol=1e-6)
            # and the same through the thesis's NED world frame
            in_ned = _tree_at(rec, cloud.log_time_ns).lookup("world_ned", cloud.frame_id).apply(xyz)
            np.testing.assert_allclose(in_ned, world_ned, atol=1e-6)


def test_flu_base_link_and_frd_body_agree_with_odometry(run: Path) -> None:
    with open_bag(run) as rec:
        for v in rec.manifest["vessels"]:
            for odom in rec.messages(f"/ground_truth/{v}/odom"):
                tree = _tree_at(rec, odom.log_time_ns)
                p, q = odom.msg.pose.pose.position, odom.msg.pose.pose.orientation
                assert (odom.msg.header.frame_id, odom.msg.child_frame_id) == ("world_ned", f"{v}/base_link_frd")
                frd = tree.lookup("world_ned", f"{v}/base_link_frd")
                odo = Transform.from_quaternion((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
                np.testing.assert_allclose(frd.translation, odo.translation, atol=1e-9)
                np.testing.assert_allclose(frd.rotation, odo.rotation, atol=1e-12)
                # FLU = FRD turned half about x: same origin and forward axis, left = −starboard, up = −down
                rel = tree.lookup(f"{v}/base_link", f"{v}/base_link_frd")
                np.testing.assert_allclose(rel.rotation, FLU_TO_FRD, atol=1e-12)
                assert rel.translation == pytest.approx([0, 0, 0])
                # base_link in the ENU map: yaw = π/2 − heading, position (east, north, up)
                heading = math.atan2(odo.rotation[1, 0], odo.rotation[0, 0])
                flu = tree.lookup("map", f"{v}/base_link")
                np.testing.assert_allclose(flu.rotation, yaw_matrix(math.pi / 2 - heading), atol=1e-12)
                np.testing.assert_allclose(flu.translation, [p.y, p.x, -p.z], atol=1e-9)


def test_camera_optical_frames_are_the_rigs(run: Path) -> None:
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sensors.camera.config import CameraConfig
    from seatwin.sensors.camera.rig import rig_mounts

    sc = builtin_scenario("ferry_crossing")
    with open_bag(run) as rec:
        frames = {f.topic: f for f in rec.images()}
        assert {f.frame_id for f in frames.values()} == {f"{OWN}/camera_{c}_optical_frame" for c in ("left", "front", "right")}
        frame = next(iter(frames.values()))
        stamp_ns = frame.log_time_ns
        tree = _tree_at(rec, stamp_ns)
        own = rec.ground_truth()[OWN]
    k = int(np.argmin(abs(own.time - frame.stamp)))
    for m in rig_mounts(CameraConfig()):
        rot, centre = m.world_pose(float(own.north[k]), float(own.east[k]), float(own.heading[k]))
        ahead = np.array([[0.0, 0.0, 25.0], [3.0, -1.0, 40.0]])  # optical: z forward, x right, y down
        got = tree.lookup("world_ned", f"{OWN}/{m.frame_id}").apply(ahead)
        np.testing.assert_allclose(got, ahead @ rot.T + centre, atol=1e-6)
    assert sc.ownship is not None and sc.ownship.name == OWN


def test_navsatfix_in_the_gnss_frame_with_a_known_covariance(run: Path) -> None:
    with open_bag(run) as rec:
        fixes = list(rec.messages(f"/ground_truth/{OWN}/fix"))
        tree = TfTree(rec.static_transforms())
    assert fixes and all(m.msg.header.frame_id == f"{OWN}/gnss" for m in fixes)
    assert {m.msg.position_covariance_type for m in fixes} == {3}  # COVARIANCE_TYPE_KNOWN: exact, zero
    assert all(not np.any(m.msg.position_covariance) for m in fixes)
    gnss = tree.lookup(f"{OWN}/base_link_frd", f"{OWN}/gnss")
    assert gnss.translation == pytest.approx([0, 0, 0])  # the antenna at the reference point the fix locates


def test_body_mounts_of_old_and_new_trees_agree() -> None:
    """Recordings before REP-105 frames: sensors (un-namespaced) directly on ``{vessel}/base_link_frd``."""
    tp = TopicConfig()
    cases = [("lidar", (0.1, -0.2, -2.0), mount_matrix("flu", roll=math.pi, pitch=0.05, yaw=1.0), math.pi)]
    cases.append(("radar", (1.0, 0.0, -3.0), mount_matrix("flu"), 0.0))
    cases.append(("camera_front_optical_frame", (0.5, 0.3, -2.2), mount_matrix("optical", pitch=-0.26, yaw=0.4), 0.0))
    old, new = [], []
    for name, t, r, roll in cases:
        old.append(StaticTransform(f"{OWN}/base_link_frd", name, t, quaternion_from_matrix(r)))
        new += sensor_mount(tp, OWN, tp.sensor(OWN, name), t, r, roll)
    old.insert(0, StaticTransform("world", "world_ned", (0, 0, 0), quaternion_from_matrix(NED_TO_ENU)))
    from seatwin.recording.tf_tree import vessel_transforms

    new += vessel_transforms(tp, OWN, gnss=True)
    m_old, m_new = body_mounts(old), body_mounts(new)
    for name, t, r, _ in cases:
        for m in (m_old[name], m_new[f"{OWN}/{name}"]):
            np.testing.assert_allclose(m.rotation, r, atol=1e-12)
            np.testing.assert_allclose(m.translation, t, atol=1e-12)


def test_tree_errors_name_the_frames() -> None:
    from seatwin.errors import InputError

    tree = TfTree([StaticTransform("a", "b", (1, 0, 0)), StaticTransform("c", "d", (0, 1, 0))])
    with pytest.raises(InputError, match="'b' and 'd'"):
        tree.lookup("d", "b")
    tree.add("b", "a", (0, 0, 0), (0, 0, 0, 1))
    with pytest.raises(InputError, match="loop"):
        tree.chain("a")


def test_perception_reads_old_and_new_recordings_alike(tmp_path: Path) -> None:
    """A run recorded as before REP-105 frames — un-namespaced sensor frames mounted straight on
    ``{vessel}/base_link_frd`` with the FRD mount (the lidar's roll inside its quaternion), the ENU root named
    ``world`` — gives the very measurements of the REP-105 one."""
    from seatwin.perception.from_recording import scans_from_recording
    from seatwin.recording import mount_rotation
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sim.loop import simulate
    from seatwin.sim.run import scenario_sensors
    from seatwin.sim.settings import SimulationSettings

    def old_mounts(sensor: object) -> list[StaticTransform]:
        body = f"{OWN}/base_link_frd"
        if sensor.name == "lidar":  # type: ignore[attr-defined]
            m = sensor.recorded_mount  # type: ignore[attr-defined]
            return [StaticTransform(body, "lidar", tuple(m.translation), quaternion_from_matrix(m.rotation()))]
        if sensor.name == "radar":  # type: ignore[attr-defined]
            c = sensor.model.config  # type: ignore[attr-defined]
            return [StaticTransform(body, "radar", (c.mount_x_m, c.mount_y_m, -c.antenna_height_m), mount_rotation("flu"))]
        return []

    sc = builtin_scenario("ferry_crossing")
    t0 = sc.start + 30.0
    settings = SimulationSettings(sensors=("lidar", "radar"))
    scans = {}
    for kind, topics in (("new", TopicConfig()), ("old", TopicConfig(sensor_frame="{sensor}", display_frame="world"))):
        sensors = scenario_sensors(sc, settings)
        if kind == "old":
            for s in sensors:
                s.static_transforms = lambda _topics, s=s: old_mounts(s)  # type: ignore[method-assign]
        simulate(sensors, tmp_path / kind, t0, t0 + 0.5, topics=topics, progress=False)
        with open_bag(tmp_path / kind) as rec:
            assert {c.frame_id for c in rec.point_clouds("/lidar/points")} == {"lidar" if kind == "old" else f"{OWN}/lidar"}
            parents = {st.child: st.parent for st in rec.static_transforms()}
            expected = (f"{OWN}/base_link_frd", "lidar") if kind == "old" else (f"{OWN}/lidar_upright", f"{OWN}/lidar")
            assert parents[expected[1]] == expected[0]
            scans[kind] = list(scans_from_recording(rec, ("lidar", "radar")).scans)
    assert len(scans["new"]) == len(scans["old"]) > 0
    assert sum(len(s.z) for s in scans["new"]) > 0
    for a, b in zip(scans["new"], scans["old"]):
        assert (a.time, a.sensor) == (b.time, b.sensor)
        np.testing.assert_allclose(a.z, b.z, atol=1e-9)


_angle = st.floats(-math.pi, math.pi, allow_nan=False)
_offset = st.floats(-50.0, 50.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(
    roll=_angle,
    pitch=st.floats(-1.4, 1.4),
    yaw=_angle,
    t=st.tuples(_offset, _offset, _offset),
    axes=st.sampled_from(["flu", "optical", "frd"]),
    heading=_angle,
    pos=st.tuples(_offset, _offset),
)
def test_any_mount_through_the_tree_is_the_mount(
    roll: float, pitch: float, yaw: float, t: tuple, axes: str, heading: float, pos: tuple
) -> None:
    """For any mount (rolled or not) and vessel pose: the sensor's pose in ``world_ned`` through
    map → odom → base_link (→ upright) → sensor equals body pose ∘ mount, and ``body_mounts`` gives the mount back."""
    from seatwin.recording import VesselPose
    from seatwin.recording.tf_tree import base_link_pose, vessel_transforms

    tp = TopicConfig()
    r = mount_matrix(axes, roll=roll, pitch=pitch, yaw=yaw)
    tree = TfTree(sensor_mount(tp, OWN, f"{OWN}/s", t, r, roll if axes == "flu" else 0.0))
    tree.add_all(vessel_transforms(tp, OWN))
    tree.add("map", "world_ned", (0, 0, 0), quaternion_from_matrix(NED_TO_ENU))
    v = VesselPose(OWN, pos[0], pos[1], heading)
    tree.add(f"{OWN}/odom", f"{OWN}/base_link", *base_link_pose(v))
    got = tree.lookup("world_ned", f"{OWN}/s")
    body = yaw_matrix(heading)
    np.testing.assert_allclose(got.rotation, body @ r, atol=1e-9)
    np.testing.assert_allclose(got.translation, body @ np.asarray(t) + [pos[0], pos[1], 0.0], atol=1e-9)
    m = body_mounts([*sensor_mount(tp, OWN, f"{OWN}/s", t, r, roll if axes == "flu" else 0.0), *vessel_transforms(tp, OWN)])
    np.testing.assert_allclose(m[f"{OWN}/s"].rotation, r, atol=1e-9)
    np.testing.assert_allclose(m[f"{OWN}/s"].translation, t, atol=1e-9)
    inv = tree.lookup(f"{OWN}/s", "world_ned")  # and back
    np.testing.assert_allclose((inv @ got).rotation, np.eye(3), atol=1e-9)
