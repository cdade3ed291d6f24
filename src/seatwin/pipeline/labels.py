"""Camera images and their ground-truth labels out of the twin: COCO export of a run, snapshots of a scenario.

``export_coco(run, out)`` writes every recorded camera image as PNG plus one COCO
``annotations.json`` (the format standard detector training tools read): one category
``vessel``, boxes ``[x, y, width, height]`` in pixels, and per annotation the vessel's name
(``instance``), its ``visible_fraction`` and ``truncation`` under ``attributes``.
``camera_snapshot(scenario, t, out)`` renders the rig at one time and writes the three images
with the ground-truth boxes drawn.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError

COCO_CATEGORIES = [{"id": 1, "name": "vessel", "supercategory": "vessel"}]


@dataclass(frozen=True)
class CocoExport:
    out_dir: Path
    images: int
    annotations: int
    annotations_file: Path


def _save_png(path: Path, bgr: NDArray[np.uint8]) -> None:
    from PIL import Image

    Image.fromarray(np.ascontiguousarray(bgr[..., ::-1])).save(path, format="PNG")


def _labels_topic(image_topic: str) -> str:
    """``/camera/front/image_raw[/compressed]`` → ``/camera/front/labels`` (another image topic: ``<topic>/labels``)."""
    image_topic = image_topic.removesuffix("/compressed")
    return image_topic.rsplit("/", 1)[0] + "/labels" if image_topic.endswith("/image_raw") else image_topic + "/labels"


def _stamp(msg: Any) -> int:
    return int(msg.header.stamp.sec) * 1_000_000_000 + int(msg.header.stamp.nanosec)


def export_coco(run: str | Path, out: str | Path, min_visible_fraction: float = 0.0, *, overwrite: bool = False) -> CocoExport:
    """Every camera image of the recording in ``run`` as PNG in ``out/images`` and ``out/annotations.json``.

    Labels whose ``visible_fraction`` is at most ``min_visible_fraction`` are left out (default:
    only vessels hidden completely). An earlier export in ``out`` is refused unless ``overwrite``; then the
    images its ``annotations.json`` lists are removed first (other files in ``out`` stay).
    """
    from seatwin.outputs import check_output_folder, write_text_atomic
    from seatwin.perception.camera_frames import label_boxes, label_visibility
    from seatwin.recording import open_bag
    from seatwin.recording.images import to_bgr

    out = Path(out)
    if check_output_folder(out, "out", ["images", "annotations.json"], inputs=[run], overwrite=overwrite):
        _remove_earlier_export(out)
    with open_bag(run) as rec:
        image_topics = rec.camera_image_topics()  # raw images, else compressed ones (--image-format jpeg|png)
        if not image_topics:
            raise InputError(run, "the recording has no camera images (simulate with --sensors ...,camera)")
        label_topics = [_labels_topic(t) for t in image_topics if _labels_topic(t) in rec.topics]
        labels: dict[tuple[str, int], Any] = {}
        if label_topics:
            for m in rec.messages(label_topics):
                labels[(m.topic, _stamp(m.msg))] = m.msg
        visibility = label_visibility(rec, label_topics)
        (out / "images").mkdir(parents=True, exist_ok=True)
        images, annotations = [], []
        for m in rec.messages(image_topics):
            stamp = _stamp(m.msg)
            camera = m.topic.removesuffix("/compressed").strip("/").replace("/image_raw", "").replace("/", "_")
            name = f"{camera}_{stamp}.png"
            frame = rec.decode_image(m)
            pixels = to_bgr(frame.pixels, frame.encoding)
            _save_png(out / "images" / name, pixels)
            image_id = len(images) + 1
            images.append(
                {
                    "id": image_id,
                    "file_name": f"images/{name}",
                    "width": int(pixels.shape[1]),
                    "height": int(pixels.shape[0]),
                    "camera": camera,
                    "frame_id": m.msg.header.frame_id,
                    "stamp_ns": stamp,
                }
            )
            key = (_labels_topic(m.topic), stamp)
            arr = labels.get(key)
            for box in label_boxes(arr, visibility.get(key)) if arr is not None else ():
                if box.visible <= min_visible_fraction:
                    continue
                w, h = box.w, box.h
                # continuous pixel coordinates (pixel centres at integers) → COCO (pixel edges at integers)
                x0, y0 = box.cx - w / 2 + 0.5, box.cy - h / 2 + 0.5
                annotations.append(
                    {
                        "id": len(annotations) + 1,
                        "image_id": image_id,
                        "category_id": 1,
                        "bbox": [round(x0, 3), round(y0, 3), round(w, 3), round(h, 3)],
                        "area": round(w * h, 3),
                        "iscrowd": 0,
                        "attributes": {
                            "instance": box.instance,
                            "visible_fraction": box.visible,
                            "truncation": box.truncation,
                        },
                    }
                )
    coco = {
        "info": {"description": f"seatwin camera labels of {Path(run).name}", "version": "1.0"},
        "images": images,
        "annotations": annotations,
        "categories": COCO_CATEGORIES,
    }
    path = out / "annotations.json"
    write_text_atomic(path, json.dumps(coco, indent=1))
    return CocoExport(out, len(images), len(annotations), path)


def _remove_earlier_export(out: Path) -> None:
    """Remove the annotations file of an earlier export and the images it lists (nothing else)."""
    path = out / "annotations.json"
    try:
        listed = [im["file_name"] for im in json.loads(path.read_text(encoding="utf-8")).get("images", [])]
    except (OSError, ValueError, TypeError, KeyError, AttributeError):
        listed = []
    for name in listed:
        target = (out / str(name)).resolve()
        if target.parent == (out / "images").resolve() and target.suffix == ".png":
            target.unlink(missing_ok=True)
    path.unlink(missing_ok=True)


def draw_boxes(bgr: NDArray[np.uint8], labels: list[Any]) -> Any:
    """A PIL RGB image of ``bgr`` with each label's box and name drawn."""
    from PIL import Image, ImageDraw

    img = Image.fromarray(np.ascontiguousarray(bgr[..., ::-1]))
    draw = ImageDraw.Draw(img)
    for b in labels:
        draw.rectangle([b.x_min, b.y_min, b.x_max, b.y_max], outline=(255, 40, 40), width=2)
        draw.text((b.x_min + 2, max(b.y_min - 12, 0)), f"{b.instance} {b.visible_fraction:.2f}", fill=(255, 255, 0))
    return img


