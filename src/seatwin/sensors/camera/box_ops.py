"""Axis-aligned 2-D boxes: corner/centre conversions, the IoU matrix and greedy non-maximum suppression.

Boxes are ``(N, 4)`` arrays of corners ``x1, y1, x2, y2`` (``x2 >= x1``) in pixels, or of centre
and size ``cx, cy, w, h``. Shared by the ``onnx`` detector (NMS) and the box comparison of two runs.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def xywh_to_xyxy(boxes: ArrayLike) -> NDArray[np.float64]:
    """Corners ``x1 y1 x2 y2`` of boxes given as centre and size ``cx cy w h``."""
    b = np.asarray(boxes, float).reshape(-1, 4)
    half = b[:, 2:] / 2.0
    return np.concatenate([b[:, :2] - half, b[:, :2] + half], axis=1)


def xyxy_to_xywh(boxes: ArrayLike) -> NDArray[np.float64]:
    """Centre and size ``cx cy w h`` of boxes given by their corners."""
    b = np.asarray(boxes, float).reshape(-1, 4)
    return np.concatenate([(b[:, :2] + b[:, 2:]) / 2.0, b[:, 2:] - b[:, :2]], axis=1)


def iou_matrix(a: ArrayLike, b: ArrayLike) -> NDArray[np.float64]:
    """(N, M) intersection over union of corner boxes ``a`` (N, 4) and ``b`` (M, 4); 0 where the union is empty."""
    a = np.asarray(a, float).reshape(-1, 4)
    b = np.asarray(b, float).reshape(-1, 4)
    w = np.clip(np.minimum(a[:, None, 2], b[None, :, 2]) - np.maximum(a[:, None, 0], b[None, :, 0]), 0.0, None)
    h = np.clip(np.minimum(a[:, None, 3], b[None, :, 3]) - np.maximum(a[:, None, 1], b[None, :, 1]), 0.0, None)
    inter = w * h
    area_a = np.clip(a[:, 2] - a[:, 0], 0.0, None) * np.clip(a[:, 3] - a[:, 1], 0.0, None)
    area_b = np.clip(b[:, 2] - b[:, 0], 0.0, None) * np.clip(b[:, 3] - b[:, 1], 0.0, None)
    union = area_a[:, None] + area_b[None, :] - inter
    return np.divide(inter, union, out=np.zeros_like(inter), where=union > 0)


def nms(boxes: ArrayLike, scores: ArrayLike, iou_threshold: float, max_keep: int | None = None) -> NDArray[np.int64]:
    """Greedy non-maximum suppression: indices of the kept boxes, best score first.

    The best remaining box is kept and every remaining box overlapping it by IoU > ``iou_threshold``
    is dropped, until none remain (or ``max_keep`` are kept). Equal scores keep their input order.
    """
    b = np.asarray(boxes, float).reshape(-1, 4)
    s = np.asarray(scores, float).reshape(-1)
    order = np.argsort(-s, kind="stable")
    keep: list[int] = []
    while order.size and (max_keep is None or len(keep) < max_keep):
        best, rest = order[0], order[1:]
        keep.append(int(best))
        order = rest[iou_matrix(b[best], b[rest])[0] <= iou_threshold]
    return np.asarray(keep, dtype=np.int64)


def batched_nms(
    boxes: ArrayLike, scores: ArrayLike, classes: ArrayLike, iou_threshold: float, max_keep: int | None = None
) -> NDArray[np.int64]:
    """:func:`nms` within each class (boxes of different classes never suppress each other)."""
    b = np.asarray(boxes, float).reshape(-1, 4)
    if len(b) == 0:
        return np.zeros(0, dtype=np.int64)
    span = float(np.max(np.abs(b))) * 2.0 + 1.0  # shift each class's boxes apart so they cannot overlap
    shifted = b + np.asarray(classes, float).reshape(-1, 1) * span
    return nms(shifted, scores, iou_threshold, max_keep)
