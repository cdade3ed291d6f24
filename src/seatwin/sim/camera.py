"""The RGB camera rig as a :class:`seatwin.sim.sensors.SimSensor`: all cameras of the rig in one frame.

Per frame and camera: ``/camera/<name>/image_raw`` (``sensor_msgs/Image`` bgr8),
``/camera/<name>/camera_info`` (plumb-bob K, R, P, D) and, with ``labels``,
``/camera/<name>/labels`` (``vision_msgs/Detection2DArray``: one detection per vessel in view, ``id`` =
vessel name, one hypothesis ``("vessel", 1.0)``: a ground-truth box is certain, and ``score`` is a
confidence as vision_msgs means it) and the same boxes as ``/camera/<name>/annotations``
(``foxglove_msgs/ImageAnnotations``, which Foxglove's Image panel draws; each box's ``metadata`` holds
``instance``, ``class``, ``visible_fraction`` and ``truncation``, for which vision_msgs has no field, and
its text says them).
Frame ids are the cameras' optical frames in the ownship's namespace (``<ownship>/camera_<name>_optical_frame``),
mounted on its ``base_link`` on /tf_static.
"""

from __future__ import annotations

import math
import posixpath
import time as _time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.recording import RecordingWriter, StaticTransform, TopicConfig
from seatwin.recording.foxglove import LabelAnnotation, image_annotations
from seatwin.recording.messages import Box2D
from seatwin.recording.tf_tree import sensor_mount
from seatwin.sensors.camera.config import CameraConfig
from seatwin.sensors.camera.intrinsics import source_pixels
from seatwin.sensors.camera.labels import BoxLabel, ground_truth_boxes
from seatwin.sensors.camera.rig import camera_info_fields, rig_mounts
from seatwin.sim.timing import periodic_times, periodic_times_from


@dataclass
class CameraTiming:
    """Wall seconds per stage over the frames so far (the benchmark's cost split)."""

    render_s: float = 0.0
    readback_s: float = 0.0
    distortion_s: float = 0.0
    labels_s: float = 0.0
    encode_s: float = 0.0
    images: int = 0

    def as_dict(self) -> dict[str, float]:
        return {k: round(v, 6) if isinstance(v, float) else v for k, v in self.__dict__.items()}


@dataclass(frozen=True)
class CameraImage:
    """One camera's image of a frame: bgr8 pixels, its pinhole object-id image and ground-truth boxes."""

    name: str
    bgr: NDArray[np.uint8]
    ids: NDArray[np.int32]
    labels: list[BoxLabel] = field(default_factory=list)


def camera_topics(topics: TopicConfig, camera: str) -> tuple[str, str, str]:
    """(image, camera_info, labels) topics of camera ``camera``: ``/camera/<camera>/image_raw`` by default."""
    image = topics.topic("camera", sensor=f"camera/{camera}")
    base = posixpath.dirname(image) if image.endswith("/image_raw") else image
    return image, f"{base}/camera_info", f"{base}/labels"


GROUND_TRUTH_CONFIDENCE = 1.0
"""The ``hypothesis.score`` of a ground-truth box: its class is known."""


def label_boxes(labels: list[BoxLabel]) -> list[Box2D]:
    """Labels as :class:`~seatwin.recording.messages.Box2D` (one hypothesis: the class, confidence 1)."""
    return [Box2D(b.instance, *b.center, *b.size, results=((b.label, GROUND_TRUTH_CONFIDENCE),)) for b in labels]


def annotations_topic(labels_topic: str) -> str:
    """The ``foxglove_msgs/ImageAnnotations`` topic beside a labels topic: ``/camera/<name>/annotations``."""
    return posixpath.join(posixpath.dirname(labels_topic), "annotations")


def annotations(labels: list[BoxLabel]) -> list[LabelAnnotation]:
    """Labels as Foxglove boxes: pixel centres at integers → pixel edges at integers (the top-left pixel's
    top-left corner is 0, 0), as ``seatwin labels export`` converts them for COCO."""
    return [
        LabelAnnotation(
            b.instance, b.label, b.x_min + 0.5, b.y_min + 0.5, b.x_max + 0.5, b.y_max + 0.5, b.visible_fraction, b.truncation
        )
        for b in labels
    ]


