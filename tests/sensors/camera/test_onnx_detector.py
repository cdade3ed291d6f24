"""The ``onnx`` detector on tiny ONNX models built here with the ``onnx`` helper API, whose boxes are known exactly."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.sensors.camera.detector import Detection
from seatwin.sensors.camera.onnx_detector import OnnxDetector, OnnxDetectorConfig

onnx = pytest.importorskip("onnx")
from onnx import TensorProto, helper, numpy_helper  # noqa: E402


def _save(path: Path, nodes: list, inits: list, in_shape: list, out_shape: list) -> Path:
    graph = helper.make_graph(
        nodes,
        "tiny",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, in_shape)],
        [helper.make_tensor_value_info("output0", TensorProto.FLOAT, out_shape)],
        inits,
    )
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)], ir_version=8)
    onnx.checker.check_model(model)
    onnx.save(model, str(path))
    return path


def constant_model(path: Path, output: np.ndarray, in_shape: list | None = None) -> Path:
    """``output0 = output + 0 · mean(images)``: a fixed tensor computed through the input."""
    out = np.asarray(output, np.float32)
    nodes = [
        helper.make_node("ReduceMean", ["images"], ["m"], keepdims=1),
        helper.make_node("Reshape", ["m", "ones"], ["m1"]),
        helper.make_node("Mul", ["m1", "zero"], ["z"]),
        helper.make_node("Add", ["const", "z"], ["output0"]),
    ]
    inits = [
        numpy_helper.from_array(np.ones(out.ndim, np.int64), "ones"),
        numpy_helper.from_array(np.zeros(1, np.float32), "zero"),
        numpy_helper.from_array(out, "const"),
    ]
    return _save(path, nodes, inits, in_shape or [1, 3, 64, 64], list(out.shape))


def red_model(
    path: Path, box: tuple[float, float, float, float], n_classes: int = 10, cls: int = 8, dynamic: bool = False
) -> Path:
    """YOLOv8 output ``[1, 4 + C, 1]``: one candidate at ``box`` (cx cy w h on the canvas) whose class ``cls``
    scores the mean of the input's channel 0 (red, 0…1) and every other class 0."""
    top = np.zeros((1, 4 + cls, 1), np.float32)
    top[0, :4, 0] = box
    bottom = np.zeros((1, n_classes - cls - 1, 1), np.float32)
    nodes = [
        helper.make_node("Slice", ["images", "s0", "s1", "s_axis"], ["red"]),
        helper.make_node("ReduceMean", ["red"], ["m"], keepdims=1),
        helper.make_node("Reshape", ["m", "ones"], ["score"]),
        helper.make_node("Concat", ["top", "score", "bottom"], ["output0"], axis=1),
    ]
    inits = [
        numpy_helper.from_array(np.array([0], np.int64), "s0"),
        numpy_helper.from_array(np.array([1], np.int64), "s1"),
        numpy_helper.from_array(np.array([1], np.int64), "s_axis"),
        numpy_helper.from_array(np.ones(3, np.int64), "ones"),
        numpy_helper.from_array(top, "top"),
        numpy_helper.from_array(bottom, "bottom"),
    ]
    in_shape = [1, 3, "height", "width"] if dynamic else [1, 3, 64, 64]
    return _save(path, nodes, inits, in_shape, [1, 4 + n_classes, 1])


# Candidates on a 64 × 64 canvas, 10 classes: (cx, cy, w, h, class, probability)
CANDIDATES = [
    (32, 32, 20, 10, 8, 0.9),  # a boat
    (33, 32, 20, 10, 8, 0.8),  # the same boat again (IoU 0.905): NMS drops it
    (33, 32, 20, 10, 3, 0.85),  # a car on it: another class, not suppressed
    (10, 10, 8, 8, 0, 0.95),  # a person
    (50, 50, 6, 6, 8, 0.2),  # a faint boat, under the confidence
]
N_CLASSES, N_CANDIDATES = 10, 16


def yolo_output(layout: str, objectness: float = 1.0) -> np.ndarray:
    """The candidates as a YOLOv8 ``[1, 14, 16]`` or YOLOv5 ``[1, 16, 15]`` output (unused rows all zero)."""
    rows = np.zeros((N_CANDIDATES, 4 + N_CLASSES), np.float32)
    for i, (cx, cy, w, h, c, p) in enumerate(CANDIDATES):
        rows[i, :4] = cx, cy, w, h
        rows[i, 4 + c] = p
    if layout == "yolov8":
        return rows.T[None]
    return np.insert(rows, 4, objectness, axis=1)[None]


def _image(w: int = 64, h: int = 64, bgr: tuple[int, int, int] = (0, 0, 255)) -> np.ndarray:
    img = np.zeros((h, w, 3), np.uint8)
    img[:] = bgr
    return img


