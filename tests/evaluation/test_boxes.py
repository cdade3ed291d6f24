"""Bounding-box comparison of two runs: Hungarian matching by IoU, per camera and pooled figures — hand-computed boxes."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.errors import ParameterError
from seatwin.evaluation.boxes import centre_offsets, compare_boxes, match_boxes


def _strip(x0: float, x1: float) -> list[float]:
    return [x0, 0.0, x1, 10.0]


def test_hungarian_beats_greedy() -> None:
    # IoU a0–b0 = 8/12 is the best single pair, but a0–b1 and a1–b0 (7/13 each) sum to more
    a = [_strip(0, 10), _strip(5, 15)]
    b = [_strip(2, 12), _strip(-3, 7)]
    ia, ib, iou = match_boxes(a, b, 0.3)
    assert ia.tolist() == [0, 1] and ib.tolist() == [1, 0]
    np.testing.assert_allclose(iou, [7 / 13, 7 / 13])
    ia, ib, iou = match_boxes(a, b, 0.6)  # neither cross pair reaches 0.6: only a0–b0 is usable
    assert ia.tolist() == [0] and ib.tolist() == [0] and iou.tolist() == pytest.approx([8 / 12])
    assert match_boxes(a, b, 0.7)[0].size == 0
    assert match_boxes(np.zeros((0, 4)), b)[0].size == 0


def test_centre_offsets() -> None:
    np.testing.assert_allclose(centre_offsets([[0, 0, 10, 10], [0, 0, 2, 2]], [[3, 4, 13, 14], [0, 0, 2, 2]]), [5.0, 0.0])


REAL = {
    "/camera/front": [
        (0.0, [[0, 0, 10, 10], [100, 100, 120, 110]]),
        (0.4, [[5, 5, 6, 6]]),  # no synthetic image at 0.4 s
        (0.2, [[0, 0, 10, 10]]),  # out of order on purpose
    ],
    "/camera/left": [(0.0, [[0, 0, 4, 4]])],
    "/camera/right": [(0.0, [[0, 0, 4, 4]])],
}
SYNTHETIC = {
    "/camera/front": [
        (0.01, [[1, 0, 11, 10], [200, 200, 210, 210]]),  # IoU 90/110, offset 1 px; and a box the real run lacks
        (0.2, [[0, 2, 10, 12]]),  # IoU 80/120, offset 2 px
    ],
    "/camera/left": [(0.0, np.zeros((0, 4)))],
}


def test_compare_boxes_per_camera_and_pooled() -> None:
    res = compare_boxes(REAL, SYNTHETIC, min_iou=0.3, time_tolerance=0.05)
    front, left = res.cameras
    assert (front.camera, left.camera) == ("/camera/front", "/camera/left")
    assert (front.n_images_real, front.n_images_synthetic, front.n_paired_images) == (3, 2, 2)
    assert (front.n_boxes_real, front.n_boxes_synthetic, front.n_matched) == (3, 3, 2)
    ious = [90 / 110, 80 / 120]
    assert front.iou_mean == pytest.approx(np.mean(ious)) and front.iou_median == pytest.approx(np.mean(ious))
    assert front.centre_offset_mean_px == pytest.approx(1.5) and front.centre_offset_p95_px == pytest.approx(1.95)
    # 4 objects seen by either run (2 matched, 1 only real, 1 only synthetic): 3 of 4 each
    assert front.detection_rate_real == 0.75 and front.detection_rate_synthetic == 0.75 and front.detection_rate_difference == 0
    # left: the synthetic image is empty → nothing matched, real 1 of 1, synthetic 0 of 1
    assert (left.n_matched, left.iou_mean, left.centre_offset_mean_px) == (0, None, None)
    assert (left.detection_rate_real, left.detection_rate_synthetic, left.detection_rate_difference) == (1.0, 0.0, -1.0)
    # pooled over cameras (not a mean of means): 2 matched of 4 real and 3 synthetic boxes → 5 objects
    all_ = res.overall
    assert (all_.camera, all_.n_images_real, all_.n_images_synthetic, all_.n_paired_images) == ("all", 4, 3, 3)
    assert (all_.n_boxes_real, all_.n_boxes_synthetic, all_.n_matched) == (4, 3, 2)
    assert all_.detection_rate_real == pytest.approx(0.8) and all_.detection_rate_synthetic == pytest.approx(0.6)
    assert all_.detection_rate_difference == pytest.approx(-0.2) and all_.iou_mean == pytest.approx(np.mean(ious))
    assert res.only_real == ["/camera/right"] and res.only_synthetic == []
    d = res.to_dict()
    assert d["overall"]["n_matched"] == 2 and d["cameras_only_real"] == ["/camera/right"] and d["min_iou"] == 0.3


def test_compare_boxes_thresholds_and_tolerance() -> None:
    strict = compare_boxes(REAL, SYNTHETIC, min_iou=0.7).cameras[0]
    assert strict.n_matched == 1 and strict.iou_mean == pytest.approx(90 / 110)
    tight = compare_boxes(REAL, SYNTHETIC, time_tolerance=0.001).cameras[0]
    assert tight.n_paired_images == 1 and tight.n_matched == 1  # 0.0 vs 0.01 s no longer pair
    empty = compare_boxes({"/c": []}, {"/c": []})
    assert empty.overall.n_paired_images == 0 and empty.overall.detection_rate_real is None
    with pytest.raises(ParameterError, match="min_iou"):
        compare_boxes(REAL, SYNTHETIC, min_iou=0.0)
    with pytest.raises(ParameterError, match="time_tolerance"):
        compare_boxes(REAL, SYNTHETIC, time_tolerance=-1)