@dataclass(frozen=True)
class Snapshot:
    files: list[Path]
    labels: dict[str, list[Any]]


def camera_snapshot(
    scenario: Any,
    time: float,
    out: str | Path,
    *,
    absolute: bool = False,
    boxes: bool = True,
    harbour: str | None = None,
    overwrite: bool = False,
) -> Snapshot:
    """Render the rig of ``scenario`` (a name, a file or a :class:`~seatwin.scenario.Scenario`) at ``time``
    seconds after its start (POSIX with ``absolute``) into ``out/<camera>.png`` with the boxes drawn, in
    ``harbour`` ('default', 'ravnkloa', 'none', a raster; default: the scenario's own); existing images are
    replaced only with ``overwrite``."""
    from seatwin.outputs import atomic_output, check_output_folder
    from seatwin.scenario import Scenario
    from seatwin.scenario.load import load_scenario
    from seatwin.sensors.camera.config import CameraConfig
    from seatwin.sim.camera import CameraSensor
    from seatwin.world.scene import Scene

    sc = scenario if isinstance(scenario, Scenario) else load_scenario(str(scenario))
    if sc.ownship is None:
        raise InputError(sc.source, "the scenario has no ownship to carry the cameras")
    t = float(time) if absolute else sc.start + float(time)
    if not sc.start <= t <= sc.end:
        from seatwin.errors import ParameterError

        raise ParameterError(
            "time", f"{t - sc.start:g} s is outside the scenario: expected 0 to {sc.end - sc.start:g} s after its start"
        )
    config = CameraConfig()
    out = Path(out)
    inputs = [scenario, harbour] if not isinstance(scenario, Scenario) else [harbour]
    check_output_folder(out, "out", [f"{n}.png" for n in config.names], inputs=inputs, overwrite=overwrite)
    sensor = CameraSensor(config, Scene.from_scenario(sc, harbour=harbour), sc.ownship.name)
    files, labels = [], {}
    for img in sensor.capture(t, 0):
        path = out / f"{img.name}.png"
        with atomic_output(path) as tmp:
            if boxes:
                draw_boxes(img.bgr, img.labels).save(tmp, format="PNG")
            else:
                _save_png(tmp, img.bgr)
        files.append(path)
        labels[img.name] = img.labels
    return Snapshot(files, labels)