@pytest.mark.parametrize("layout", ["yolov8", "yolov5"])
def test_decoded_boxes_of_both_layouts(tmp_path: Path, layout: str) -> None:
    path = constant_model(tmp_path / f"{layout}.onnx", yolo_output(layout))
    for cfg_layout in ("auto", layout):
        det = OnnxDetector(OnnxDetectorConfig(model=str(path), layout=cfg_layout))
        assert det.layout == layout and (det.in_width, det.in_height) == (64, 64)
        # the default class filter (COCO 8, boat): the boat, its duplicate suppressed, the faint one dropped;
        # YOLO's pixel edges → the twin's pixel centres: −0.5 px
        assert det.detect(_image()) == [Detection(31.5, 31.5, 20.0, 10.0, pytest.approx(0.9))]
    every = OnnxDetector(OnnxDetectorConfig(model=str(path), classes=()))
    got = every.detect(_image())
    assert [(d.center_x, d.center_y, d.size_x, d.size_y) for d in got] == [
        (9.5, 9.5, 8, 8),
        (31.5, 31.5, 20, 10),
        (32.5, 31.5, 20, 10),
    ]
    assert [d.confidence for d in got] == pytest.approx([0.95, 0.9, 0.85])
    strict = OnnxDetector(OnnxDetectorConfig(model=str(path), min_confidence=0.92, classes=()))
    assert len(strict.detect(_image())) == 1


def test_objectness_multiplies_the_class_probability(tmp_path: Path) -> None:
    path = constant_model(tmp_path / "v5.onnx", yolo_output("yolov5", objectness=0.5))
    got = OnnxDetector(OnnxDetectorConfig(model=str(path), classes=())).detect(_image())
    assert [d.confidence for d in got] == pytest.approx([0.475, 0.45, 0.425])  # 0.5 × (0.95, 0.9, 0.85)


def test_scores_follow_the_pixels_through_the_letterbox(tmp_path: Path) -> None:
    det = OnnxDetector(OnnxDetectorConfig(model=str(red_model(tmp_path / "red.onnx", (20, 30, 10, 8))), layout="yolov8"))
    (red,) = det.detect(_image())  # 64 × 64: no scaling, score = mean red = 1
    assert (red.center_x, red.center_y, red.size_x, red.size_y) == (19.5, 29.5, 10.0, 8.0) and red.confidence == 1.0
    assert det.detect(_image(bgr=(255, 0, 0))) == []  # blue is channel 2 of BGR: no red
    (grey,) = det.detect(_image(bgr=(128, 128, 128)))
    assert grey.confidence == pytest.approx(128 / 255, rel=1e-5)
    # 128 × 64 → halved onto rows 16…47 of the canvas, grey 114 above and below: mean red (32 · 1 + 32 · 114/255) / 64
    (wide,) = det.detect(_image(128, 64))
    assert wide.confidence == pytest.approx(0.5 + 57 / 255, rel=1e-5)
    # canvas box (15, 26)–(25, 34) → image (30, 20)–(50, 36)
    assert (wide.center_x, wide.center_y, wide.size_x, wide.size_y) == (39.5, 27.5, 20.0, 16.0)


def test_dynamic_input_size(tmp_path: Path) -> None:
    path = red_model(tmp_path / "dyn.onnx", (48, 48, 30, 30), dynamic=True)
    det = OnnxDetector(OnnxDetectorConfig(model=str(path), layout="yolov8", input_size=96))
    assert (det.in_width, det.in_height) == (96, 96)
    (d,) = det.detect(_image())  # 64 → 96: r = 1.5, box (33, 33)–(63, 63) on the canvas → (22, 22)–(42, 42)
    assert (d.center_x, d.center_y) == pytest.approx((31.5, 31.5)) and (d.size_x, d.size_y) == pytest.approx((20, 20))
    assert d.confidence == pytest.approx(1.0, rel=1e-5)
    default = OnnxDetector(OnnxDetectorConfig(model=str(path), layout="yolov8"))
    assert (default.in_width, default.in_height) == (640, 640)


