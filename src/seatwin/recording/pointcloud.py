"""PointCloud2 field layouts: the VLP-16 layout of thesis Table 4.2, the radar-plot layout, and
turning any ``PointField`` list into a numpy structured dtype (for reading foreign drivers).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError

# sensor_msgs/PointField datatype enumeration → numpy type code (little endian added later).
POINTFIELD_TYPES: dict[int, str] = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}
INT8, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64 = range(1, 9)
MAX_POINT_STEP = 2**31 - 1
"""Largest ``point_step`` read: numpy's item size is a C int."""


@dataclass(frozen=True)
class Field:
    """One ``sensor_msgs/PointField``."""

    name: str
    offset: int
    datatype: int
    count: int = 1


@dataclass(frozen=True)
class Layout:
    """A fixed point layout: its fields and ``point_step``."""

    fields: tuple[Field, ...]
    point_step: int

    @cached_property
    def dtype(self) -> np.dtype:
        return dtype_from_fields(self.fields, self.point_step, big_endian=False)

    @cached_property
    def field_types(self) -> dict[str, np.dtype]:
        """Field name → its numpy type (the base type of a ``count > 1`` field)."""
        return {name: self.dtype[name].base for name in self.dtype.names or ()}


VLP16_LAYOUT = Layout(
    fields=(
        Field("x", 0, FLOAT32),
        Field("y", 4, FLOAT32),
        Field("z", 8, FLOAT32),
        Field("intensity", 12, FLOAT32),
        Field("ring", 16, UINT16),
        Field("time", 18, FLOAT32),
    ),
    point_step=24,
)
"""Thesis Table 4.2 (VLP-16 in ROS): x, y, z, intensity FLOAT32 at 0/4/8/12, ring UINT16 at 16,
time FLOAT32 at 18 (seconds since the sweep start); 24 bytes a point (bytes 22–23 padding).
The thesis's GPU build wrote ring as FLOAT32; we follow the table (and the real driver)."""

RADAR_LAYOUT = Layout(
    fields=(
        Field("x", 0, FLOAT32),
        Field("y", 4, FLOAT32),
        Field("z", 8, FLOAT32),
        Field("intensity", 12, FLOAT32),
        Field("range", 16, FLOAT32),
        Field("bearing", 20, FLOAT32),
        Field("time", 24, FLOAT32),
    ),
    point_step=28,
)
"""Radar plots (detections) as PointCloud2: x, y, z in ``header.frame_id`` (the radar frame,
REP-103 x forward / y left / z up, or the world NED frame for imported datasets); ``range`` [m]
horizontal distance from the radar; ``bearing`` [rad] clockwise seen from above from the frame's
x axis (relative bearing in the radar frame, true bearing in the NED world frame); ``time`` [s]
since the scan start (0 when unknown); ``intensity`` (echo strength, 0 when unknown)."""


def dtype_from_fields(fields: Sequence[object], point_step: int, big_endian: bool = False) -> np.dtype:
    """A structured dtype (itemsize ``point_step``) from PointField-like objects (name, offset, datatype, count).

    Fields with an empty name are skipped; repeated names get a ``_1``, ``_2`` suffix; a field with
    ``count > 1`` becomes a sub-array. Unknown datatypes or fields beyond ``point_step`` are an
    :class:`InputError`.
    """
    order = ">" if big_endian else "<"
    names: list[str] = []
    formats: list[object] = []
    offsets: list[int] = []
    for f in fields:
        name, offset, datatype = str(f.name), int(f.offset), int(f.datatype)  # type: ignore[attr-defined]
        count = max(int(getattr(f, "count", 1)), 1)
        if not name:
            continue
        code = POINTFIELD_TYPES.get(datatype)
        if code is None:
            raise InputError("PointCloud2", f"field {name!r} has unknown datatype {datatype}; expected 1..8")
        base = np.dtype(order + code)
        if offset < 0 or offset + base.itemsize * count > point_step:
            raise InputError(
                "PointCloud2", f"field {name!r} (offset {offset}, {count}×{base.itemsize} B) exceeds point_step {point_step}"
            )
        unique, k = name, 1
        while unique in names:
            unique, k = f"{name}_{k}", k + 1
        names.append(unique)
        formats.append(base if count == 1 else (base, (count,)))
        offsets.append(offset)
    return np.dtype({"names": names, "formats": formats, "offsets": offsets, "itemsize": point_step})


