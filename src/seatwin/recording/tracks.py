"""A tracker's tracks as ROS messages, one set per tracker instant (``seatwin track --out-bag``).

Per scan time (every instant the tracker produced output, with or without tracks), in the world
frame ``world_ned`` (positions north, east; the tracker's state ``[north, v_north, east, v_east]``):

* ``/tracks/odom`` — ``nav_msgs/Odometry``, one per live track: ``child_frame_id`` ``track/<id>``,
  position (north, east, 0), identity orientation (so the twist, in the child frame, is the world
  velocity v_north, v_east), the position and velocity covariances from the track's P; what the
  tracker does not estimate (height, attitude, vertical and angular rates) has variance
  :data:`UNKNOWN_VARIANCE`. Every ROS tool reads it; existence and confirmation are in the other two.
* ``/tracks/markers`` — ``visualization_msgs/MarkerArray`` (RViz and Foxglove): ``DELETEALL`` then per
  track its 2σ position ellipse (a flat cylinder along the covariance's axes), its velocity (an arrow
  over 10 s of travel) and a text ``T<id> <existence %>``; confirmed tracks green, tentative grey.
* ``/tracks/scene`` — ``foxglove_msgs/SceneUpdate`` (Foxglove's own 3-D entities): delete all, then one
  entity ``track <id>`` a track, with the same shapes and ``metadata`` holding track_id, existence,
  confirmed, the state and the 4×4 covariance (row-major) as text.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np
from rosbags.typesys.store import Typestore

from seatwin.recording.foxglove import default_message
from seatwin.recording.messages import header, split_stamp, stamp_ns, typestore

TRACK_TOPICS = {"odom": "/tracks/odom", "markers": "/tracks/markers", "scene": "/tracks/scene"}
"""Topic of each kind of track message."""
TYPES = {
    "odom": "nav_msgs/msg/Odometry",
    "markers": "visualization_msgs/msg/MarkerArray",
    "scene": "foxglove_msgs/msg/SceneUpdate",
}
UNKNOWN_VARIANCE = 1e6
"""Variance of what the tracker does not estimate (height, attitude, their rates)."""
CONFIRMED = (0.2, 0.9, 0.3, 0.9)
TENTATIVE = (0.7, 0.7, 0.7, 0.6)
ARROW_S = 10.0
"""The velocity arrow shows this many seconds of travel."""
SIGMAS = 2.0
"""The position ellipse's half axes in standard deviations."""


def track_messages(tracks: Any, fmt: str, frame: str = "world_ned") -> Iterator[tuple[str, str, int, bytes]]:
    """(topic, type, log time ns, serialised bytes) of ``tracks`` (a :class:`~seatwin.evaluation.Tracks`),
    every scan time in order, in the serialisation of bag format ``fmt`` (ROS 1 or CDR)."""
    store = typestore(fmt)
    ser = store.serialize_ros1 if fmt == "ros1" else store.serialize_cdr
    times = np.asarray(tracks.time, float)
    scan_times = np.union1d(np.asarray(tracks.scan_times, float), times)
    for t in scan_times:
        rows = np.flatnonzero(times == t)
        ts = stamp_ns(float(t))
        for k in rows:
            msg = track_odometry(store, float(t), frame, tracks, int(k))
            yield TRACK_TOPICS["odom"], TYPES["odom"], ts, bytes(ser(msg, TYPES["odom"]))
        msg = track_markers(store, float(t), frame, tracks, rows)
        yield TRACK_TOPICS["markers"], TYPES["markers"], ts, bytes(ser(msg, TYPES["markers"]))
        msg = track_scene(store, float(t), frame, tracks, rows)
        yield TRACK_TOPICS["scene"], TYPES["scene"], ts, bytes(ser(msg, TYPES["scene"]))


def _pose(store: Typestore, x: float, y: float, z: float, yaw: float = 0.0) -> Any:
    T = store.types
    return T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=x, y=y, z=z),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2)),
    )


def _vec(store: Typestore, x: float, y: float, z: float) -> Any:
    return store.types["geometry_msgs/msg/Vector3"](x=float(x), y=float(y), z=float(z))


def track_odometry(store: Typestore, t: float, frame: str, tracks: Any, k: int) -> Any:
    """``nav_msgs/Odometry`` of row ``k`` (see the module docstring)."""
    T = store.types
    n, vn, e, ve = (float(v) for v in tracks.state[k])
    P = np.asarray(tracks.covariance[k], float)
    pose_cov = np.diag([0.0, 0.0, UNKNOWN_VARIANCE, UNKNOWN_VARIANCE, UNKNOWN_VARIANCE, UNKNOWN_VARIANCE])
    twist_cov = pose_cov.copy()
    pose_cov[:2, :2] = P[np.ix_([0, 2], [0, 2])]
    twist_cov[:2, :2] = P[np.ix_([1, 3], [1, 3])]
    return T["nav_msgs/msg/Odometry"](
        header=header(store, t, frame),
        child_frame_id=f"track/{int(tracks.track_id[k])}",
        pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=_pose(store, n, e, 0.0), covariance=pose_cov.reshape(-1)),
        twist=T["geometry_msgs/msg/TwistWithCovariance"](
            twist=T["geometry_msgs/msg/Twist"](linear=_vec(store, vn, ve, 0.0), angular=_vec(store, 0.0, 0.0, 0.0)),
            covariance=twist_cov.reshape(-1),
        ),
    )


