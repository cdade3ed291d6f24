"""Box geometry: IoU, greedy NMS (per class), corner/centre conversions; YOLO letterbox and decoding — hand values."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.sensors.camera.box_ops import batched_nms, iou_matrix, nms, xywh_to_xyxy, xyxy_to_xywh
from seatwin.sensors.camera.yolo import decode, guess_layout, layout_problem, letterbox, letterbox_geometry, unletterbox

BOXES = np.array([[0, 0, 10, 10], [1, 0, 11, 10], [20, 20, 30, 30], [0, 0, 10, 10]], float)
SCORES = np.array([0.9, 0.8, 0.7, 0.95])


def test_iou_hand_values() -> None:
    assert iou_matrix([[0, 0, 2, 2]], [[1, 1, 3, 3]])[0, 0] == pytest.approx(1 / 7)
    assert iou_matrix([[0, 0, 10, 10]], [[1, 0, 11, 10]])[0, 0] == pytest.approx(90 / 110)
    assert iou_matrix([[0, 0, 1, 1]], [[1, 0, 2, 1]])[0, 0] == 0.0  # touching
    assert iou_matrix([[3, 3, 3, 3]], [[3, 3, 3, 3]])[0, 0] == 0.0  # empty union
    m = iou_matrix(BOXES, BOXES[:2])
    assert m.shape == (4, 2) and m[3, 0] == 1.0 and m[2, 1] == 0.0
    assert iou_matrix(np.zeros((0, 4)), BOXES).shape == (0, 4)


def test_conversions_round_trip() -> None:
    np.testing.assert_array_equal(xywh_to_xyxy([[5, 6, 4, 2]]), [[3, 5, 7, 7]])
    np.testing.assert_array_equal(xyxy_to_xywh([[3, 5, 7, 7]]), [[5, 6, 4, 2]])


def test_nms_keeps_best_and_drops_overlaps() -> None:
    assert nms(BOXES, SCORES, 0.5).tolist() == [3, 2]  # 0 (IoU 1) and 1 (IoU 0.82) fall under 3
    assert nms(BOXES, SCORES, 0.85).tolist() == [3, 1, 2]  # IoU 0.82 ≤ 0.85 survives
    assert nms(BOXES, SCORES, 0.5, max_keep=1).tolist() == [3]
    assert nms(np.zeros((0, 4)), [], 0.5).tolist() == []
    assert nms(BOXES[:2], [0.5, 0.5], 0.5).tolist() == [0]  # equal scores: input order
    # per class: boxes of another class never suppress each other
    assert batched_nms(BOXES, SCORES, [0, 1, 0, 0], 0.5).tolist() == [3, 1, 2]
    assert batched_nms(BOXES, SCORES, [0, 0, 0, 0], 0.5).tolist() == [3, 2]


def test_letterbox_geometry_and_inverse() -> None:
    # 612 × 512 onto 640 × 640: r = 640/612, 640 × 535, 52 rows of border above (Ultralytics' rounding)
    w, h, box = letterbox_geometry(612, 512, 640, 640)
    assert (w, h, box.pad_x, box.pad_y) == (640, 535, 0, 52) and box.scale == pytest.approx(640 / 612)
    w, h, box = letterbox_geometry(128, 64, 64, 64)
    assert (w, h, box.scale, box.pad_x, box.pad_y) == (64, 32, 0.5, 0, 16)
    np.testing.assert_allclose(unletterbox(np.array([[10.0, 22.0, 30.0, 30.0]]), box, 128, 64), [[20, 12, 60, 28]])
    np.testing.assert_allclose(unletterbox(np.array([[-4.0, 0.0, 70.0, 60.0]]), box, 128, 64), [[0, 0, 128, 64]])  # clipped


def test_letterbox_pixels() -> None:
    bgr = np.zeros((64, 128, 3), np.uint8)
    bgr[..., 2] = 255  # red
    bgr[:, 64:, 0] = 200  # right half also blue 200
    x, box = letterbox(bgr, 64, 64)
    assert x.shape == (1, 3, 64, 64) and x.dtype == np.float32 and box.pad_y == 16
    np.testing.assert_allclose(x[0, :, :16], 114 / 255)  # grey border above …
    np.testing.assert_allclose(x[0, :, 48:], 114 / 255)  # … and below
    np.testing.assert_array_equal(x[0, 0, 16:48], 1.0)  # channel 0 is red (RGB order)
    np.testing.assert_array_equal(x[0, 1, 16:48], 0.0)
    np.testing.assert_allclose(x[0, 2, 16:48, :32], 0.0)  # halved by 2: left half no blue …
    np.testing.assert_allclose(x[0, 2, 16:48, 32:], 200 / 255, rtol=1e-6)  # … right half blue


def test_decode_layouts_hand_values() -> None:
    # YOLOv8 [1, 4 + 3, N]: cx cy w h p0 p1 p2
    cand = np.array(
        [
            [32, 32, 20, 10, 0.0, 0.9, 0.0],  # class 1, 0.9
            [33, 32, 20, 10, 0.0, 0.8, 0.0],  # class 1, overlaps the first (IoU 0.905): suppressed
            [33, 32, 20, 10, 0.0, 0.0, 0.85],  # class 2: not suppressed by class 1
            [10, 10, 8, 8, 0.3, 0.2, 0.0],  # best class 0 (0.3), not 1
            [50, 50, 6, 6, 0.0, 0.2, 0.0],  # under the confidence
        ]
    )
    v8 = cand.T[None]
    dec = decode(v8, "yolov8", 0.25, 0.45)
    assert dec.cls.tolist() == [1, 2, 0] and dec.score.tolist() == pytest.approx([0.9, 0.85, 0.3])
    np.testing.assert_allclose(dec.xyxy[0], [22, 27, 42, 37])
    assert decode(v8, "yolov8", 0.25, 0.45, classes=(1,)).cls.tolist() == [1]
    assert decode(v8, "yolov8", 0.25, 0.45, classes=(1,), max_detections=0).cls.tolist() == []
    # YOLOv5 [1, N, 5 + 3]: the score is objectness × class probability
    v5 = np.insert(cand, 4, [1.0, 1.0, 1.0, 0.5, 1.0], axis=1)[None]
    dec5 = decode(v5, "yolov5", 0.25, 0.45)
    assert dec5.cls.tolist() == [1, 2] and dec5.score.tolist() == pytest.approx([0.9, 0.85])  # 0.5 × 0.3 < 0.25
    # end2end [1, N, 6]: x1 y1 x2 y2 score class, no NMS
    e2e = np.array([[[22, 27, 42, 37, 0.9, 8], [23, 27, 43, 37, 0.8, 8], [0, 0, 1, 1, 0.1, 8]]])
    dec2 = decode(e2e, "end2end", 0.25, 0.45, classes=(8,))
    assert dec2.cls.tolist() == [8, 8] and dec2.score.tolist() == pytest.approx([0.9, 0.8])


def test_layout_guess_and_problems() -> None:
    assert guess_layout([1, 84, 8400]) == "yolov8" and guess_layout([1, 25200, 85]) == "yolov5"
    assert guess_layout([1, 84, "anchors"]) == "yolov8"
    assert layout_problem([1, 84, 8400], "yolov8") is None
    assert "rank 2" in layout_problem([1, 1000], "yolov5")
    assert "4 values per candidate" in layout_problem([1, 100, 4], "yolov5")
    assert "batch 2" in layout_problem([2, 84, 8400], "yolov8")
    assert layout_problem([1, 300, 7], "end2end") is not None