def test_bad_models_give_one_clear_line(tmp_path: Path) -> None:
    def refused(match: str, **cfg: object) -> InputError:
        with pytest.raises(InputError, match=match) as exc:
            OnnxDetector(OnnxDetectorConfig(**cfg))
        assert "\n" not in str(exc.value) and str(cfg["model"]) in str(exc.value)
        return exc.value

    refused("no such ONNX model file", model=str(tmp_path / "absent.onnx"))
    (tmp_path / "text.onnx").write_text("not a model")
    refused("not a loadable ONNX model", model=str(tmp_path / "text.onnx"))
    classifier = constant_model(tmp_path / "cls.onnx", np.zeros((1, 1000)))
    refused(
        r"output 'output0' has shape \[1, 1000\]; expected \[1, N, 5\+C\] \(YOLOv5\) or \[1, 4\+C, N\]", model=str(classifier)
    )
    grey = constant_model(tmp_path / "grey.onnx", yolo_output("yolov8"), in_shape=[1, 1, 64, 64])
    refused(r"has shape \[1, 1, 64, 64\]; expected an image batch \[1, 3, H, W\]", model=str(grey))
    narrow = constant_model(tmp_path / "narrow.onnx", np.zeros((1, 20, 4)))
    refused("4 values per candidate", model=str(narrow), layout="yolov5")
    fixed = constant_model(tmp_path / "v8.onnx", yolo_output("yolov8"))
    err = refused("takes 64×64 images", model=str(fixed), input_size=320)
    assert err.where == "input_size"
    err = refused("the model has 10 classes", model=str(fixed), classes=(12,))
    assert err.where == "classes"


def test_same_image_same_detections(tmp_path: Path) -> None:
    det = OnnxDetector(OnnxDetectorConfig(model=str(red_model(tmp_path / "red.onnx", (20, 30, 10, 8))), layout="yolov8"))
    rng = np.random.default_rng(3)
    img = rng.integers(0, 256, (50, 90, 3), dtype=np.uint8)
    assert det.detect(img) == det.detect(img.copy())


@pytest.mark.slow
def test_onnx_detections_become_camera_bearings_and_tracks(tmp_path: Path, capsys) -> None:
    """A model that always sees a boat at the canvas centre: every camera's bearing is its optical axis."""
    import math

    from seatwin.cli.main import run
    from seatwin.perception.from_recording import scans_from_recording
    from seatwin.recording import open_bag
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sensors.camera import CameraConfig
    from seatwin.sim.run import simulate_scenario

    box = np.zeros((1, 14, 16), np.float32)
    box[0, :4, 0] = 32, 32, 8, 4  # 612 × 512 → 64 × 54 at rows 5…58: centre column 306 → u = 305.5 = c_x
    box[0, 4 + 8, 0] = 0.9
    model = constant_model(tmp_path / "centre.onnx", box)
    rec_dir = tmp_path / "run"
    sc = builtin_scenario("ferry_crossing")
    simulate_scenario(sc, rec_dir, start=sc.start + 39.0, duration=1.0, progress=False, sensors=("lidar", "camera"))
    cfg = OnnxDetectorConfig(model=str(model))
    with open_bag(rec_dir) as rec:
        own = next(v for v in rec.ground_truth().values() if v.ownship)
        found = scans_from_recording(rec, ("camera",), camera=cfg)
        scans = list(found.scans)
    assert found.total == 5 and len(scans) == 5
    azimuths = np.radians(CameraConfig().azimuths_deg)
    for s in scans:
        heading = float(np.interp(s.time, own.time, np.unwrap(own.heading)))
        want = sorted(math.remainder(heading + az, 2 * math.pi) for az in azimuths)
        np.testing.assert_allclose(sorted(s.z[:, 0]), want, atol=1e-9)
        assert s.extra["confidence"] == pytest.approx([0.9] * 3)
    out = tmp_path / "t.csv"
    args = ["track", str(rec_dir), "--out", str(out), "--sensors", "lidar,camera", "--tuning", "synthetic", "--no-progress"]
    assert run([*args, "--detector", "onnx", "--model", str(model)]) == 0 and out.is_file()
    assert run([*args, "--detector", "onnx", "--model", str(tmp_path / "absent.onnx"), "--overwrite"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "absent.onnx: no such ONNX model file" in err[0]
    assert run([*args, "--detector", "onnx", "--model", str(model), "--classes", "12", "--overwrite"]) == 2
    assert "classes: the model has 10 classes" in capsys.readouterr().err


def test_end2end_export(tmp_path: Path) -> None:
    """An export with NMS inside: [1, N, 6] rows x1 y1 x2 y2 score class, read as they are."""
    rows = np.array([[[22, 27, 42, 37, 0.9, 8], [23, 27, 43, 37, 0.8, 8], [0, 0, 9, 9, 0.95, 0], [0, 0, 0, 0, 0, 0]]], np.float32)
    path = constant_model(tmp_path / "e2e.onnx", np.concatenate([rows, np.zeros((1, 6, 6), np.float32)], axis=1))  # [1, 10, 6]
    det = OnnxDetector(OnnxDetectorConfig(model=str(path), layout="end2end"))
    got = det.detect(_image())
    assert [(d.center_x, d.center_y, d.size_x, d.size_y) for d in got] == [(31.5, 31.5, 20, 10), (32.5, 31.5, 20, 10)]
    with pytest.raises(InputError, match="is an end2end export: layout end2end"):
        OnnxDetector(OnnxDetectorConfig(model=str(path)))  # guessed as YOLOv5 with 1 class: class 8 cannot exist
