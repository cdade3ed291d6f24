"""YOLO pre- and post-processing, as the Ultralytics exports expect it: letterbox in, boxes out.

Pre-processing (:func:`letterbox`): the image is scaled by ``r = min(H_in / h, W_in / w)`` (bilinear,
half-pixel centres like OpenCV's ``INTER_LINEAR``), centred on a grey (114) canvas of the model's
input size, converted to RGB, scaled to [0, 1] and laid out ``[1, 3, H_in, W_in]``.

Post-processing (:func:`decode`): the output layouts of the common exports —

* ``yolov5`` ``[1, N, 5 + C]``: ``cx cy w h objectness p_1 … p_C``; score = objectness · p_best;
* ``yolov8`` ``[1, 4 + C, N]`` (also YOLO11): ``cx cy w h p_1 … p_C``; score = p_best;
* ``end2end`` ``[1, N, 6]`` (exports with NMS inside, e.g. YOLOv10): ``x1 y1 x2 y2 score class``;

each candidate takes its best class; candidates below the confidence or outside the wanted classes
are dropped, the rest go through per-class NMS, and the boxes are mapped back to the image
(:func:`unletterbox`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from seatwin.sensors.camera.box_ops import batched_nms, xywh_to_xyxy

Layout = Literal["yolov5", "yolov8", "end2end"]
LAYOUTS: tuple[str, ...] = ("yolov5", "yolov8", "end2end")
PAD_VALUE = 114
"""Grey of the letterbox border (Ultralytics)."""


def resize_bilinear(image: NDArray[np.uint8], width: int, height: int) -> NDArray[np.float32]:
    """``image`` (H×W×C) resized to ``height``×``width`` by bilinear interpolation with half-pixel centres."""
    h, w = image.shape[:2]
    img = image.astype(np.float32)

    def axis(n_out: int, n_in: int) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float32]]:
        src = np.clip((np.arange(n_out) + 0.5) * (n_in / n_out) - 0.5, 0.0, n_in - 1)
        i0 = np.floor(src).astype(np.int64)
        i1 = np.minimum(i0 + 1, n_in - 1)
        return i0, i1, (src - i0).astype(np.float32)

    y0, y1, fy = axis(height, h)
    x0, x1, fx = axis(width, w)
    rows = img[y0] * (1 - fy)[:, None, None] + img[y1] * fy[:, None, None]
    return rows[:, x0] * (1 - fx)[None, :, None] + rows[:, x1] * fx[None, :, None]


@dataclass(frozen=True)
class Letterbox:
    """Where the image went on the model's canvas: ``canvas = image · scale + (pad_x, pad_y)``."""

    scale: float
    pad_x: int
    pad_y: int


def letterbox_geometry(width: int, height: int, in_width: int, in_height: int) -> tuple[int, int, Letterbox]:
    """(scaled width, scaled height, placement) of a ``width``×``height`` image on an ``in_width``×``in_height`` canvas."""
    r = min(in_height / height, in_width / width)
    new_w, new_h = int(round(width * r)), int(round(height * r))
    dw, dh = (in_width - new_w) / 2.0, (in_height - new_h) / 2.0
    return new_w, new_h, Letterbox(r, int(round(dw - 0.1)), int(round(dh - 0.1)))


def letterbox(bgr: NDArray[np.uint8], in_width: int, in_height: int) -> tuple[NDArray[np.float32], Letterbox]:
    """The network input ``[1, 3, in_height, in_width]`` (RGB, [0, 1]) of a bgr8 image, and its placement."""
    h, w = bgr.shape[:2]
    new_w, new_h, box = letterbox_geometry(w, h, in_width, in_height)
    scaled = bgr.astype(np.float32) if (new_w, new_h) == (w, h) else resize_bilinear(bgr, new_w, new_h)
    canvas = np.full((in_height, in_width, 3), float(PAD_VALUE), np.float32)
    canvas[box.pad_y : box.pad_y + new_h, box.pad_x : box.pad_x + new_w] = scaled
    chw = canvas[..., ::-1].transpose(2, 0, 1) / np.float32(255.0)
    return np.ascontiguousarray(chw[None], dtype=np.float32), box


