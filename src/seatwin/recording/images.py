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


def to_bgr(pixels: NDArray[np.uint8], encoding: str) -> NDArray[np.uint8]:
    """H×W×3 bgr8 from pixels in ``encoding`` (rgb8 reversed, mono8 repeated, bgr8 as it is)."""
    if encoding in ("bgr8", "8UC3"):
        return pixels
    return np.ascontiguousarray(to_rgb(pixels, encoding)[..., ::-1])


def _pil() -> Any:
    try:
        from PIL import Image
    except ImportError:  # pragma: no cover - Pillow ships with matplotlib
        raise InputError("CompressedImage", "JPEG/PNG needs Pillow (pip install pillow)") from None
    return Image


_PIL_FORMAT = {"jpg": "JPEG", "jpeg": "JPEG", "png": "PNG"}
PNG_LEVEL = 1
"""zlib level of PNG images: the fastest (level 6, Pillow's default, takes ~2.5× as long for ~30 % less)."""
MAX_PIXELS = 64 * 1024 * 1024
"""Largest compressed image decoded (pixels): a 40-byte PNG can declare 2³¹ × 2³¹ pixels; Pillow only warns
below twice its own limit (89 M pixels)."""


def transport_format(fmt: str, encoding: str = "bgr8") -> str:
    """``CompressedImage.format`` as ROS's compressed_image_transport writes it: the source encoding, then what
    the payload holds (colour as bgr8): ``bgr8; jpeg compressed bgr8``, ``mono8; png compressed mono8``."""
    kind = _PIL_FORMAT.get(fmt.lower())
    if kind is None:
        raise InputError("CompressedImage", f"unsupported format {fmt!r}; expected jpeg or png")
    target = "mono8" if CHANNELS.get(encoding) == 1 else "bgr8"
    return f"{encoding}; {kind.lower()} compressed {target}"


def encode_image(pixels: NDArray[np.uint8], fmt: str = "jpeg", encoding: str = "bgr8", quality: int = 90) -> bytes:
    """JPEG (``quality``) or PNG (zlib level :data:`PNG_LEVEL`) bytes of an H×W(×C) image given in ``encoding``
    (bgr8 handed to Pillow as it is, its raw ``BGR`` mode: no reordered copy)."""
    Image = _pil()
    kind = _PIL_FORMAT.get(fmt.lower())
    if kind is None:
        raise InputError("CompressedImage", f"unsupported format {fmt!r}; expected jpeg or png")
    a = np.ascontiguousarray(pixels, np.uint8)
    h, w = a.shape[:2]
    if CHANNELS.get(encoding) == 1:
        img = Image.frombuffer("L", (w, h), a, "raw", "L", 0, 1)
    elif encoding in ("bgr8", "8UC3"):
        img = Image.frombuffer("RGB", (w, h), a, "raw", "BGR", 0, 1)
    else:
        img = Image.frombuffer("RGB", (w, h), a, "raw", "RGB", 0, 1)
    bio = io.BytesIO()
    img.save(bio, format=kind, **({"quality": quality} if kind == "JPEG" else {"compress_level": PNG_LEVEL}))
    return bio.getvalue()


def decode_compressed(msg: Any, source: str = "CompressedImage") -> tuple[NDArray[np.uint8], str]:
    """(pixels, encoding) of a ``sensor_msgs/CompressedImage``: colour as bgr8 (like cv_bridge), grey as mono8.

    Only JPEG and PNG are decoded (what compressed_image_transport writes), at most :data:`MAX_PIXELS`; anything
    else, a damaged payload included, is one :class:`InputError` naming ``source`` and the format."""
    import warnings

    Image = _pil()
    fmt = str(getattr(msg, "format", "?"))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            img = Image.open(io.BytesIO(np.asarray(msg.data, np.uint8).tobytes()), formats=("JPEG", "PNG"))
            w, h = img.size
            if w * h > MAX_PIXELS:
                raise InputError(source, f"{fmt!r} image of {w}×{h} pixels exceeds the {MAX_PIXELS} decoded at most")
            img.load()
            if img.mode in ("L", "LA", "I", "I;16", "1"):
                return np.asarray(img.convert("L"))[:, :, None], "mono8"
            rgb = np.asarray(img.convert("RGB"))
    except InputError:
        raise
    except Exception as exc:  # noqa: BLE001 - Pillow raises many types for bad data
        raise InputError(source, f"cannot decode the {fmt!r} image: {type(exc).__name__}: {exc}") from None
    return np.ascontiguousarray(rgb[..., ::-1]), "bgr8"
