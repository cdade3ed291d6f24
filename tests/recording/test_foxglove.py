"""What Foxglove and RViz draw: ImageAnnotations beside every camera's labels, vessel markers, the layout file."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from seatwin.recording import open_bag

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module", params=["mcap", "ros1"])
def run(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Path:
    from seatwin.pipeline.simulate import simulate_run

    out = tmp_path_factory.mktemp("fx") / request.param
    sensors = ("lidar", "radar", "camera")
    simulate_run("ferry_crossing", out, duration=0.3, start_offset=30.0, sensors=sensors, fmt=request.param, progress=False)
    return out


def _messages(run: Path, topic: str) -> list:
    with open_bag(run) as rec:
        return list(rec.messages(topic))


def test_annotations_are_the_labels_boxes(run: Path) -> None:
    from rosbags.highlevel import AnyReader

    from seatwin.perception.camera_frames import label_boxes, label_visibility

    with open_bag(run) as rec:
        bag = rec.bag
        label_topics = rec.topics_of_type("vision_msgs/msg/Detection2DArray")
        cams = [t.rsplit("/", 1)[0] for t in label_topics]
        visibility = label_visibility(rec, label_topics)
    assert len(cams) == 3 and len(visibility) == 6
    seen = 0
    for cam in cams:
        labels, notes = _messages(run, f"{cam}/labels"), _messages(run, f"{cam}/annotations")
        assert [m.log_time_ns for m in labels] == [m.log_time_ns for m in notes]
        for lab, ann in zip(labels, notes):
            assert len(ann.msg.points) == len(ann.msg.texts) == len(lab.msg.detections)
            stamp = lab.msg.header.stamp.sec * 1_000_000_000 + lab.msg.header.stamp.nanosec
            read = label_boxes(lab.msg, visibility[(f"{cam}/labels", stamp)])
            for det, box, text, got in zip(lab.msg.detections, ann.msg.points, ann.msg.texts, read):
                meta = {kv.key: kv.value for kv in box.metadata}
                # vision_msgs: one hypothesis, its score a confidence (ground truth: certain)
                assert [(r.hypothesis.class_id, r.hypothesis.score) for r in det.results] == [("vessel", 1.0)]
                assert meta["instance"] == det.id == got.instance and text.text.startswith(det.id)
                assert 0 < got.visible == float(meta["visible_fraction"]) <= 1
                assert 0 <= got.truncation == float(meta["truncation"]) < 1
                b = det.bbox
                # Detection2D: pixel centres at integers; Foxglove: the top-left pixel's corner at 0, 0
                x0, y0 = b.center.position.x - b.size_x / 2 + 0.5, b.center.position.y - b.size_y / 2 + 0.5
                assert box.type == 2 and len(box.points) == 4  # LINE_LOOP
                assert (box.points[0].x, box.points[0].y) == pytest.approx((x0, y0))
                assert (box.points[2].x, box.points[2].y) == pytest.approx((x0 + b.size_x, y0 + b.size_y))
                seen += 1
    assert seen > 0
    with AnyReader([bag]) as r:  # the bag carries foxglove_msgs' definitions: any reader decodes them
        conns = [c for c in r.connections if c.msgtype == "foxglove_msgs/msg/ImageAnnotations"]
        assert len(conns) == 3
        for c, _t, raw in r.messages(connections=conns):
            r.deserialize(raw, c.msgtype)


def test_vessel_markers_follow_the_body_frames(run: Path) -> None:
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario("ferry_crossing")
    with open_bag(run) as rec:
        markers = list(rec.messages("/ground_truth/markers"))
        poses = list(rec.messages(f"/ground_truth/{sc.vessels[0].name}/pose"))
        tf_children = {t.child_frame_id for tp in ("/tf", "/tf_static") for m in rec.messages(tp) for t in m.msg.transforms}
    assert len(poses) == 3 and len(markers) == 1  # once a second: the first ground-truth step of 0.3 s
    assert markers[0].log_time_ns == poses[0].log_time_ns
    for m in markers:
        boxes = [x for x in m.msg.markers if x.type == 1]
        names = {x.text for x in m.msg.markers if x.type == 9}
        assert names == {v.name for v in sc.vessels} and len(boxes) == len(sc.vessels)
        for v, box in zip(sc.vessels, boxes):
            assert box.header.frame_id == f"{v.name}/base_link_frd" and box.header.frame_id in tf_children
            assert box.frame_locked and (box.scale.x, box.scale.y, box.scale.z) == pytest.approx(
                (v.dimensions.length, v.dimensions.beam, v.dimensions.height)
            )
            assert box.pose.position.z == pytest.approx(-v.dimensions.height / 2)  # FRD: above the water is −z
            assert box.header.stamp.sec == box.header.stamp.nanosec == 0  # the latest /tf


def test_layout_opens_topics_a_run_has(run: Path, tmp_path: Path) -> None:
    layout = json.loads((ROOT / "docs" / "foxglove" / "seatwin-layout.json").read_text())
    panels = layout["configById"]
    named: set[str] = set()
    images = [p["imageMode"] for k, p in panels.items() if k.startswith("Image!")]
    assert len(images) == 3
    for mode in images:
        named |= {mode["imageTopic"], mode["calibrationTopic"], *mode["annotations"]}
    (scene,) = [p for k, p in panels.items() if k.startswith("3D!")]
    named |= set(scene["topics"])
    from seatwin.pipeline.track import track_into_run

    _, tracked = track_into_run(run, tmp_path / "tracked")  # the run with its tracks (seatwin track --out-bag)
    with open_bag(tracked.path) as rec:
        missing = named - set(rec.topics)
        dynamic = {t.child_frame_id for m in rec.messages("/tf") for t in m.msg.transforms}
        fixed = {(t.header.frame_id, t.child_frame_id) for m in rec.messages("/tf_static") for t in m.msg.transforms}
    assert not missing, missing
    assert {"/lidar/points", "/radar/detections", "/ground_truth/markers", "/tracks/scene"} <= set(scene["topics"])
    assert scene["followTf"] in dynamic and scene["followTf"].endswith("/base_link")  # the ownship's REP-103 body
    roots = {p for p, _ in fixed} - {c for _, c in fixed} - dynamic
    assert roots == {scene["layers"]["grid"]["frameId"]} == {"map"}  # the grid lies in the tree's one root

    def leaves(node: object) -> list[str]:
        return [node] if isinstance(node, str) else [x for k in ("first", "second") for x in leaves(node[k])]  # type: ignore[index]

    assert sorted(leaves(layout["layout"])) == sorted(panels)  # every panel placed, none missing


def test_labels_of_older_recordings_still_read() -> None:
    """Recordings made before the annotations carried visible fraction and truncation as hypotheses."""
    from seatwin.perception.camera_frames import label_boxes
    from seatwin.recording.messages import Box2D, detection2d_array, typestore

    old = detection2d_array(typestore("mcap"), 1.0, "cam", [Box2D("Finn", 10, 20, 4, 3, (("vessel", 0.6), ("truncation", 0.25)))])
    (box,) = label_boxes(old)
    assert (box.instance, box.visible, box.truncation) == ("Finn", 0.6, 0.25)
    (box,) = label_boxes(old, {"Finn": (0.5, 0.0)})  # the annotations' values win where given
    assert (box.visible, box.truncation) == (0.5, 0.0)


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
def test_hand_encoded_markers_are_rosbags_bytes(fmt: str) -> None:
    from seatwin.recording.foxglove import marker_array_bytes, vessel_marker_specs, vessel_markers
    from seatwin.recording.messages import typestore

    vessels = [("Finn", "Finn/base_link_frd", (9.5, 3.0, 2.0), False), ("Ø 7", "ø/b", (0.0, 0.0, 0.0), False)]
    vessels.append(("milliAmpere", "milliAmpere/base_link_frd", (5.0, 2.8, 1.5), True))
    specs = vessel_marker_specs(vessels)
    assert [s.type for s in specs] == [1, 9, 9, 1, 9]  # a vessel of unknown size: its name only
    store = typestore(fmt)
    msg = vessel_markers(store, specs)
    ref = store.serialize_ros1(msg, msg.__msgtype__) if fmt == "ros1" else store.serialize_cdr(msg, msg.__msgtype__)
    assert marker_array_bytes(specs, ros1=fmt == "ros1") == bytes(ref)
    assert marker_array_bytes([], ros1=fmt == "ros1") == bytes(
        store.serialize_ros1(vessel_markers(store, []), msg.__msgtype__)
        if fmt == "ros1"
        else store.serialize_cdr(vessel_markers(store, []), msg.__msgtype__)
    )


def test_markers_once_a_second(tmp_path: Path) -> None:
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sim import simulate_scenario

    simulate_scenario(builtin_scenario("ferry_crossing"), tmp_path / "r", duration=2.5, sensors=("lidar",), progress=False)
    with open_bag(tmp_path / "r") as rec:
        times = [m.log_time_ns for m in rec.messages("/ground_truth/markers")]
    assert len(times) == 3 and [b - a for a, b in zip(times, times[1:])] == pytest.approx([1e9, 1e9], abs=1e3)
