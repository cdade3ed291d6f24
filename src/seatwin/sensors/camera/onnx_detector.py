"""The ``onnx`` detector: any YOLO-style ONNX model the user points to, run with onnxruntime on the camera images.

The model is read from the given file only (weights are never downloaded). Its one input must be an
image batch ``[1, 3, H, W]`` (float); a dynamic ``H``/``W`` takes ``input_size`` (default 640). Its
first output must be one of the layouts of :mod:`seatwin.sensors.camera.yolo` (``auto``:
``[1, 4+C, N]`` with 4+C < N is YOLOv8, else YOLOv5). A file that is missing, not ONNX, or not such
a detector is refused with one line naming it and what was expected.

Detections are :class:`~seatwin.sensors.camera.detector.Detection` in the twin's pixel convention
(pixel centres at integers, as the labels and ``camera_info``): a YOLO box centre (pixel edges at
integers) minus half a pixel. onnxruntime runs on ``threads`` CPU threads (1: bit-identical runs).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, field_validator

from seatwin.errors import InputError
from seatwin.sensors.camera.box_ops import xyxy_to_xywh
from seatwin.sensors.camera.detector import Detection
from seatwin.sensors.camera.yolo import Layout, decode, guess_layout, layout_problem, letterbox, n_classes, unletterbox
from seatwin.settings import Settings

COCO_BOAT = 8
"""The class id of 'boat' in the 80 COCO classes (every COCO-trained YOLO export)."""
DEFAULT_INPUT_SIZE = 640


class OnnxDetectorConfig(Settings):
    """Parameters of the ``onnx`` detector."""

    model: str = Field(min_length=1, description="The YOLO-style ONNX model file (read locally, never downloaded).")
    layout: Literal["auto", "yolov5", "yolov8", "end2end"] = Field(
        "auto", description="Output layout: [1, N, 5+C] (yolov5), [1, 4+C, N] (yolov8), [1, N, 6] (end2end), or guessed."
    )
    classes: tuple[int, ...] = Field((COCO_BOAT,), description="Class ids kept (default: COCO 8 'boat'); empty: every class.")
    min_confidence: float = Field(0.25, ge=0.0, le=1.0, description="Detections scoring at most this are dropped.")
    iou_threshold: float = Field(0.45, ge=0.0, le=1.0, description="NMS: a box overlapping a better one by more IoU is dropped.")
    max_detections: int = Field(100, ge=1, description="Most detections kept per image.")
    input_size: int | None = Field(
        None, ge=32, le=4096, multiple_of=32, description="Square input side for a model with a dynamic input size (default 640)."
    )
    threads: int = Field(1, ge=1, le=64, description="onnxruntime CPU threads (1: bit-identical runs).")

    @field_validator("classes")
    @classmethod
    def _class_ids(cls, v: tuple[int, ...]) -> tuple[int, ...]:
        if any(c < 0 for c in v):
            raise ValueError("expected class ids >= 0")
        return v


def check_model_file(model: str | Path) -> Path:
    """``model`` as a path, or one :class:`InputError` when it is not a file."""
    path = Path(model)
    if not path.is_file():
        raise InputError(path, "no such ONNX model file; expected a YOLO-style detector exported to ONNX")
    return path


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


class OnnxDetector:
    """A loaded, checked model: :meth:`detect` turns one bgr8 image into detections."""

    def __init__(self, config: OnnxDetectorConfig):
        self.config = config
        self.path = check_model_file(config.model)
        try:
            import onnxruntime as ort
        except ImportError:  # pragma: no cover - a dependency of seatwin
            raise InputError(self.path, "the onnx detector needs onnxruntime (pip install onnxruntime)") from None
        opts = ort.SessionOptions()
        opts.intra_op_num_threads = config.threads
        opts.inter_op_num_threads = 1
        opts.log_severity_level = 3
        try:
            self.session = ort.InferenceSession(str(self.path), opts, providers=["CPUExecutionProvider"])
        except Exception as exc:  # noqa: BLE001 - onnxruntime raises its own types for unreadable models
            raise InputError(self.path, f"not a loadable ONNX model ({_first_line(exc)})") from None
        self.input_name, self.in_height, self.in_width, self.dtype = self._check_input()
        self.output_name, self.layout = self._check_output()

    def _refuse(self, what: str, where: str | None = None) -> InputError:
        return InputError(self.path, f"{what}; not a YOLO-style detector", where=where)

    def _check_input(self) -> tuple[str, int, int, type]:
        inputs = self.session.get_inputs()
        if len(inputs) != 1:
            raise self._refuse(f"{len(inputs)} inputs; expected one image input [1, 3, H, W]")
        inp, shape = inputs[0], list(inputs[0].shape)
        if len(shape) != 4 or (isinstance(shape[0], int) and shape[0] != 1) or (isinstance(shape[1], int) and shape[1] != 3):
            raise self._refuse(f"input {inp.name!r} has shape {shape}; expected an image batch [1, 3, H, W]")
        dtypes = {"tensor(float)": np.float32, "tensor(float16)": np.float16}
        if inp.type not in dtypes:
            raise self._refuse(f"input {inp.name!r} is {inp.type}; expected tensor(float) or tensor(float16)")
        size = self.config.input_size
        fixed = [d if isinstance(d, int) and d > 0 else None for d in shape[2:]]
        if size is not None and any(d is not None and d != size for d in fixed):
            raise InputError(
                self.path,
                f"the model takes {shape[3]}×{shape[2]} images (width × height), not {size}×{size}",
                where="input_size",
            )
        h, w = (d if d is not None else (size or DEFAULT_INPUT_SIZE) for d in fixed)
        return inp.name, int(h), int(w), dtypes[inp.type]

    def _check_output(self) -> tuple[str, Layout]:
        out = self.session.get_outputs()[0]
        shape = list(out.shape)
        if self.config.layout == "auto" and len(shape) != 3:
            raise self._refuse(f"output {out.name!r} has shape {shape}; expected [1, N, 5+C] (YOLOv5) or [1, 4+C, N] (YOLOv8)")
        layout: Layout = guess_layout(shape) if self.config.layout == "auto" else self.config.layout
        problem = layout_problem(shape, layout)
        if problem is not None:
            raise self._refuse(f"output {out.name!r} has shape {shape}: {problem}")
        self._check_classes(shape, layout)
        return out.name, layout

    def _check_classes(self, shape: list[Any], layout: Layout) -> None:
        c = n_classes(shape, layout)
        beyond = [k for k in self.config.classes if c is not None and k >= c]
        if beyond:
            hint = ""
            if self.config.layout == "auto" and shape[-1] == 6:
                hint = " (an output [1, N, 6] of x1 y1 x2 y2 score class is an end2end export: layout end2end)"
            raise InputError(
                self.path,
                f"the model has {c} classes (0…{c - 1}); the class filter {list(self.config.classes)} "
                f"(default: COCO 8 'boat') names classes it does not have{hint}",
                where="classes",
            )

    def detect(self, bgr: NDArray[np.uint8]) -> list[Detection]:
        """Detections of one bgr8 image (H×W×3), best first."""
        h, w = bgr.shape[:2]
        x, box = letterbox(bgr, self.in_width, self.in_height)
        try:
            out = self.session.run([self.output_name], {self.input_name: x.astype(self.dtype, copy=False)})[0]
        except Exception as exc:  # noqa: BLE001 - onnxruntime's own error types
            raise InputError(
                self.path, f"inference on a [1, 3, {self.in_height}, {self.in_width}] input failed ({_first_line(exc)})"
            ) from None
        problem = layout_problem(list(out.shape), self.layout)
        if problem is not None:
            raise self._refuse(f"output {self.output_name!r} came out as {list(out.shape)}: {problem}")
        self._check_classes(list(out.shape), self.layout)
        cfg = self.config
        dec = decode(out, self.layout, cfg.min_confidence, cfg.iou_threshold, cfg.classes, cfg.max_detections)
        xywh = xyxy_to_xywh(unletterbox(dec.xyxy, box, w, h))
        return [
            Detection(float(cx - 0.5), float(cy - 0.5), float(bw), float(bh), float(s))
            for (cx, cy, bw, bh), s in zip(xywh, dec.score)
            if bw > 0 and bh > 0
        ]