def pack(layout: Layout, **columns: ArrayLike) -> NDArray[np.uint8]:
    """Points of ``layout`` as a flat uint8 array (the PointCloud2 ``data``); absent columns are 0.

    All given columns must have the same length; padding bytes are zero.
    """
    arrays, n = checked_columns(layout, columns)
    out = np.zeros(n, dtype=layout.dtype)
    fill(out, arrays)
    return out.view(np.uint8)


def checked_columns(layout: Layout, columns: dict[str, ArrayLike | None]) -> tuple[dict[str, NDArray[Any]], int]:
    """The given (not None) columns as arrays, and their common length; an :class:`InputError` for
    unknown fields, columns of different lengths, or integers out of their field's range."""
    types = layout.field_types
    unknown = sorted(k for k in columns if k not in types)
    if unknown:
        raise InputError("point cloud", f"unknown field(s) {unknown}; layout has {list(types)}")
    arrays = {k: v if type(v) is np.ndarray else np.asarray(v) for k, v in columns.items() if v is not None}
    sizes = {a.size for a in arrays.values()}
    if len(sizes) > 1:
        raise InputError("point cloud", f"columns differ in length: { {k: a.size for k, a in arrays.items()} }")
    n = sizes.pop() if sizes else 0
    for k, a in arrays.items():
        kind = types[k]
        if kind.kind in "iu" and n and a.dtype != kind and not np.can_cast(a.dtype, kind, "safe"):
            info = np.iinfo(kind)
            lo, hi = a.min(), a.max()
            if lo < info.min or hi > info.max or (a.dtype.kind == "f" and not np.isfinite(a).all()):
                raise InputError(
                    "point cloud", f"field {k!r} ({kind.name}) needs values in [{info.min}, {info.max}], got [{lo}, {hi}]"
                )
    return arrays, n


def fill(points: NDArray[Any], arrays: dict[str, NDArray[Any]]) -> None:
    """Write checked columns (:func:`checked_columns`) into a zeroed structured array of the layout."""
    n = len(points)
    for k, a in arrays.items():
        points[k] = a.reshape(n)


def unpack(
    data: ArrayLike | bytes,
    fields: Sequence[object],
    point_step: int,
    width: int,
    height: int = 1,
    row_step: int = 0,
    big_endian: bool = False,
) -> NDArray:
    """The points of a PointCloud2 as a flat structured array (fields named as in the message).

    Handles rows padded beyond ``width·point_step`` and ``row_step = 0`` (as in the thesis bags).
    """
    if min(point_step, width, height, row_step) < 0:
        raise InputError("PointCloud2", f"negative size: point_step {point_step}, {height}×{width} points, row_step {row_step}")
    n = width * height
    if n and point_step == 0:
        raise InputError("PointCloud2", f"point_step is 0 for {height}×{width} points")
    if point_step > MAX_POINT_STEP:
        raise InputError("PointCloud2", f"point_step {point_step} exceeds {MAX_POINT_STEP} (the largest point numpy can hold)")
    buf = np.frombuffer(data, dtype=np.uint8) if not isinstance(data, np.ndarray) else data.view(np.uint8).reshape(-1)
    if n and point_step > buf.size:
        raise InputError("PointCloud2", f"point_step {point_step} exceeds the data's {buf.size} bytes")
    dtype = dtype_from_fields(fields, point_step, big_endian)
    packed = width * point_step
    row = row_step if row_step else packed
    if row < packed:
        raise InputError("PointCloud2", f"row_step {row_step} is smaller than width·point_step = {packed}")
    if n and buf.size < row * (height - 1) + packed:
        raise InputError(
            "PointCloud2",
            f"data has {buf.size} bytes, expected {row * (height - 1) + packed} for {height}×{width} points "
            f"(point_step {point_step}, row_step {row}): width × height × point_step exceeds the data",
        )
    if n == 0:
        return np.zeros(0, dtype=dtype)
    if row == packed:
        return np.ascontiguousarray(buf[: n * point_step]).view(dtype)
    rows = np.lib.stride_tricks.as_strided(buf, shape=(height, packed), strides=(row, 1))
    return np.ascontiguousarray(rows).reshape(-1).view(dtype)
