"""ROS message builders over a rosbags typestore (ROS 2 Humble for rosbag2, ROS 1 Noetic for .bag).

Frames: ground truth is in the world frame (local NED); a vessel pose is its body frame
(x forward, y starboard, z down) in NED, so its orientation is the heading ψ about z (down):
q = (x 0, y 0, z sin ψ/2, w cos ψ/2). Odometry twists are in the body frame (ROS convention:
twist in ``child_frame_id``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from rosbags.typesys import Stores, get_typestore
from rosbags.typesys.store import Typestore

from seatwin.errors import InputError
from seatwin.geo import NED_TO_ENU, GeodeticOrigin, mount_matrix, ned_to_llh_exact
from seatwin.recording.pointcloud import Layout

_STORES: dict[str, Typestore] = {}


def typestore(fmt: str) -> Typestore:
    """The typestore for a bag format: ROS 1 Noetic for ``ros1``, ROS 2 Humble otherwise."""
    key = "ros1" if fmt == "ros1" else "ros2"
    if key not in _STORES:
        store = get_typestore(Stores.ROS1_NOETIC if key == "ros1" else Stores.ROS2_HUMBLE)
        if "tf2_msgs/msg/TFMessage" not in store.types:  # rosbags' Noetic store lacks tf2_msgs
            from rosbags.typesys import get_types_from_msg

            store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", "tf2_msgs/msg/TFMessage"))
        for package in (VISION_MSGS, FOXGLOVE_MSGS):  # neither store ships vision_msgs or foxglove_msgs
            from rosbags.typesys import get_types_from_msg

            types: dict[str, Any] = {}
            for name, text in package.items():
                types.update(get_types_from_msg(text, name))
            store.register(types)
        _STORES[key] = store
    return _STORES[key]


VISION_MSGS: dict[str, str] = {
    "vision_msgs/msg/Point2D": "float64 x\nfloat64 y",
    "vision_msgs/msg/Pose2D": "vision_msgs/Point2D position\nfloat64 theta",
    "vision_msgs/msg/BoundingBox2D": "vision_msgs/Pose2D center\nfloat64 size_x\nfloat64 size_y",
    "vision_msgs/msg/ObjectHypothesis": "string class_id\nfloat64 score",
    "vision_msgs/msg/ObjectHypothesisWithPose": "vision_msgs/ObjectHypothesis hypothesis\ngeometry_msgs/PoseWithCovariance pose",
    "vision_msgs/msg/Detection2D": "std_msgs/Header header\nvision_msgs/ObjectHypothesisWithPose[] results\n"
    "vision_msgs/BoundingBox2D bbox\nstring id",
    "vision_msgs/msg/Detection2DArray": "std_msgs/Header header\nvision_msgs/Detection2D[] detections",
}
"""``vision_msgs`` 4.x (ROS 2 Humble) definitions of the 2-D detection messages, registered in both
typestores (a ROS 1 bag carries the same layout with its own Header)."""


_KV = "foxglove_msgs/KeyValuePair[] metadata"
FOXGLOVE_MSGS: dict[str, str] = {
    "foxglove_msgs/msg/Point2": "float64 x\nfloat64 y",
    "foxglove_msgs/msg/Color": "float64 r\nfloat64 g\nfloat64 b\nfloat64 a",
    "foxglove_msgs/msg/KeyValuePair": "string key\nstring value",
    "foxglove_msgs/msg/CircleAnnotation": "builtin_interfaces/Time timestamp\nfoxglove_msgs/Point2 position\n"
    "float64 diameter\nfloat64 thickness\nfoxglove_msgs/Color fill_color\nfoxglove_msgs/Color outline_color\n" + _KV,
    "foxglove_msgs/msg/PointsAnnotation": "builtin_interfaces/Time timestamp\nuint8 UNKNOWN=0\nuint8 POINTS=1\n"
    "uint8 LINE_LOOP=2\nuint8 LINE_STRIP=3\nuint8 LINE_LIST=4\nuint8 type\nfoxglove_msgs/Point2[] points\n"
    "foxglove_msgs/Color outline_color\nfoxglove_msgs/Color[] outline_colors\nfoxglove_msgs/Color fill_color\n"
    "float64 thickness\n" + _KV,
    "foxglove_msgs/msg/TextAnnotation": "builtin_interfaces/Time timestamp\nfoxglove_msgs/Point2 position\n"
    "string text\nfloat64 font_size\nfoxglove_msgs/Color text_color\nfoxglove_msgs/Color background_color\n" + _KV,
    "foxglove_msgs/msg/ImageAnnotations": "builtin_interfaces/Time timestamp\nfoxglove_msgs/CircleAnnotation[] circles\n"
    "foxglove_msgs/PointsAnnotation[] points\nfoxglove_msgs/TextAnnotation[] texts\n" + _KV,
    # 3-D scene entities (tracks): the primitives as in foxglove/schemas' ros2 definitions, without per-primitive metadata
    "foxglove_msgs/msg/ArrowPrimitive": "geometry_msgs/Pose pose\nfloat64 shaft_length\nfloat64 shaft_diameter\n"
    "float64 head_length\nfloat64 head_diameter\nfoxglove_msgs/Color color",
    "foxglove_msgs/msg/CubePrimitive": "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfoxglove_msgs/Color color",
    "foxglove_msgs/msg/SpherePrimitive": "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfoxglove_msgs/Color color",
    "foxglove_msgs/msg/CylinderPrimitive": "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfloat64 bottom_scale\n"
    "float64 top_scale\nfoxglove_msgs/Color color",
    "foxglove_msgs/msg/LinePrimitive": "uint8 LINE_STRIP=0\nuint8 LINE_LOOP=1\nuint8 LINE_LIST=2\nuint8 type\n"
    "geometry_msgs/Pose pose\nfloat64 thickness\nbool scale_invariant\ngeometry_msgs/Point[] points\n"
    "foxglove_msgs/Color color\nfoxglove_msgs/Color[] colors\nuint32[] indices",
    "foxglove_msgs/msg/TriangleListPrimitive": "geometry_msgs/Pose pose\ngeometry_msgs/Point[] points\n"
    "foxglove_msgs/Color color\nfoxglove_msgs/Color[] colors\nuint32[] indices",
    "foxglove_msgs/msg/TextPrimitive": "geometry_msgs/Pose pose\nbool billboard\nfloat64 font_size\nbool scale_invariant\n"
    "foxglove_msgs/Color color\nstring text",
    "foxglove_msgs/msg/ModelPrimitive": "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nfoxglove_msgs/Color color\n"
    "bool override_color\nstring url\nstring media_type\nuint8[] data",
    "foxglove_msgs/msg/SceneEntityDeletion": "builtin_interfaces/Time timestamp\nuint8 MATCHING_ID=0\nuint8 ALL=1\n"
    "uint8 type\nstring id",
    "foxglove_msgs/msg/SceneEntity": "builtin_interfaces/Time timestamp\nstring frame_id\nstring id\n"
    "builtin_interfaces/Duration lifetime\nbool frame_locked\n" + _KV + "\nfoxglove_msgs/ArrowPrimitive[] arrows\n"
    "foxglove_msgs/CubePrimitive[] cubes\nfoxglove_msgs/SpherePrimitive[] spheres\n"
    "foxglove_msgs/CylinderPrimitive[] cylinders\nfoxglove_msgs/LinePrimitive[] lines\n"
    "foxglove_msgs/TriangleListPrimitive[] triangles\nfoxglove_msgs/TextPrimitive[] texts\nfoxglove_msgs/ModelPrimitive[] models",
    "foxglove_msgs/msg/SceneUpdate": "foxglove_msgs/SceneEntityDeletion[] deletions\nfoxglove_msgs/SceneEntity[] entities",
}
"""``foxglove_msgs`` ROS 2 definitions of the Foxglove SDK's current schema (comments left out), in dependency
order; registered in both typestores (:mod:`seatwin.recording.foxglove` builds the messages)."""


def split_stamp(t: float) -> tuple[int, int]:
    """POSIX seconds → (sec, nanosec) with 0 ≤ nanosec < 1e9."""
    if not math.isfinite(t):
        raise InputError("time stamp", f"must be a finite number of seconds, got {t!r}")
    sec = math.floor(t)
    nsec = round((t - sec) * 1e9)
    if nsec >= 1_000_000_000:
        sec, nsec = sec + 1, nsec - 1_000_000_000
    return int(sec), int(nsec)


def stamp_ns(t: float) -> int:
    """POSIX seconds → integer nanoseconds (the bag's log time)."""
    sec, nsec = split_stamp(t)
    return sec * 1_000_000_000 + nsec


def ns_to_s(ns: int) -> float:
    return ns // 1_000_000_000 + (ns % 1_000_000_000) * 1e-9


def header(store: Typestore, t: float, frame_id: str) -> Any:
    T = store.types
    sec, nsec = split_stamp(t)
    stamp = T["builtin_interfaces/msg/Time"](sec=sec, nanosec=nsec)
    H = T["std_msgs/msg/Header"]
    if "seq" in H.__dataclass_fields__:
        return H(seq=0, stamp=stamp, frame_id=frame_id)
    return H(stamp=stamp, frame_id=frame_id)


def quaternion_yaw(yaw: float) -> tuple[float, float, float, float]:
    """(x, y, z, w) of a rotation by ``yaw`` about the frame's z axis."""
    return 0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)


