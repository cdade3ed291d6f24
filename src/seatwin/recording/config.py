"""Recording configuration: bag formats, topic-name templates and frame ids (all configurable).

Templates use ``{sensor}`` and ``{vessel}``; names are sanitised to valid ROS names
(letters, digits, ``_`` and ``/``; a token never starts with a digit).
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass, fields
from typing import Any, Literal

from seatwin.defaults import COMPRESSIONS, DEFAULT_COMPRESSION, IMAGE_FORMATS, ROS_DISTROS, ImageFormat, RosDistro
from seatwin.errors import InputError, ParameterError

BagFormat = Literal["mcap", "sqlite3", "ros1"]
FORMATS: tuple[str, ...] = ("mcap", "sqlite3", "ros1")


_BAD = re.compile(r"[^A-Za-z0-9_/]")


def ros_name(name: str) -> str:
    """``name`` as a valid ROS graph/frame name: bad characters → ``_``, digit-led tokens → ``_`` prefix."""
    clean = _BAD.sub("_", name.strip())
    tokens = [("_" + t if t[:1].isdigit() else t) for t in clean.split("/")]
    out = "/".join(tokens)
    return out or "_"


@dataclass(frozen=True)
class TopicConfig:
    """Topic templates and frame ids of a recording. Defaults are the ones listed in the README."""

    lidar: str = "/{sensor}/points"
    camera: str = "/{sensor}/image_raw"
    camera_compressed: str = "/{sensor}/image_raw/compressed"
    radar: str = "/{sensor}/detections"
    pose: str = "/ground_truth/{vessel}/pose"
    odom: str = "/ground_truth/{vessel}/odom"
    fix: str = "/ground_truth/{vessel}/fix"
    markers: str = "/ground_truth/markers"
    """Every vessel as a 3-D box and its name (``visualization_msgs/MarkerArray``, RViz and Foxglove)."""
    tf: str = "/tf"
    tf_static: str = "/tf_static"
    world_frame: str = "world_ned"
    """Frame of all ground truth: the scenario's local NED frame (REP-103 ``_ned`` suffix)."""
    display_frame: str | None = "map"
    """The REP-105 ``map`` frame: ENU at the scenario's origin, the root of the tf tree — parent of
    ``world_frame`` and of every vessel's ``odom_frame`` on /tf_static (None: omit both links).
    Recordings before REP-105 frames named it ``world``."""
    odom_frame: str = "{vessel}/odom"
    """A vessel's REP-105 ``odom`` frame (ENU; equal to ``map``: ground truth does not drift)."""
    base_frame: str = "{vessel}/base_link"
    """A vessel's REP-103 body frame (x forward, y left, z up): its pose in ``odom_frame`` on /tf."""
    body_frame: str = "{vessel}/base_link_frd"
    """The thesis's vessel body frame (x forward, y starboard, z down): a fixed child of ``base_frame``;
    odometry, markers and the mounts in the manifest use it."""
    sensor_frame: str = "{vessel}/{sensor}"
    """A sensor's frame on its carrier (``{sensor}`` alone gives the un-namespaced ids of older recordings)."""
    gnss_frame: str = "{vessel}/gnss"
    """The GNSS antenna frame of a vessel (the NavSatFix's ``frame_id``), at its reference point."""

    def topic(self, kind: str, *, sensor: str | None = None, vessel: str | None = None) -> str:
        """The topic name of ``kind`` (a field name) for a sensor or a vessel."""
        template = getattr(self, kind)
        name = template.format(sensor=ros_name(sensor or ""), vessel=ros_name(vessel or ""))
        return "/" + ros_name(name.lstrip("/")) if name.startswith("/") else ros_name(name)

    def body(self, vessel: str) -> str:
        """The vessel's FRD body frame (the thesis's ``base_link_frd``)."""
        return self.frame("body_frame", vessel)

    def frame(self, kind: str, vessel: str, sensor: str = "") -> str:
        """The frame id of ``kind`` (``body_frame``, ``base_frame``, ``odom_frame``, ``gnss_frame``, ``sensor_frame``)."""
        return ros_name(getattr(self, kind).format(vessel=ros_name(vessel), sensor=ros_name(sensor)))

    def sensor(self, vessel: str | None, sensor: str) -> str:
        """A sensor's frame id: ``{vessel}/{sensor}`` by default; the bare name for a sensor without a carrier."""
        return ros_name(sensor) if vessel is None else self.frame("sensor_frame", vessel, sensor)

    def vessel_from_topic(self, kind: str, topic: str) -> str | None:
        """Invert a ``{vessel}`` template: the vessel name in ``topic``, or None when it does not match."""
        template = getattr(self, kind)
        if "{vessel}" not in template:
            return None
        head, tail = template.split("{vessel}", 1)
        m = re.fullmatch(re.escape(head) + r"(.+?)" + re.escape(tail), topic)
        return m.group(1) if m else None

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any] | None, source: str = "topics") -> TopicConfig:
        """Build from a mapping (e.g. a YAML ``topics:`` section); unknown keys are an :class:`InputError`."""
        data = dict(data or {})
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(data) - known)
        if unknown:
            raise InputError(source, f"unknown topic setting(s) {unknown}; expected some of {sorted(known)}")
        for key, value in data.items():
            if not (isinstance(value, str) or (key == "display_frame" and value is None)):
                raise InputError(source, f"expected a string, got {value!r}", where=key)
        return cls(**data)


def check_ros_distro(name: str, param: str = "ros_distro") -> RosDistro:
    """Validate a ROS 2 distribution name (a :class:`ParameterError` naming ``param`` otherwise)."""
    if name not in ROS_DISTROS:
        raise ParameterError(param, f"unknown ROS 2 distribution {name!r}; expected one of {', '.join(ROS_DISTROS)}")
    return name  # type: ignore[return-value]


def check_format(fmt: str, param: str = "fmt") -> BagFormat:
    """Validate a bag format name (a :class:`ParameterError` naming ``param`` otherwise)."""
    if fmt not in FORMATS:
        raise ParameterError(param, f"unknown bag format {fmt!r}; expected one of {', '.join(FORMATS)}")
    return fmt  # type: ignore[return-value]


def check_compression(fmt: str, compression: str | None, param: str = "compression") -> str:
    """The compression of a ``fmt`` bag: ``compression`` if that format has it (a :class:`ParameterError` naming
    ``param`` otherwise), None → the format's default (:data:`~seatwin.defaults.DEFAULT_COMPRESSION`)."""
    if compression is None:
        return DEFAULT_COMPRESSION[fmt]
    names = COMPRESSIONS[fmt]
    if compression not in names:
        raise ParameterError(param, f"{compression!r} is not a compression of {fmt} bags; expected one of {', '.join(names)}")
    return compression


def check_image_format(name: str, param: str = "image_format") -> ImageFormat:
    """Validate a camera image format (raw, jpeg, png; a :class:`ParameterError` naming ``param`` otherwise)."""
    if name not in IMAGE_FORMATS:
        raise ParameterError(param, f"unknown image format {name!r}; expected one of {', '.join(IMAGE_FORMATS)}")
    return name  # type: ignore[return-value]
