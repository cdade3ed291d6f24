"""Camera detections of a recording, per camera and image: the camera view of the autonomous agent.

Two detectors (issue 10): ``label`` (:class:`~seatwin.sensors.camera.detector.LabelDetectorConfig`)
runs on the recorded ground-truth labels (``vision_msgs/Detection2DArray``); ``onnx``
(:class:`~seatwin.sensors.camera.onnx_detector.OnnxDetectorConfig`) runs a YOLO-style model on
the recorded images (``sensor_msgs/Image`` bgr8/rgb8/mono8, or ``CompressedImage``). Each
camera's model (K, D) is its ``camera_info`` beside the topic read (``/camera/front/labels`` →
``/camera/front/camera_info``). Used by the tracker's camera bearings and the box comparison of two runs.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.sensors.camera.detector import Detection, LabelDetectorConfig
from seatwin.sensors.camera.onnx_detector import OnnxDetectorConfig, check_model_file

CameraDetector = LabelDetectorConfig | OnnxDetectorConfig
DETECTORS = ("label", "onnx")
LABELS_TYPE = "vision_msgs/msg/Detection2DArray"


@dataclass(frozen=True)
class CameraFrame:
    """The detections of one image (or one labels message) of one camera."""

    camera: str
    """The camera's topic prefix (``/camera/front``): the same camera in two runs."""
    topic: str
    time: float
    """Header stamp [s]."""
    log_time_ns: int
    frame_id: str
    detections: list[Detection]
    k: NDArray[np.float64]
    d: tuple[float, ...] | None


def detector_name(detector: CameraDetector) -> str:
    """``label`` or ``onnx``."""
    return "onnx" if isinstance(detector, OnnxDetectorConfig) else "label"


def camera_detector(
    detector: str = "label", model: str | None = None, classes: tuple[int, ...] | None = None
) -> CameraDetector | None:
    """The config of detector ``detector``: ``label`` → None (its defaults, seeded per recording), ``onnx`` → reads ``model``."""
    if detector not in DETECTORS:
        raise ParameterError("detector", f"expected one of {', '.join(DETECTORS)}, got {detector!r}")
    if detector == "label":
        if model or classes is not None:
            raise ParameterError("model" if model else "classes", "only the onnx detector reads a model: choose detector onnx")
        return None
    if not model:
        raise ParameterError("model", "the onnx detector needs a YOLO-style ONNX model file (model weights are never downloaded)")
    check_model_file(model)
    return OnnxDetectorConfig(model=str(model), **({} if classes is None else {"classes": tuple(classes)}))


def default_detector(rec: Any) -> LabelDetectorConfig:
    """The ``label`` detector with its defaults, seeded with the recording's seed."""
    return LabelDetectorConfig(seed=int((rec.manifest or {}).get("seed") or 0))


def camera_prefix(topic: str) -> str:
    """``/camera/front/image_raw[/compressed]`` or ``/camera/front/labels`` → ``/camera/front``."""
    from seatwin.recording.reader import camera_of_topic

    return camera_of_topic(topic)


def camera_topics(rec: Any, detector: CameraDetector) -> list[str]:
    """The topics ``detector`` reads: labels (``label``) or images (``onnx``: raw, else compressed, one topic per
    camera); empty when the recording has none."""
    if isinstance(detector, OnnxDetectorConfig):
        return list(rec.camera_image_topics())
    return list(rec.topics_of_type(LABELS_TYPE))


def missing_camera(rec: Any, detector: CameraDetector) -> InputError:
    """The error for a recording without what ``detector`` reads."""
    if isinstance(detector, OnnxDetectorConfig):
        return InputError(
            rec.path,
            "no camera images (sensor_msgs/Image) for the onnx detector in this recording; simulate with --sensors ...,camera",
        )
    return InputError(
        rec.path, "no camera labels (vision_msgs/Detection2DArray) in this recording; simulate with --sensors ...,camera"
    )


def camera_info(rec: Any, topic: str) -> tuple[NDArray[np.float64], tuple[float, ...] | None]:
    """(K, D) of the camera whose labels or images are on ``topic`` (its ``camera_info`` beside it; D None if all zero)."""
    info_topic = camera_prefix(topic) + "/camera_info"
    if info_topic not in rec.topics:
        raise InputError(rec.path, f"no {info_topic} for {topic}: the camera model is unknown")
    msg = next(rec.messages(info_topic)).msg
    k = np.asarray(msg.k if hasattr(msg, "k") else msg.K, float).reshape(3, 3)
    d = tuple(float(x) for x in (msg.d if hasattr(msg, "d") else msg.D))
    return k, (d if any(d) else None)


@dataclass(frozen=True)
class LabelBox:
    """One ground-truth box of a labels topic: pixel centre and size (pixel centres at integers),
    the vessel's visible fraction and truncation at the image edge."""

    instance: str
    cx: float
    cy: float
    w: float
    h: float
    visible: float
    truncation: float


Visibility = dict[str, tuple[float, float]]
"""instance → (visible fraction, truncation) of one labels message."""


