"""Bounding-box comparison of two runs (issue 10; the thesis's further work): the camera's view, real against synthetic.

Input per run: per camera, its images as ``(time, boxes)`` with ``boxes`` the (k, 4) corners
``x1 y1 x2 y2`` [pixels] of the detections (or labels) in that image. The two runs' images of a
camera are paired in time (mutual nearest neighbours within ``time_tolerance``,
:func:`~seatwin.evaluation.compare.match_times`); in each pair of images the boxes are matched
one-to-one by the Hungarian method maximising the summed IoU, and a matched pair counts when its
IoU is at least ``min_iou``. Reported per camera and over all cameras (pooled, not averaged):

* the matched boxes' IoU (mean, median) and centre offset [px] (mean, 95th percentile);
* each run's *detection rate*: the share of the objects seen in either run (matched pairs plus the
  boxes left over on each side) that this run has, ``(matched + only this run) / (matched + only real
  + only synthetic)``, and their difference (synthetic − real);
* counts: images of each run, paired images, boxes of each run in the paired images, matched pairs.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import linear_sum_assignment

from seatwin.errors import ParameterError
from seatwin.evaluation.compare import DEFAULT_TIME_TOLERANCE_S, match_times
from seatwin.sensors.camera.box_ops import iou_matrix

DEFAULT_MIN_IOU = 0.3
"""Smallest IoU of a matched pair (lower than the usual 0.5: the two runs' boxes may be offset)."""

CameraImages = Sequence[tuple[float, ArrayLike]]
"""One camera's images: ``(time [s], (k, 4) corner boxes)``."""


def match_boxes(
    a: ArrayLike, b: ArrayLike, min_iou: float = DEFAULT_MIN_IOU
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray]:
    """One-to-one matches ``(ia, ib, iou)`` between corner boxes ``a`` and ``b``: among the pairs with
    IoU ≥ ``min_iou``, the assignment of largest summed IoU (Hungarian)."""
    iou = iou_matrix(a, b)
    if iou.size == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    usable = np.where(iou >= min_iou, iou, 0.0)  # a pair under min_iou never displaces a usable one
    ia, ib = linear_sum_assignment(usable, maximize=True)
    keep = iou[ia, ib] >= min_iou
    return ia[keep].astype(np.int64), ib[keep].astype(np.int64), iou[ia, ib][keep]


def centre_offsets(a: ArrayLike, b: ArrayLike) -> NDArray[np.float64]:
    """Distance [px] between the centres of corner boxes ``a[i]`` and ``b[i]``."""
    a, b = np.asarray(a, float).reshape(-1, 4), np.asarray(b, float).reshape(-1, 4)
    return np.hypot((a[:, 0] + a[:, 2] - b[:, 0] - b[:, 2]) / 2.0, (a[:, 1] + a[:, 3] - b[:, 1] - b[:, 3]) / 2.0)


@dataclass
class BoxStats:
    """The box comparison of one camera (or of all cameras pooled: ``camera`` "all")."""

    camera: str
    n_images_real: int
    n_images_synthetic: int
    n_paired_images: int
    n_boxes_real: int
    """Boxes of the real run in the paired images."""
    n_boxes_synthetic: int
    n_matched: int
    iou_mean: float | None
    iou_median: float | None
    centre_offset_mean_px: float | None
    centre_offset_p95_px: float | None
    detection_rate_real: float | None
    detection_rate_synthetic: float | None
    detection_rate_difference: float | None
    """Synthetic − real."""

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class PooledMatches:
    """Matches gathered over paired images."""

    iou: list[float] = field(default_factory=list)
    offset: list[float] = field(default_factory=list)
    n_real: int = 0
    n_synthetic: int = 0
    n_paired: int = 0


def box_stats(camera: str, n_images_real: int, n_images_synthetic: int, pooled: PooledMatches) -> BoxStats:
    """The figures of :class:`BoxStats` from the matches of the paired images."""
    iou, off = np.asarray(pooled.iou, float), np.asarray(pooled.offset, float)
    m = len(iou)
    objects = pooled.n_real + pooled.n_synthetic - m
    rate_r = pooled.n_real / objects if objects else None
    rate_s = pooled.n_synthetic / objects if objects else None
    return BoxStats(
        camera=camera,
        n_images_real=n_images_real,
        n_images_synthetic=n_images_synthetic,
        n_paired_images=pooled.n_paired,
        n_boxes_real=pooled.n_real,
        n_boxes_synthetic=pooled.n_synthetic,
        n_matched=m,
        iou_mean=float(np.mean(iou)) if m else None,
        iou_median=float(np.median(iou)) if m else None,
        centre_offset_mean_px=float(np.mean(off)) if m else None,
        centre_offset_p95_px=float(np.percentile(off, 95)) if m else None,
        detection_rate_real=rate_r,
        detection_rate_synthetic=rate_s,
        detection_rate_difference=None if rate_r is None or rate_s is None else rate_s - rate_r,
    )


@dataclass
class BoxComparison:
    """Per camera (in name order) and over all cameras, with the conventions used."""

    cameras: list[BoxStats]
    overall: BoxStats
    min_iou: float
    time_tolerance: float
    only_real: list[str] = field(default_factory=list)
    """Cameras only the real run has (not compared)."""
    only_synthetic: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {
            "cameras": [c.to_dict() for c in self.cameras],
            "overall": self.overall.to_dict(),
            "min_iou": self.min_iou,
            "time_tolerance_s": self.time_tolerance,
            "cameras_only_real": self.only_real,
            "cameras_only_synthetic": self.only_synthetic,
        }


def _sorted(images: CameraImages) -> tuple[NDArray[np.float64], list[NDArray[np.float64]]]:
    order = sorted(range(len(images)), key=lambda i: images[i][0])
    return np.array([float(images[i][0]) for i in order]), [np.asarray(images[i][1], float).reshape(-1, 4) for i in order]


def _pool_camera(real: CameraImages, synthetic: CameraImages, min_iou: float, time_tolerance: float) -> PooledMatches:
    tr, br = _sorted(real)
    ts, bs = _sorted(synthetic)
    ir, is_ = match_times(tr, ts, time_tolerance)
    pooled = PooledMatches()
    for i, j in zip(ir, is_):
        if i < 0 or j < 0:
            continue
        a, b = br[i], bs[j]
        ia, ib, iou = match_boxes(a, b, min_iou)
        pooled.iou += iou.tolist()
        pooled.offset += centre_offsets(a[ia], b[ib]).tolist()
        pooled.n_real += len(a)
        pooled.n_synthetic += len(b)
        pooled.n_paired += 1
    return pooled


def compare_boxes(
    real: Mapping[str, CameraImages],
    synthetic: Mapping[str, CameraImages],
    *,
    min_iou: float = DEFAULT_MIN_IOU,
    time_tolerance: float = DEFAULT_TIME_TOLERANCE_S,
) -> BoxComparison:
    """Compare two runs' boxes per camera (cameras by name) and over all cameras (see the module docstring)."""
    if not 0.0 < min_iou <= 1.0:
        raise ParameterError("min_iou", f"expected 0 < min_iou <= 1, got {min_iou}")
    if not time_tolerance >= 0.0:
        raise ParameterError("time_tolerance", f"must be >= 0, got {time_tolerance}")
    names = sorted(set(real) & set(synthetic))
    total = PooledMatches()
    cameras = []
    for name in names:
        pooled = _pool_camera(real[name], synthetic[name], min_iou, time_tolerance)
        cameras.append(box_stats(name, len(real[name]), len(synthetic[name]), pooled))
        total.iou += pooled.iou
        total.offset += pooled.offset
        total.n_real += pooled.n_real
        total.n_synthetic += pooled.n_synthetic
        total.n_paired += pooled.n_paired
    overall = box_stats("all", sum(len(real[n]) for n in names), sum(len(synthetic[n]) for n in names), total)
    return BoxComparison(
        cameras, overall, min_iou, time_tolerance, sorted(set(real) - set(synthetic)), sorted(set(synthetic) - set(real))
    )
