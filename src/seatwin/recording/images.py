"""Image payloads: ``sensor_msgs/Image`` (bgr8, rgb8, mono8) to arrays, and JPEG/PNG via Pillow for
``CompressedImage`` (Pillow comes with matplotlib; without it compressed images raise a clear error).
"""

from __future__ import annotations

import io
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError

CHANNELS = {"bgr8": 3, "rgb8": 3, "mono8": 1, "8UC1": 1, "8UC3": 3}


def image_to_array(msg: Any, source: str = "Image") -> NDArray[np.uint8]:
    """The pixels of a ``sensor_msgs/Image`` as H×W×C uint8 in the message's own channel order
    (bgr8 stays BGR; mono8 is H×W×1). Rows padded beyond ``width·C`` (``step``) are cut."""
    enc = str(msg.encoding)
    c = CHANNELS.get(enc)
    if c is None:
        raise InputError(source, f"unsupported image encoding {enc!r}; expected one of bgr8, rgb8, mono8")
    h, w, step = int(msg.height), int(msg.width), int(msg.step) or int(msg.width) * c
    buf = np.asarray(msg.data, dtype=np.uint8).reshape(-1)
    if step < w * c or buf.size < step * h:
        raise InputError(source, f"image data has {buf.size} bytes, step {step}: too small for {h}×{w}×{c}")
    rows = buf[: step * h].reshape(h, step)[:, : w * c]
    return np.ascontiguousarray(rows).reshape(h, w, c)


def to_rgb(pixels: NDArray[np.uint8], encoding: str) -> NDArray[np.uint8]:
    """H×W×3 RGB from pixels in ``encoding`` (bgr8 reversed, mono8 repeated)."""
    if encoding in ("bgr8",):
        return pixels[..., ::-1]
    if pixels.ndim == 2 or pixels.shape[-1] == 1:
        return np.repeat(pixels.reshape(pixels.shape[0], pixels.shape[1], 1), 3, axis=2)
    return pixels


def _pil() -> Any:
    try:
        from PIL import Image
    except ImportError:  # pragma: no cover - Pillow ships with matplotlib
        raise InputError("CompressedImage", "JPEG/PNG needs Pillow (pip install pillow)") from None
    return Image


def encode_image(pixels: NDArray[np.uint8], fmt: str = "jpeg", encoding: str = "bgr8", quality: int = 90) -> bytes:
    """JPEG or PNG bytes of an image given in ``encoding``."""
    Image = _pil()
    rgb = to_rgb(np.asarray(pixels, np.uint8), encoding)
    if encoding == "mono8":
        img = Image.fromarray(np.asarray(pixels, np.uint8).reshape(rgb.shape[:2]), mode="L")
    else:
        img = Image.fromarray(np.ascontiguousarray(rgb), mode="RGB")
    bio = io.BytesIO()
    kind = {"jpg": "JPEG", "jpeg": "JPEG", "png": "PNG"}.get(fmt.lower())
    if kind is None:
        raise InputError("CompressedImage", f"unsupported format {fmt!r}; expected jpeg or png")
    img.save(bio, format=kind, **({"quality": quality} if kind == "JPEG" else {}))
    return bio.getvalue()


def decode_compressed(msg: Any, source: str = "CompressedImage") -> tuple[NDArray[np.uint8], str]:
    """(pixels, encoding) of a ``sensor_msgs/CompressedImage``: colour as bgr8 (like cv_bridge), grey as mono8."""
    Image = _pil()
    try:
        img = Image.open(io.BytesIO(np.asarray(msg.data, np.uint8).tobytes()))
        img.load()
    except Exception as exc:  # noqa: BLE001 - Pillow raises many types for bad data
        raise InputError(source, f"cannot decode {msg.format!r} image: {exc}") from None
    if img.mode in ("L", "I;16", "1"):
        return np.asarray(img.convert("L"))[:, :, None], "mono8"
    rgb = np.asarray(img.convert("RGB"))
    return np.ascontiguousarray(rgb[..., ::-1]), "bgr8"