def label_visibility(rec: Any, label_topics: list[str]) -> dict[tuple[str, int], Visibility]:
    """(labels topic, header stamp ns) → each box's visible fraction and truncation, from the
    ``foxglove_msgs/ImageAnnotations`` beside the labels (``/camera/<name>/annotations``: each box's
    ``metadata``). Empty for recordings made before the annotations, whose labels carry both as hypotheses."""
    beside = {camera_prefix(t) + "/annotations": t for t in label_topics}
    beside = {a: t for a, t in beside.items() if a in rec.topics}
    out: dict[tuple[str, int], Visibility] = {}
    for m in rec.messages(sorted(beside)) if beside else ():
        stamp = int(m.msg.timestamp.sec) * 1_000_000_000 + int(m.msg.timestamp.nanosec)
        vis: Visibility = {}
        for box in m.msg.points:
            meta = {kv.key: kv.value for kv in box.metadata}
            try:
                vis[meta["instance"]] = (float(meta["visible_fraction"]), float(meta["truncation"]))
            except (KeyError, ValueError):
                what = f"an annotation at {stamp} ns lacks its instance, visible_fraction or truncation"
                raise InputError(rec.bag, what, where=m.topic) from None
        out[(beside[m.topic], stamp)] = vis
    return out


def label_boxes(arr: Any, visibility: Visibility | None = None) -> list[LabelBox]:
    """The boxes of a ``vision_msgs/Detection2DArray`` of the labels topic, with each box's visible fraction and
    truncation from ``visibility`` (:func:`label_visibility`); without it, as recordings made before the
    annotations carried them: hypotheses ``vessel`` = visible fraction and ``truncation``."""
    boxes = []
    for d in arr.detections:
        b = d.bbox
        if visibility is not None and d.id in visibility:
            visible, truncation = visibility[d.id]
        else:
            scores = {r.hypothesis.class_id: float(r.hypothesis.score) for r in d.results}
            visible, truncation = scores.get("vessel", 1.0), scores.get("truncation", 0.0)
        cx, cy = float(b.center.position.x), float(b.center.position.y)
        boxes.append(LabelBox(d.id, cx, cy, float(b.size_x), float(b.size_y), visible, truncation))
    return boxes


def _labels(arr: Any, visibility: Visibility | None = None) -> list[tuple[str, float, float, float, float, float]]:
    """``(instance, cx, cy, w, h, visible_fraction)`` of a ``Detection2DArray`` (the label detector's input)."""
    return [(b.instance, b.cx, b.cy, b.w, b.h, b.visible) for b in label_boxes(arr, visibility)]


def _bgr(rec: Any, m: Any) -> NDArray[np.uint8]:
    """The pixels of an Image or CompressedImage message as bgr8 (a bad one: an error naming bag, topic and time)."""
    from seatwin.recording.images import to_bgr

    frame = rec.decode_image(m)
    return to_bgr(frame.pixels, frame.encoding)


def detected_frames(rec: Any, topics: list[str], detector: CameraDetector) -> Iterator[CameraFrame]:
    """The detections of every message on ``topics`` (from :func:`camera_topics`), in recording order."""
    from seatwin.recording.reader import stamp_s
    from seatwin.sensors.camera.detector import detect

    models = {t: camera_info(rec, t) for t in topics}
    onnx = None
    visibility: dict[tuple[str, int], Visibility] = {}
    if isinstance(detector, OnnxDetectorConfig):
        from seatwin.sensors.camera.onnx_detector import OnnxDetector

        onnx = OnnxDetector(detector)
    else:
        visibility = label_visibility(rec, topics)
    for m in rec.messages(topics):
        k, dist = models[m.topic]
        if onnx is not None:
            dets = onnx.detect(_bgr(rec, m))
        else:
            w, h = int(round(2 * (k[0, 2] + 0.5))), int(round(2 * (k[1, 2] + 0.5)))
            stamp = int(m.msg.header.stamp.sec) * 1_000_000_000 + int(m.msg.header.stamp.nanosec)
            dets = detect(_labels(m.msg, visibility.get((m.topic, stamp))), detector, m.topic, m.log_time_ns, w, h)
        yield CameraFrame(
            camera_prefix(m.topic), m.topic, stamp_s(m.msg.header.stamp), m.log_time_ns, m.msg.header.frame_id, dets, k, dist
        )


def camera_boxes(rec: Any, detector: CameraDetector | None = None) -> dict[str, list[tuple[float, NDArray[np.float64]]]]:
    """Per camera (topic prefix), its images as ``(time [s], (k, 4) corner boxes x1 y1 x2 y2)`` of ``detector``'s
    detections (default: the ``label`` detector seeded with the recording's seed); empty without camera topics."""
    from seatwin.sensors.camera.box_ops import xywh_to_xyxy

    det = detector or default_detector(rec)
    out: dict[str, list[tuple[float, NDArray[np.float64]]]] = {}
    for f in detected_frames(rec, camera_topics(rec, det), det):
        xywh = [(d.center_x, d.center_y, d.size_x, d.size_y) for d in f.detections]
        out.setdefault(f.camera, []).append((f.time, xywh_to_xyxy(xywh)))
    return out