def _ellipse(P: np.ndarray) -> tuple[float, float, float]:
    """(length along the major axis, along the minor, the major axis' angle from north towards east) of the
    2σ position ellipse of a state covariance."""
    vals, vecs = np.linalg.eigh(P[np.ix_([0, 2], [0, 2])])
    vals = np.clip(vals, 0.0, None)
    major = vecs[:, 1]
    return 2 * SIGMAS * math.sqrt(vals[1]), 2 * SIGMAS * math.sqrt(vals[0]), math.atan2(major[1], major[0])


def _shapes(tracks: Any, k: int) -> tuple[float, float, float, float, float, float, tuple[float, ...], str]:
    """(north, east, v_north, v_east, ellipse major, minor, angle, colour, label) of row ``k``."""
    n, vn, e, ve = (float(v) for v in tracks.state[k])
    color = CONFIRMED if tracks.confirmed[k] else TENTATIVE
    label = f"T{int(tracks.track_id[k])} {100 * float(tracks.existence[k]):.0f} %"
    return n, e, vn, ve, *_ellipse(np.asarray(tracks.covariance[k], float)), color, label  # type: ignore[return-value]


def track_markers(store: Typestore, t: float, frame: str, tracks: Any, rows: np.ndarray) -> Any:
    """``visualization_msgs/MarkerArray``: DELETEALL, then per track its ellipse, velocity arrow and label."""
    T = store.types
    hdr = header(store, t, frame)

    def marker(**values: Any) -> Any:
        return default_message(store, "visualization_msgs/msg/Marker", header=hdr, ns="tracks", **values)

    def rgba(c: tuple[float, ...]) -> Any:
        return T["std_msgs/msg/ColorRGBA"](r=c[0], g=c[1], b=c[2], a=c[3])

    out = [marker(action=3)]  # DELETEALL: tracks that ended disappear
    for k in rows:
        n, e, vn, ve, major, minor, angle, color, label = _shapes(tracks, int(k))
        tid = int(tracks.track_id[k])
        out.append(
            marker(
                id=3 * tid, type=3, pose=_pose(store, n, e, 0.0, angle), scale=_vec(store, major, minor, 0.2), color=rgba(color)
            )
        )
        tip = T["geometry_msgs/msg/Point"](x=n + ARROW_S * vn, y=e + ARROW_S * ve, z=0.0)
        base = T["geometry_msgs/msg/Point"](x=n, y=e, z=0.0)
        out.append(
            marker(
                id=3 * tid + 1,
                type=0,
                pose=_pose(store, 0.0, 0.0, 0.0),
                scale=_vec(store, 0.4, 0.8, 1.0),
                color=rgba(color),
                points=[base, tip],
            )
        )
        out.append(
            marker(
                id=3 * tid + 2,
                type=9,
                pose=_pose(store, n, e, -4.0),
                scale=_vec(store, 0.0, 0.0, 2.0),
                color=rgba((1.0, 1.0, 1.0, 1.0)),
                text=label,
            )
        )
    return T["visualization_msgs/msg/MarkerArray"](markers=out)


def track_scene(store: Typestore, t: float, frame: str, tracks: Any, rows: np.ndarray) -> Any:
    """``foxglove_msgs/SceneUpdate``: delete all, then one entity per track (shapes and metadata)."""
    T = store.types
    sec, nsec = split_stamp(t)
    stamp = T["builtin_interfaces/msg/Time"](sec=sec, nanosec=nsec)

    def color(c: tuple[float, ...]) -> Any:
        return T["foxglove_msgs/msg/Color"](r=c[0], g=c[1], b=c[2], a=c[3])

    def kv(key: str, value: str) -> Any:
        return T["foxglove_msgs/msg/KeyValuePair"](key=key, value=value)

    entities = []
    for k in rows:
        n, e, vn, ve, major, minor, angle, rgba, label = _shapes(tracks, int(k))
        speed = math.hypot(vn, ve)
        meta = [
            kv("track_id", str(int(tracks.track_id[k]))),
            kv("existence", f"{float(tracks.existence[k]):.6f}"),
            kv("confirmed", "true" if tracks.confirmed[k] else "false"),
            kv("state", " ".join(f"{v:.6g}" for v in tracks.state[k])),
            kv("state_names", "north v_north east v_east"),
            kv("covariance", " ".join(f"{v:.6g}" for v in np.asarray(tracks.covariance[k]).reshape(-1))),
        ]
        cyl = T["foxglove_msgs/msg/CylinderPrimitive"](
            pose=_pose(store, n, e, 0.0, angle),
            size=_vec(store, major, minor, 0.2),
            bottom_scale=1.0,
            top_scale=1.0,
            color=color(rgba),
        )
        arrows = []
        if speed > 0:
            arrows.append(
                T["foxglove_msgs/msg/ArrowPrimitive"](
                    pose=_pose(store, n, e, 0.0, math.atan2(ve, vn)),
                    shaft_length=ARROW_S * speed * 0.8,
                    shaft_diameter=0.4,
                    head_length=ARROW_S * speed * 0.2,
                    head_diameter=0.8,
                    color=color(rgba),
                )
            )
        text = T["foxglove_msgs/msg/TextPrimitive"](
            pose=_pose(store, n, e, -4.0),
            billboard=True,
            font_size=14.0,
            scale_invariant=True,
            color=color((1, 1, 1, 1)),
            text=label,
        )
        entities.append(
            default_message(
                store,
                "foxglove_msgs/msg/SceneEntity",
                timestamp=stamp,
                frame_id=frame,
                id=f"track {int(tracks.track_id[k])}",
                metadata=meta,
                arrows=arrows,
                cylinders=[cyl],
                texts=[text],
            )
        )
    deletion = T["foxglove_msgs/msg/SceneEntityDeletion"](timestamp=stamp, type=1, id="")  # ALL earlier than now
    return T["foxglove_msgs/msg/SceneUpdate"](deletions=[deletion], entities=entities)
