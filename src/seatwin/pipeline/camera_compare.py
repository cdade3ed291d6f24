"""The camera part of ``seatwin compare``: AHED with lidar alone and with lidar + camera side by side
(the thesis's Fig. 5.3 against Fig. 5.16), and the bounding-box comparison of the two runs.

It applies to a real/synthetic pair of recordings that both have lidar and what the camera
detector reads (labels for ``label``, images for ``onnx``), under a tuning with a camera entry
(Table 5.2's ``R_c``). Each recording is tracked twice, with ``("lidar",)`` and
``("lidar", "camera")``; each pair of runs is compared by :func:`seatwin.evaluation.compare`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from seatwin.pipeline.track import tracking_hints

if TYPE_CHECKING:
    from seatwin.evaluation import CompareOptions, Comparison, Tracks, TruthSet
    from seatwin.perception.camera_frames import CameraDetector

LIDAR = ("lidar",)
FUSED = ("lidar", "camera")
RunOf = Callable[[str, "str | None", str, tuple[str, ...]], "Tracks"]
"""(dataset, tuning, side, sensors) → its tracks (tracked once, cached by the caller)."""


def camera_problem(spec: str | Path, detector: CameraDetector | None) -> str | None:
    """Why recording ``spec`` cannot take part in the camera comparison (None when it can)."""
    from seatwin.perception.camera_frames import camera_topics, default_detector
    from seatwin.recording import open_bag

    with open_bag(spec) as rec:
        radar = set(rec.radar_topics())
        if not [t for t in rec.topics_of_type("sensor_msgs/msg/PointCloud2") if t not in radar]:
            return f"{spec} has no lidar"
        if not camera_topics(rec, detector or default_detector(rec)):
            return f"{spec} has no camera {'images' if detector is not None else 'labels'}"
    return None


def tuning_has_camera(spec: str | Path, tuning: str | None) -> bool:
    """Whether ``tuning`` (None: the recording's suggestion, else 'real') has a camera entry."""
    from seatwin.recording.manifest import read_manifest
    from seatwin.tracking import load_tuning

    manifest = read_manifest(Path(spec)) if Path(spec).is_dir() else None
    return "camera" in load_tuning(tuning or tracking_hints(manifest).get("tuning") or "real").sensors


def fusion_table(fusion: Sequence[tuple[str, Comparison, Comparison]]) -> dict[str, Any]:
    """Per (target, tuning): AHED and common / one-sided instants with lidar and with lidar + camera; the means."""
    from seatwin.evaluation import comparison_table

    rows = []
    for label, lidar, fused in fusion:
        for a, b in zip(lidar.targets, fused.targets, strict=True):
            rows.append(
                {
                    "target": a.target,
                    "tuning": label,
                    "ahed_lidar": a.ahed,
                    "ahed_lidar_camera": b.ahed,
                    "n_common_lidar": a.n_common,
                    "n_common_lidar_camera": b.n_common,
                    "fraction_only_one_lidar": a.fraction_only_one,
                    "fraction_only_one_lidar_camera": b.fraction_only_one,
                }
            )
    lt = comparison_table([c for _, c, _ in fusion])
    ft = comparison_table([c for _, _, c in fusion])
    return {
        "targets": rows,
        "ahed_mean_lidar": lt["ahed_mean"],
        "ahed_n_lidar": lt["ahed_n"],
        "ahed_mean_lidar_camera": ft["ahed_mean"],
        "ahed_n_lidar_camera": ft["ahed_n"],
    }


def camera_comparison(
    pairs: Sequence[tuple[str, str, str | None, str]],
    truth: TruthSet,
    options: CompareOptions,
    mask: object | None,
    detector: CameraDetector | None,
    run_of: RunOf,
    min_iou: float,
) -> dict[str, Any] | None:
    """The ``camera`` block of ``seatwin compare`` for the recording ``pairs`` (real, synthetic, tuning, label);
    None when no pair has lidar and cameras on both sides."""
    from seatwin.evaluation import compare
    from seatwin.evaluation.boxes import compare_boxes
    from seatwin.perception.camera_frames import camera_boxes, detector_name
    from seatwin.recording import open_bag

    problems = {spec: camera_problem(spec, detector) for r, s, _, _ in pairs for spec in (r, s)}
    usable = [p for p in pairs if problems[p[0]] is None and problems[p[1]] is None]
    if not usable:
        return None
    skipped = sorted({why for why in problems.values() if why is not None})
    ahed_only = dataclasses.replace(options, score=None)  # the block reports AHED; the score's bootstrap would be thrown away
    fusion = []
    for r, s, tuning, label in usable:
        if not (tuning_has_camera(r, tuning) and tuning_has_camera(s, tuning)):
            skipped.append(f"tuning {tuning or 'of the recording'} has no camera entry (R_c): {r} / {s} not fused")
            continue
        lidar = compare(run_of(r, tuning, "real", LIDAR), run_of(s, tuning, "synthetic", LIDAR), truth, label, ahed_only, mask)
        fused = compare(run_of(r, tuning, "real", FUSED), run_of(s, tuning, "synthetic", FUSED), truth, label, ahed_only, mask)
        fusion.append((label, lidar, fused))
    boxes = []
    for r, s in dict.fromkeys((r, s) for r, s, _, _ in usable):
        with open_bag(r) as rec_r, open_bag(s) as rec_s:
            got = compare_boxes(
                camera_boxes(rec_r, detector),
                camera_boxes(rec_s, detector),
                min_iou=min_iou,
                time_tolerance=options.time_tolerance,
            )
        boxes.append({"real": r, "synthetic": s, **got.to_dict()})
    return {
        "detector": detector_name(detector) if detector is not None else "label",
        "model": getattr(detector, "model", None),
        "fusion": fusion_table(fusion),
        "boxes": boxes,
        "skipped": skipped,
    }