def quaternion_from_matrix(r: NDArray[np.float64]) -> tuple[float, float, float, float]:
    """(x, y, z, w) of a rotation matrix (w ≥ 0)."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(np.asarray(r, float)).as_quat()
    if w < 0:
        x, y, z, w = -x, -y, -z, -w
    return float(x), float(y), float(z), float(w)


R_ENU_NED = NED_TO_ENU
"""Maps NED coordinates to ENU: the rotation of the ``world_ned`` frame in the ``world`` (ENU) frame."""


def mount_rotation(
    convention: str = "flu", roll: float = 0.0, pitch: float = 0.0, yaw: float = 0.0
) -> tuple[float, float, float, float]:
    """Quaternion (x, y, z, w) of a sensor frame in the vessel body frame (FRD).

    The sensor is first turned by yaw (to starboard), pitch (nose up), roll (starboard down) —
    Z-Y-X Euler angles in the body FRD frame — and its axes follow ``convention``: ``flu``
    (REP-103 lidar/radar: x forward, y left, z up), ``optical`` (camera: z forward, x right,
    y down) or ``frd`` (the matrix: :func:`seatwin.geo.mount_matrix`).
    """
    return quaternion_from_matrix(mount_matrix(convention, roll=roll, pitch=pitch, yaw=yaw))


@dataclass(frozen=True)
class StaticTransform:
    """A fixed transform: the pose of ``child`` in ``parent`` (translation [m], quaternion x, y, z, w)."""

    parent: str
    child: str
    translation: tuple[float, float, float]
    rotation: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)


def transform_stamped(
    store: Typestore, t: float, parent: str, child: str, translation: Sequence[float], rotation: Sequence[float]
) -> Any:
    T = store.types
    return T["geometry_msgs/msg/TransformStamped"](
        header=header(store, t, parent),
        child_frame_id=child,
        transform=T["geometry_msgs/msg/Transform"](
            translation=T["geometry_msgs/msg/Vector3"](x=float(translation[0]), y=float(translation[1]), z=float(translation[2])),
            rotation=_quat(store, rotation),
        ),
    )


def tf_message(store: Typestore, transforms: Sequence[Any]) -> Any:
    return store.types["tf2_msgs/msg/TFMessage"](transforms=list(transforms))


def _quat(store: Typestore, q: Sequence[float]) -> Any:
    return store.types["geometry_msgs/msg/Quaternion"](x=float(q[0]), y=float(q[1]), z=float(q[2]), w=float(q[3]))


def _point(store: Typestore, p: Sequence[float]) -> Any:
    return store.types["geometry_msgs/msg/Point"](x=float(p[0]), y=float(p[1]), z=float(p[2]))


def _vec(store: Typestore, v: Sequence[float]) -> Any:
    return store.types["geometry_msgs/msg/Vector3"](x=float(v[0]), y=float(v[1]), z=float(v[2]))


def point_cloud2(
    store: Typestore,
    t: float,
    frame_id: str,
    layout: Layout,
    data: NDArray[np.uint8],
    *,
    is_dense: bool = True,
    row_step_zero: bool = False,
) -> Any:
    """A PointCloud2 of ``layout`` (height 1, little endian). ``row_step_zero`` reproduces the thesis bags."""
    T = store.types
    PF = T["sensor_msgs/msg/PointField"]
    width = data.size // layout.point_step
    return T["sensor_msgs/msg/PointCloud2"](
        header=header(store, t, frame_id),
        height=1,
        width=width,
        fields=[PF(name=f.name, offset=f.offset, datatype=f.datatype, count=f.count) for f in layout.fields],
        is_bigendian=False,
        point_step=layout.point_step,
        row_step=0 if row_step_zero else layout.point_step * width,
        data=data,
        is_dense=is_dense,
    )


IMAGE_CHANNELS = {"bgr8": 3, "rgb8": 3, "mono8": 1}


def image(store: Typestore, t: float, frame_id: str, pixels: NDArray[np.uint8], encoding: str = "bgr8") -> Any:
    """A ``sensor_msgs/Image`` (bgr8 as in the thesis, rgb8 or mono8) from an H×W(×C) uint8 array."""
    if encoding not in IMAGE_CHANNELS:
        raise ValueError(f"unsupported encoding {encoding!r}; expected one of {sorted(IMAGE_CHANNELS)}")
    a = np.ascontiguousarray(pixels, dtype=np.uint8)
    c = IMAGE_CHANNELS[encoding]
    if a.ndim == 2 and c == 1:
        a = a[:, :, None]
    if a.ndim != 3 or a.shape[2] != c:
        raise ValueError(f"{encoding} needs an H×W×{c} array, got shape {pixels.shape}")
    h, w = a.shape[:2]
    return store.types["sensor_msgs/msg/Image"](
        header=header(store, t, frame_id),
        height=h,
        width=w,
        encoding=encoding,
        is_bigendian=0,
        step=w * c,
        data=a.reshape(-1),
    )


def compressed_image(store: Typestore, t: float, frame_id: str, payload: bytes, fmt: str) -> Any:
    """A ``sensor_msgs/CompressedImage`` (``fmt`` e.g. ``jpeg`` or ``png``) from encoded bytes."""
    return store.types["sensor_msgs/msg/CompressedImage"](
        header=header(store, t, frame_id),
        format=fmt,
        data=np.frombuffer(payload, dtype=np.uint8),
    )


def camera_info(
    store: Typestore,
    t: float,
    frame_id: str,
    width: int,
    height: int,
    k: ArrayLike,
    d: Sequence[float],
    r: ArrayLike,
    p: ArrayLike,
    distortion_model: str = "plumb_bob",
) -> Any:
    """A ``sensor_msgs/CameraInfo`` (row-major K 3×3, R 3×3, P 3×4; D as given; no binning, full ROI)."""
    T = store.types
    CI = T["sensor_msgs/msg/CameraInfo"]
    roi = T["sensor_msgs/msg/RegionOfInterest"](x_offset=0, y_offset=0, height=0, width=0, do_rectify=False)
    fields = CI.__dataclass_fields__
    names = ("k", "r", "p", "d") if "k" in fields else ("K", "R", "P", "D")  # ROS 2 lower case, ROS 1 upper
    values = dict(
        zip(
            names,
            (
                np.asarray(k, np.float64).reshape(9),
                np.asarray(r, np.float64).reshape(9),
                np.asarray(p, np.float64).reshape(12),
                np.asarray(d, np.float64).reshape(-1),
            ),
            strict=True,
        )
    )
    return CI(
        header=header(store, t, frame_id),
        height=int(height),
        width=int(width),
        distortion_model=distortion_model,
        binning_x=0,
        binning_y=0,
        roi=roi,
        **values,
    )


@dataclass(frozen=True)
class Box2D:
    """One 2-D detection: centre and size [pixels], an id (the instance) and (class, score) hypotheses."""

    id: str
    center_x: float
    center_y: float
    size_x: float
    size_y: float
    results: tuple[tuple[str, float], ...] = ()


def detection2d_array(store: Typestore, t: float, frame_id: str, boxes: Sequence[Box2D]) -> Any:
    """A ``vision_msgs/Detection2DArray`` (vision_msgs 4.x layout) of ``boxes``."""
    T = store.types
    zeros = np.zeros(36, dtype=np.float64)
    pose = T["geometry_msgs/msg/PoseWithCovariance"](
        pose=T["geometry_msgs/msg/Pose"](position=_point(store, (0, 0, 0)), orientation=_quat(store, (0, 0, 0, 1))),
        covariance=zeros,
    )
    dets = []
    for b in boxes:
        bbox = T["vision_msgs/msg/BoundingBox2D"](
            center=T["vision_msgs/msg/Pose2D"](
                position=T["vision_msgs/msg/Point2D"](x=float(b.center_x), y=float(b.center_y)), theta=0.0
            ),
            size_x=float(b.size_x),
            size_y=float(b.size_y),
        )
        results = [
            T["vision_msgs/msg/ObjectHypothesisWithPose"](
                hypothesis=T["vision_msgs/msg/ObjectHypothesis"](class_id=c, score=float(sc)), pose=pose
            )
            for c, sc in b.results
        ]
        dets.append(T["vision_msgs/msg/Detection2D"](header=header(store, t, frame_id), results=results, bbox=bbox, id=b.id))
    return T["vision_msgs/msg/Detection2DArray"](header=header(store, t, frame_id), detections=dets)


@dataclass(frozen=True)
class VesselPose:
    """Ground truth of one vessel at one time, in the world NED frame (SI units, radians)."""

    name: str
    north: float
    east: float
    heading: float
    """Radians clockwise from north."""
    down: float = 0.0
    v_north: float = 0.0
    v_east: float = 0.0
    yaw_rate: float = 0.0
    """rad/s, positive clockwise seen from above."""
    ownship: bool = False
    llh: tuple[float, float, float] | None = None
    """WGS-84 (latitude °, longitude °, height m) of this position when the caller converted it
    already (e.g. a whole run at once); otherwise the NavSatFix converts with the origin."""


def vessel_llh(v: VesselPose, origin: GeodeticOrigin | None) -> tuple[float, float, float]:
    """The vessel's WGS-84 position: its ``llh``, else exact NED → LLH about ``origin``."""
    if v.llh is not None:
        return v.llh
    if origin is None:
        raise InputError("NavSatFix", f"vessel {v.name!r}: a geodetic origin (or the pose's llh) is needed")
    lat, lon, alt = ned_to_llh_exact(v.north, v.east, v.down, origin)
    return float(lat), float(lon), float(alt)


