"""What Foxglove (and RViz) draw: 2-D boxes as ``foxglove_msgs/ImageAnnotations``, vessels as 3-D markers.

``foxglove_msgs`` is not in rosbags' type stores; its ROS 2 message definitions
(:data:`~seatwin.recording.messages.FOXGLOVE_MSGS`, the
current schema of the Foxglove SDK, per-annotation ``metadata`` included) are registered in seatwin's stores
from their ``.msg`` text, so each bag carries them (MCAP schema, SQLite3 ``message_definitions``, ROS 1
connection header) and Foxglove decodes them with no package installed.

* :func:`image_annotations`: one ``LINE_LOOP`` box per label (pixel edges: the top-left corner of the
  top-left pixel is (0, 0)) and a text above it (``Finn 83 % visible``); each box's ``metadata`` holds
  ``instance``, ``class``, ``visible_fraction`` and ``truncation`` (what ``vision_msgs`` has no field for).
* :func:`vessel_marker_specs` → :func:`marker_array_bytes`: ``visualization_msgs/MarkerArray``, per vessel a
  ``CUBE`` of its length, beam and height and a ``TEXT_VIEW_FACING`` name, in the vessel's body frame
  (``frame_locked``, stamp 0: they move with /tf), serialised by hand.
  MarkerArray rather than ``foxglove_msgs/SceneUpdate``: RViz draws only the former, Foxglove's 3-D panel
  both, so one topic serves both viewers.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from rosbags.typesys.store import Typestore

from seatwin.recording.messages import header, split_stamp

MARKER_PERIOD_S = 1.0
"""The vessel markers are written once a second of recording (the first ground-truth step, then every step
1 s or more after the last): they never change within a run and live until replaced, and a viewer that
seeks shows the latest one before the seek point."""

LINE_LOOP = 2
BOX_COLOR = (1.0, 0.85, 0.0, 1.0)
"""Yellow, as ``seatwin labels export`` draws the boxes."""
VESSEL_COLOR = (0.1, 0.6, 1.0, 0.6)
OWNSHIP_COLOR = (1.0, 0.35, 0.1, 0.6)


@dataclass(frozen=True)
class LabelAnnotation:
    """One ground-truth box: pixel edges (x_min, y_min, x_max, y_max), the instance and what is seen of it."""

    instance: str
    label: str
    x_min: float
    y_min: float
    x_max: float
    y_max: float
    visible_fraction: float
    truncation: float


def _time(store: Typestore, t: float) -> Any:
    sec, nsec = split_stamp(t)
    return store.types["builtin_interfaces/msg/Time"](sec=sec, nanosec=nsec)


def _color(store: Typestore, rgba: tuple[float, float, float, float]) -> Any:
    r, g, b, a = rgba
    return store.types["foxglove_msgs/msg/Color"](r=r, g=g, b=b, a=a)


def image_annotations(store: Typestore, t: float, labels: Sequence[LabelAnnotation]) -> Any:
    """``foxglove_msgs/ImageAnnotations`` of ``labels`` at POSIX time ``t``."""
    T = store.types
    stamp = _time(store, t)
    P, KV = T["foxglove_msgs/msg/Point2"], T["foxglove_msgs/msg/KeyValuePair"]
    box_color, clear = _color(store, BOX_COLOR), _color(store, (0.0, 0.0, 0.0, 0.0))
    points, texts = [], []
    for b in labels:
        meta = [
            KV(key="instance", value=b.instance),
            KV(key="class", value=b.label),
            KV(key="visible_fraction", value=f"{b.visible_fraction:.4f}"),
            KV(key="truncation", value=f"{b.truncation:.4f}"),
        ]
        corners = [(b.x_min, b.y_min), (b.x_max, b.y_min), (b.x_max, b.y_max), (b.x_min, b.y_max)]
        points.append(
            T["foxglove_msgs/msg/PointsAnnotation"](
                timestamp=stamp,
                type=LINE_LOOP,
                points=[P(x=float(x), y=float(y)) for x, y in corners],
                outline_color=box_color,
                outline_colors=[],
                fill_color=clear,
                thickness=2.0,
                metadata=meta,
            )
        )
        text = f"{b.instance} {100 * b.visible_fraction:.0f} % visible"
        if b.truncation > 0:
            text += f", {100 * b.truncation:.0f} % cut"
        texts.append(
            T["foxglove_msgs/msg/TextAnnotation"](
                timestamp=stamp,
                position=P(x=float(b.x_min), y=float(max(b.y_min - 2.0, 12.0))),
                text=text,
                font_size=12.0,
                text_color=box_color,
                background_color=_color(store, (0.0, 0.0, 0.0, 0.5)),
                metadata=meta,
            )
        )
    return T["foxglove_msgs/msg/ImageAnnotations"](timestamp=stamp, circles=[], points=points, texts=texts, metadata=[])


def default_message(store: Typestore, typename: str, **values: Any) -> Any:
    """A ``typename`` message with ``values`` and every other field zero / empty (works on both ROS 1 and
    ROS 2 stores, whose ``visualization_msgs/Marker`` differ)."""
    from rosbags.typesys.base import Nodetype

    _, fields = store.fielddefs[typename]
    out: dict[str, Any] = {}
    for name, desc in fields:
        if name in values:
            out[name] = values[name]
            continue
        kind, rest = desc
        if kind == Nodetype.BASE:
            base = rest[0]
            out[name] = "" if base == "string" else (False if base == "bool" else 0)
        elif kind == Nodetype.NAME:
            out[name] = default_message(store, rest)
        else:  # arrays and sequences
            sub, count = rest
            if sub[0] == Nodetype.BASE and sub[1][0] != "string":
                dtype = {"bool": np.bool_, "float32": np.float32, "float64": np.float64}.get(sub[1][0], np.uint8)
                out[name] = np.zeros(count if kind == Nodetype.ARRAY else 0, dtype=dtype)
            else:
                out[name] = []
    return store.types[typename](**out)


@dataclass(frozen=True)
class MarkerSpec:
    """What one ``visualization_msgs/Marker`` of :func:`vessel_marker_specs` says (the rest is zero / empty)."""

    frame_id: str
    id: int
    type: int
    z: float
    scale: tuple[float, float, float]
    color: tuple[float, float, float, float]
    text: str
    ns: str = "vessels"


CUBE, TEXT_VIEW_FACING = 1, 9


def vessel_marker_specs(vessels: Sequence[tuple[str, str, tuple[float, float, float], bool]]) -> list[MarkerSpec]:
    """Per (name, body frame, (length, beam, height), ownship) a box and its name above it; frame-locked, stamp 0.

    The body frame is FRD (z down): the box's centre is half its height above the waterline, at z = −height/2.
    A vessel of unknown size (zeros) gets its name only."""
    out = []
    for k, (name, frame, (length, beam, height), own) in enumerate(vessels):
        if length > 0 and beam > 0 and height > 0:
            color = OWNSHIP_COLOR if own else VESSEL_COLOR
            out.append(MarkerSpec(frame, 2 * k, CUBE, -height / 2.0, (length, beam, height), color, ""))
        out.append(MarkerSpec(frame, 2 * k + 1, TEXT_VIEW_FACING, -height - 2.0, (0.0, 0.0, 2.0), (1.0, 1.0, 1.0, 1.0), name))
    return out


def vessel_markers(store: Typestore, specs: Sequence[MarkerSpec]) -> Any:
    """``visualization_msgs/MarkerArray`` of ``specs`` as message objects (the reference of :func:`marker_array_bytes`)."""
    T = store.types
    markers = []
    for m in specs:
        pose = T["geometry_msgs/msg/Pose"](
            position=T["geometry_msgs/msg/Point"](x=0.0, y=0.0, z=float(m.z)),
            orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        )
        markers.append(
            default_message(
                store,
                "visualization_msgs/msg/Marker",
                header=header(store, 0.0, m.frame_id),
                ns=m.ns,
                id=m.id,
                type=m.type,
                action=0,
                pose=pose,
                scale=T["geometry_msgs/msg/Vector3"](x=float(m.scale[0]), y=float(m.scale[1]), z=float(m.scale[2])),
                color=T["std_msgs/msg/ColorRGBA"](r=m.color[0], g=m.color[1], b=m.color[2], a=m.color[3]),
                frame_locked=True,
                text=m.text,
            )
        )
    return T["visualization_msgs/msg/MarkerArray"](markers=markers)


def marker_array_bytes(specs: Sequence[MarkerSpec], ros1: bool) -> bytes:
    """``visualization_msgs/MarkerArray`` of ``specs`` serialised by hand (CDR: ROS 2 Humble's Marker; ROS 1:
    Noetic's), byte for byte what rosbags' serialisers give (tested) without their ~0.1 s first-use compile."""
    from seatwin.recording.fast_cdr import _Bytes

    b = _Bytes(ros1)
    b.put("I", len(specs))
    for m in specs:
        if ros1:
            b.put("I", 0)  # seq
        b.put("i" if not ros1 else "I", 0)
        b.put("I", 0)  # stamp 0: the latest transform
        b.string(m.frame_id)
        b.string(m.ns)
        for v in (m.id, m.type, 0):  # id, type, action ADD
            b.put("i", v)
        for v in (0.0, 0.0, float(m.z), 0.0, 0.0, 0.0, 1.0, *(float(s) for s in m.scale)):  # pose, scale
            b.put("d", v)
        for v in m.color:
            b.put("f", v)
        b.put("i", 0)  # lifetime 0: forever
        b.put("i" if ros1 else "I", 0)
        b.put("B", 1)  # frame_locked
        b.put("I", 0)  # points
        b.put("I", 0)  # colors
        if not ros1:
            b.string("")  # texture_resource
            b.put("i", 0)  # texture: header stamp, frame_id, format, data
            b.put("I", 0)
            b.string("")
            b.string("")
            b.put("I", 0)
            b.put("I", 0)  # uv_coordinates
        b.string(m.text)
        b.string("")  # mesh_resource
        if not ros1:
            b.string("")  # mesh_file: filename, data
            b.put("I", 0)
        b.put("B", 0)  # mesh_use_embedded_materials
    return bytes(b.buf)