class CameraSensor:
    """The rig of ``config`` on vessel ``ownship`` of ``scene`` (a :class:`~seatwin.world.scene.Scene`).

    The renderer is created here (an EGL problem fails before a bag is opened); the ownship is
    not drawn (the cameras look out from its rig).
    """

    def __init__(self, config: CameraConfig, scene: Any, ownship: str, name: str = "camera"):
        from seatwin.render import SceneRenderer

        self.config, self.scene, self.ownship, self.name = config, scene, ownship, name
        self.rate_hz, self.phase_s = float(config.rate_hz), float(config.phase_s)
        self.mounts = rig_mounts(config)
        self.info = camera_info_fields(config)
        self.distortion = config.distortion if config.has_distortion else None
        self.renderer = SceneRenderer(
            scene,
            self.info.k,
            config.width,
            config.height,
            near=config.near_m,
            far=config.far_m,
            exclude=[ownship],
            sun=(config.sun_azimuth_deg, config.sun_elevation_deg),
        )
        if config.has_distortion:  # resampled on the GPU (the CPU reference: DistortionMap)
            self.renderer.set_distortion(*source_pixels(self.info.k, config.distortion, config.width, config.height))
        self.labelled = [n for n in scene.vessel_names if n != ownship] + list(scene.moored_boats)
        self.timing = CameraTiming()

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        return periodic_times(t0, t1, self.rate_hz, self.phase_s)

    def frame_times_from(self, t0: float, t1: float, first: int) -> NDArray[np.float64]:
        return periodic_times_from(t0, t1, self.rate_hz, self.phase_s, first)

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        return [
            s
            for m in self.mounts
            for s in sensor_mount(topics, self.ownship, topics.sensor(self.ownship, m.frame_id), m.translation, m.rotation)
        ]

    def parameters(self) -> dict[str, Any]:
        return {
            "kind": "camera",
            "rate_hz": self.rate_hz,
            "phase_s": self.phase_s,
            "carrier": self.ownship,
            "renderer": "moderngl-egl",
            "k": self.info.k.tolist(),
            "vfov_deg": math.degrees(2 * math.atan(0.5 * self.config.height / self.info.k[1, 1])),
            "config": self.config.model_dump(mode="json"),
        }

    def capture(self, t: float, frame: int) -> list[CameraImage]:
        """Render every camera at ``t`` (and label each image from ground truth)."""
        pose = self.scene.pose(self.ownship, t)
        out = []
        r = self.renderer
        for m in self.mounts:
            rot, centre = m.world_pose(float(pose.north), float(pose.east), float(pose.heading))
            before = r.timing.render_s, r.timing.readback_s, r.timing.distortion_s
            f = r.render(t, rot, centre, solo=self.labelled if self.config.labels else ())
            self.timing.render_s += r.timing.render_s - before[0]
            self.timing.readback_s += r.timing.readback_s - before[1]
            self.timing.distortion_s += r.timing.distortion_s - before[2]
            t0 = _time.perf_counter()
            labels: list[BoxLabel] = []
            if self.config.labels:
                labels = ground_truth_boxes(
                    self.scene,
                    t,
                    rot,
                    centre,
                    self.info.k,
                    self.distortion,
                    self.config.width,
                    self.config.height,
                    f.ids,
                    f.unoccluded,
                    exclude=(self.ownship,),
                    near=self.config.near_m,
                    min_visible_pixels=self.config.min_visible_pixels,
                )
            self.timing.labels_s += _time.perf_counter() - t0
            self.timing.images += 1
            out.append(CameraImage(m.name, f.bgr, f.ids, labels))
        return out

    def record(self, writer: RecordingWriter, t: float, data: list[CameraImage]) -> None:
        t0 = _time.perf_counter()
        info = self.info
        for img, m in zip(data, self.mounts, strict=True):
            image_topic, info_topic, labels_topic = camera_topics(writer.topics, img.name)
            frame_id = writer.topics.sensor(self.ownship, m.frame_id)
            writer.write_image(image_topic, frame_id, t, img.bgr)
            writer.write_camera_info(info_topic, frame_id, t, info.width, info.height, info.k, info.d, info.r, info.p)
            if self.config.labels:
                writer.write_labels(labels_topic, frame_id, t, label_boxes(img.labels))
                writer.write(annotations_topic(labels_topic), t, image_annotations(writer.store, t, annotations(img.labels)))
        self.timing.encode_s += _time.perf_counter() - t0