def pose_stamped(store: Typestore, t: float, world_frame: str, v: VesselPose) -> Any:
    T = store.types
    return T["geometry_msgs/msg/PoseStamped"](
        header=header(store, t, world_frame),
        pose=T["geometry_msgs/msg/Pose"](
            position=_point(store, (v.north, v.east, v.down)), orientation=_quat(store, quaternion_yaw(v.heading))
        ),
    )


def body_velocity(v: VesselPose) -> tuple[float, float]:
    """(surge, sway): the NED velocity in the body frame (x forward, y starboard)."""
    c, s = math.cos(v.heading), math.sin(v.heading)
    return c * v.v_north + s * v.v_east, -s * v.v_north + c * v.v_east


def odometry(store: Typestore, t: float, world_frame: str, body_frame: str, v: VesselPose) -> Any:
    """``nav_msgs/Odometry``: pose in the world NED frame, twist in the body FRD frame; zero covariances."""
    T = store.types
    zeros = np.zeros(36, dtype=np.float64)
    u, w = body_velocity(v)
    return T["nav_msgs/msg/Odometry"](
        header=header(store, t, world_frame),
        child_frame_id=body_frame,
        pose=T["geometry_msgs/msg/PoseWithCovariance"](
            pose=T["geometry_msgs/msg/Pose"](
                position=_point(store, (v.north, v.east, v.down)), orientation=_quat(store, quaternion_yaw(v.heading))
            ),
            covariance=zeros,
        ),
        twist=T["geometry_msgs/msg/TwistWithCovariance"](
            twist=T["geometry_msgs/msg/Twist"](linear=_vec(store, (u, w, 0.0)), angular=_vec(store, (0.0, 0.0, v.yaw_rate))),
            covariance=zeros.copy(),
        ),
    )


def nav_sat_fix(store: Typestore, t: float, frame_id: str, v: VesselPose, origin: GeodeticOrigin | None) -> Any:
    """``sensor_msgs/NavSatFix`` of the vessel's reference point (:func:`vessel_llh`): ground truth, so its
    covariance is known and zero (``COVARIANCE_TYPE_KNOWN``)."""
    T = store.types
    lat, lon, alt = vessel_llh(v, origin)
    NSS = T["sensor_msgs/msg/NavSatStatus"]
    return T["sensor_msgs/msg/NavSatFix"](
        header=header(store, t, frame_id),
        status=NSS(status=NSS.STATUS_FIX, service=NSS.SERVICE_GPS),
        latitude=float(lat),
        longitude=float(lon),
        altitude=float(alt),
        position_covariance=np.zeros(9, dtype=np.float64),
        position_covariance_type=T["sensor_msgs/msg/NavSatFix"].COVARIANCE_TYPE_KNOWN,
    )
