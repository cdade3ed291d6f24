"""The ``label`` detector: detections from the ground-truth labels, and detections → world bearings.

The camera view of the autonomous agent without a trained network: each labelled vessel is
detected with a probability that grows with its box height and its visible fraction,

    P_D(h, v) = p_max · v / (1 + exp(−(h − h₅₀) / s)),

(h: box height [pixels], v: visible fraction; ``h50_px`` is the height detected half as often as
a large one), its box jittered by Gaussian noise (σ = ``box_sigma_px`` + ``box_sigma_rel`` · size
per coordinate) and given a confidence ``P_D`` plus noise, clipped to [0, 1]. False detections:
a Poisson number per image (``false_per_image``) of small boxes anywhere below the horizon band.
Draws are keyed by (seed, camera, stamp), so a run is bit-identical whatever else runs.

:func:`detection_bearings` turns box centres into world bearings through the full camera model
(undistort with ``D``, back-project with ``K``, rotate by the camera's world pose), the bearing
measurement of the thesis's camera (5.1.3; noise ``R_c`` from Table 5.2 in the tracker tuning).
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from pydantic import Field

from seatwin.sensors.camera.intrinsics import undistort
from seatwin.settings import Settings


class LabelDetectorConfig(Settings):
    """Parameters of the ``label`` detector (all seeded draws)."""

    p_max: float = Field(0.95, ge=0.0, le=1.0, description="Detection probability of a large, fully visible vessel.")
    h50_px: float = Field(8.0, gt=0.0, description="Box height [pixels] detected with half of p_max.")
    slope_px: float = Field(2.5, gt=0.0, description="Width of the logistic rise of P_D with box height [pixels].")
    box_sigma_px: float = Field(1.0, ge=0.0, description="Box coordinate noise σ, constant part [pixels].")
    box_sigma_rel: float = Field(0.04, ge=0.0, description="Box coordinate noise σ per pixel of box size.")
    confidence_sigma: float = Field(0.05, ge=0.0, description="Noise σ of the confidence about P_D.")
    false_per_image: float = Field(0.0, ge=0.0, description="Mean number of false detections per image (Poisson).")
    min_confidence: float = Field(0.3, ge=0.0, le=1.0, description="Detections below this confidence are dropped.")
    seed: int = Field(0, description="Seed of every draw.")


def detection_probability(height_px: ArrayLike, visible: ArrayLike, cfg: LabelDetectorConfig) -> NDArray[np.float64]:
    """P_D(h, v) = p_max · v / (1 + exp(−(h − h50) / s)) (see the module docstring)."""
    h = np.asarray(height_px, float)
    v = np.clip(np.asarray(visible, float), 0.0, 1.0)
    return cfg.p_max * v / (1.0 + np.exp(-(h - cfg.h50_px) / cfg.slope_px))


@dataclass(frozen=True)
class Detection:
    """One detected box (pixels, centre and size), its confidence and the instance it came from ("" = a false
    detection of the ``label`` detector, or unknown: the ``onnx`` detector)."""

    center_x: float
    center_y: float
    size_x: float
    size_y: float
    confidence: float
    instance: str = ""


def _rng(seed: int, camera: str, stamp_ns: int) -> np.random.Generator:
    return np.random.default_rng([seed & 0xFFFFFFFF, zlib.crc32(camera.encode()), stamp_ns & 0xFFFFFFFFFFFF])


def detect(
    boxes: Sequence[tuple[str, float, float, float, float, float]],
    cfg: LabelDetectorConfig,
    camera: str,
    stamp_ns: int,
    width: int,
    height: int,
) -> list[Detection]:
    """Detections of one image from its labels ``(instance, cx, cy, w, h, visible_fraction)``."""
    rng = _rng(cfg.seed, camera, stamp_ns)
    out = []
    for inst, cx, cy, w, h, vis in boxes:
        p = float(detection_probability(h, vis, cfg))
        u, noise = rng.random(), rng.standard_normal(5)
        if u >= p:
            continue
        conf = float(np.clip(p + cfg.confidence_sigma * noise[4], 0.0, 1.0))
        if conf < cfg.min_confidence:
            continue
        sx = cfg.box_sigma_px + cfg.box_sigma_rel * w
        sy = cfg.box_sigma_px + cfg.box_sigma_rel * h
        out.append(
            Detection(
                float(cx + sx * noise[0]),
                float(cy + sy * noise[1]),
                float(max(w + sx * noise[2], 1.0)),
                float(max(h + sy * noise[3], 1.0)),
                conf,
                inst,
            )
        )
    for _ in range(int(rng.poisson(cfg.false_per_image))):
        x, y = rng.uniform(0, width), rng.uniform(0.25 * height, 0.6 * height)
        size = rng.uniform(4, 20)
        conf = float(rng.uniform(cfg.min_confidence, 0.7))
        out.append(Detection(float(x), float(y), float(size * 1.6), float(size), conf))
    return out


def detection_bearings(
    u: ArrayLike, v: ArrayLike, k: ArrayLike, d: Sequence[float] | None, rotation: ArrayLike
) -> NDArray[np.float64]:
    """World bearings [rad, clockwise from north] of pixels (u, v) of a camera whose optical frame has
    world ``rotation`` (optical → NED): the horizontal direction of each pixel's ray."""
    k = np.asarray(k, float)
    y = (np.asarray(v, float) - k[1, 2]) / k[1, 1]
    x = (np.asarray(u, float) - k[0, 2] - k[0, 1] * y) / k[0, 0]
    if d is not None and any(c != 0.0 for c in d):
        x, y = undistort(x, y, d)
    rays = np.stack([x, y, np.ones_like(x)], axis=-1) @ np.asarray(rotation, float).T
    return np.arctan2(rays[..., 1], rays[..., 0])


def bearing_sigma_deg(r_c: float) -> float:
    """σ [deg] of a bearing variance ``r_c`` [rad²] (Table 5.2's R_c)."""
    return math.degrees(math.sqrt(r_c))
