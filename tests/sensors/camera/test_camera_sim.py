"""The camera rig in the one simulation loop: topics, rate, layout, CameraInfo, labels; COCO export; snapshot CLI."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from seatwin.layout import DEFAULT_LAYOUT
from seatwin.recording import open_bag
from seatwin.recording.images import image_to_array
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sim.run import simulate_scenario

CAMS = ("left", "front", "right")


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    sc = builtin_scenario("ferry_crossing")
    out = tmp_path_factory.mktemp("cam") / "run"
    res = simulate_scenario(sc, out, start=sc.start + 39.0, duration=1.0, progress=False, sensors=("camera",))
    assert res.completed and res.frames["camera"] == 5
    return out


def test_bag_has_the_three_cameras_at_5_hz(run: Path) -> None:
    with open_bag(run) as rec:
        for cam in CAMS:
            assert rec.topics[f"/camera/{cam}/image_raw"].msgtype == "sensor_msgs/msg/Image"
            assert rec.topics[f"/camera/{cam}/camera_info"].msgtype == "sensor_msgs/msg/CameraInfo"
            assert rec.topics[f"/camera/{cam}/labels"].msgtype == "vision_msgs/msg/Detection2DArray"
            assert rec.topics[f"/camera/{cam}/image_raw"].count == 5
        stamps = [m.log_time_ns for m in rec.messages("/camera/front/image_raw")]
        assert np.allclose(np.diff(stamps), 2e8)
        img = next(rec.messages("/camera/front/image_raw")).msg
        assert (img.width, img.height, img.encoding, img.step) == (612, 512, "bgr8", 612 * 3)
        assert image_to_array(img).shape == (512, 612, 3)
        info = next(rec.messages("/camera/front/camera_info")).msg
        assert info.distortion_model == "plumb_bob" and len(info.d) == 5
        assert info.k[0] == pytest.approx(352.013, abs=1e-3) and list(info.r) == [1, 0, 0, 0, 1, 0, 0, 0, 1]
        assert img.header.frame_id == info.header.frame_id == "milliAmpere/camera_front_optical_frame"
        tf = {s.child: s for s in rec.static_transforms()}
        assert {f"milliAmpere/camera_{c}_optical_frame" for c in ("left", "front", "right")} <= set(tf)
        labels = [m.msg for m in rec.messages("/camera/right/labels")]
        dets = [d for arr in labels for d in arr.detections]
        moored = {m.name for m in DEFAULT_LAYOUT.moored_boats}
        assert dets and {"Havfruen", "Finn"} & {d.id for d in dets} and {d.id for d in dets} <= {"Havfruen", "Finn"} | moored
        assert all(d.results[0].hypothesis.class_id == "vessel" and 0 < d.results[0].hypothesis.score <= 1 for d in dets)


@pytest.mark.slow
def test_same_seed_bit_identical_images(run: Path, tmp_path: Path) -> None:
    sc = builtin_scenario("ferry_crossing")
    simulate_scenario(sc, tmp_path / "again", start=sc.start + 39.0, duration=1.0, progress=False, sensors=("camera",))
    topics = {f"/camera/{c}/{k}" for c in CAMS for k in ("image_raw", "labels")}
    with open_bag(run) as a, open_bag(tmp_path / "again") as b:
        assert [x[3] for x in a.raw_messages(topics)] == [x[3] for x in b.raw_messages(topics)]


def test_coco_export(run: Path, tmp_path: Path) -> None:
    from seatwin.cli.main import run as cli

    assert cli(["labels", "export", str(run), "--out", str(tmp_path / "coco")]) == 0
    coco = json.loads((tmp_path / "coco" / "annotations.json").read_text())
    assert len(coco["images"]) == 15 and coco["categories"][0]["name"] == "vessel"
    assert all((tmp_path / "coco" / im["file_name"]).is_file() for im in coco["images"])
    ann = coco["annotations"]
    assert ann and all(a["bbox"][2] > 0 and a["bbox"][3] > 0 and a["attributes"]["instance"] for a in ann)
    from PIL import Image

    im = coco["images"][0]
    assert Image.open(tmp_path / "coco" / im["file_name"]).size == (612, 512)


def test_snapshot_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from seatwin.cli.main import run as cli

    assert cli(["camera", "snapshot", "ferry_crossing", "--time", "40", "-o", str(tmp_path / "snap")]) == 0
    assert sorted(p.name for p in (tmp_path / "snap").iterdir()) == ["front.png", "left.png", "right.png"]
    assert "Havfruen" in capsys.readouterr().out
    assert cli(["camera", "snapshot", "ferry_crossing", "--time", "9999", "-o", str(tmp_path / "x")]) == 2