def unletterbox(xyxy: NDArray[np.float64], box: Letterbox, width: int, height: int) -> NDArray[np.float64]:
    """Corner boxes on the canvas → corner boxes on the ``width``×``height`` image, clipped to it."""
    out = (np.asarray(xyxy, float).reshape(-1, 4) - [box.pad_x, box.pad_y, box.pad_x, box.pad_y]) / box.scale
    out[:, [0, 2]] = np.clip(out[:, [0, 2]], 0.0, width)
    out[:, [1, 3]] = np.clip(out[:, [1, 3]], 0.0, height)
    return out


def guess_layout(shape: Sequence[int | str | None]) -> Layout:
    """``yolov8`` when the output is ``[1, small, large]`` (4 + C rows of N candidates), else ``yolov5``."""
    a, b = shape[1], shape[2]
    if isinstance(a, int) and isinstance(b, int) and a < b:
        return "yolov8"
    if isinstance(a, int) and not isinstance(b, int):
        return "yolov8"
    return "yolov5"


def n_classes(shape: Sequence[int | str | None], layout: Layout) -> int | None:
    """Classes C of an output ``shape`` in ``layout`` (None when unknown: ``end2end`` or a symbolic size)."""
    dim = {"yolov5": (2, 5), "yolov8": (1, 4)}.get(layout)
    if dim is None or not isinstance(shape[dim[0]], int):
        return None
    return int(shape[dim[0]]) - dim[1]


def layout_problem(shape: Sequence[int | str | None], layout: Layout) -> str | None:
    """Why an output of ``shape`` is not a detector output in ``layout`` (None when it can be)."""
    expected = {"yolov5": "[1, N, 5+C]", "yolov8": "[1, 4+C, N]", "end2end": "[1, N, 6]"}[layout]
    if len(shape) != 3:
        return f"rank {len(shape)}; expected {expected} ({layout})"
    if isinstance(shape[0], int) and shape[0] != 1:
        return f"batch {shape[0]}; expected {expected} ({layout})"
    need = {"yolov5": (2, 6), "yolov8": (1, 5), "end2end": (2, 6)}[layout]
    dim = shape[need[0]]
    if isinstance(dim, int) and (dim < need[1] or (layout == "end2end" and dim != 6)):
        return f"{dim} values per candidate; expected {expected} ({layout})"
    return None


@dataclass(frozen=True)
class Decoded:
    """Candidates that passed the confidence, class filter and NMS: corner boxes on the canvas."""

    xyxy: NDArray[np.float64]
    score: NDArray[np.float64]
    cls: NDArray[np.int64]


Candidates = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]


def candidates(output: NDArray[np.floating], layout: Layout) -> Candidates:
    """(corner boxes, score, best class) of every candidate of one output ``[1, …, …]``."""
    out = np.asarray(output, np.float64)[0]
    if layout == "end2end":
        return out[:, :4].copy(), out[:, 4].copy(), np.rint(out[:, 5]).astype(np.int64)
    rows = out if layout == "yolov5" else out.T
    first = 5 if layout == "yolov5" else 4
    probs = rows[:, first:]
    cls = np.argmax(probs, axis=1) if probs.shape[1] else np.zeros(len(rows), np.int64)
    score = probs[np.arange(len(rows)), cls] if probs.shape[1] else np.zeros(len(rows))
    if layout == "yolov5":
        score = score * rows[:, 4]
    return xywh_to_xyxy(rows[:, :4]), score, cls.astype(np.int64)


def decode(
    output: NDArray[np.floating],
    layout: Layout,
    min_confidence: float,
    iou_threshold: float,
    classes: Sequence[int] = (),
    max_detections: int = 100,
) -> Decoded:
    """The detections of one output: best class per candidate, score > ``min_confidence``, class in
    ``classes`` (all when empty), per-class NMS at ``iou_threshold``, at most ``max_detections``."""
    xyxy, score, cls = candidates(output, layout)
    keep = (score > min_confidence) & np.isfinite(xyxy).all(axis=1) & np.isfinite(score)
    if len(classes):
        keep &= np.isin(cls, np.asarray(classes, np.int64))
    xyxy, score, cls = xyxy[keep], score[keep], cls[keep]
    if layout != "end2end":
        idx = batched_nms(xyxy, score, cls, iou_threshold, max_detections)
    else:
        idx = np.argsort(-score, kind="stable")[:max_detections]
    return Decoded(xyxy[idx], score[idx], cls[idx])
