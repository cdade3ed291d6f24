"""The tf tree of a recording (REP-103/105): which frames exist, how they hang together, composing them.

Every recording since REP-105 frames has one tree (``TopicConfig`` names every frame)::

    map                                   ENU at the scenario's origin (REP-105), root
    ├── world_ned                         the thesis's NED world frame (ground truth's frame)  /tf_static
    └── {vessel}/odom                     = map (ground truth does not drift)                   /tf_static
        └── {vessel}/base_link            FLU body (REP-103), its pose at every step             /tf
            ├── {vessel}/base_link_frd    the thesis's FRD body: a half turn about x             /tf_static
            ├── {vessel}/gnss             the GNSS antenna (NavSatFix), at the reference point   /tf_static
            ├── {vessel}/lidar_upright    the lidar as if mounted upright (z up), yawed/pitched  /tf_static
            │   └── {vessel}/lidar        the VLP-16, rolled 180° (upside down: z points down)  /tf_static
            ├── {vessel}/radar            FLU at the antenna                                     /tf_static
            └── {vessel}/camera_<name>_optical_frame                                            /tf_static

:class:`TfTree` composes transforms (``v_parent = R @ v_child + t``); :func:`body_mounts` gives every
sensor frame's pose in its vessel's FRD body frame — what perception poses sensors with — from the
transforms of any recording: the chain above, or older recordings' sensors directly on
``{vessel}/base_link_frd``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.geo.frames import FLU_TO_FRD, quaternion_matrix
from seatwin.recording.config import TopicConfig
from seatwin.recording.messages import StaticTransform, VesselPose, quaternion_from_matrix, quaternion_yaw

Array = NDArray[np.float64]

FLU_FRD_ROTATION = (1.0, 0.0, 0.0, 0.0)
"""Quaternion (x, y, z, w) of a FRD frame in the FLU frame with the same origin and x: a half turn about x."""


@dataclass(frozen=True)
class Transform:
    """A rigid transform: ``v_parent = rotation @ v_child + translation``."""

    rotation: Array
    translation: Array

    @classmethod
    def from_quaternion(cls, translation: ArrayLike, q: ArrayLike) -> Transform:
        return cls(quaternion_matrix(q), np.asarray(translation, float).reshape(3))

    @classmethod
    def identity(cls) -> Transform:
        return cls(np.eye(3), np.zeros(3))

    def __matmul__(self, other: Transform) -> Transform:
        """``self ∘ other``: first ``other`` (child → middle), then ``self`` (middle → parent)."""
        return Transform(self.rotation @ other.rotation, self.rotation @ other.translation + self.translation)

    def inverse(self) -> Transform:
        rt = self.rotation.T
        return Transform(rt, -rt @ self.translation)

    def apply(self, points: ArrayLike) -> Array:
        """(…, 3) child-frame points → the parent frame."""
        return np.asarray(points, float) @ self.rotation.T + self.translation


class TfTree:
    """Frames joined by transforms, each frame with one parent (a later transform of a child replaces the
    earlier one, as tf2 keeps the latest)."""

    def __init__(self, transforms: Iterable[StaticTransform] = ()) -> None:
        self.parents: dict[str, tuple[str, Transform]] = {}
        self.add_all(transforms)

    def add(self, parent: str, child: str, translation: Sequence[float], rotation: Sequence[float]) -> None:
        self.parents[child] = (parent, Transform.from_quaternion(translation, rotation))

    def add_all(self, transforms: Iterable[StaticTransform]) -> None:
        for s in transforms:
            self.add(s.parent, s.child, s.translation, s.rotation)

    def chain(self, frame: str) -> list[str]:
        """``frame`` and its ancestors up to the root, in that order."""
        out = [frame]
        while out[-1] in self.parents:
            out.append(self.parents[out[-1]][0])
            if len(out) > len(self.parents) + 1:
                raise InputError("tf", f"the transforms above frame {frame!r} form a loop: {' → '.join(out)}")
        return out

    def to_ancestor(self, frame: str, ancestor: str) -> Transform:
        """``frame`` → ``ancestor`` (which must be on ``frame``'s chain)."""
        out = Transform.identity()
        f = frame
        while f != ancestor:
            if f not in self.parents:
                raise InputError("tf", f"frame {ancestor!r} is not above frame {frame!r}")
            parent, tr = self.parents[f]
            out = tr @ out
            f = parent
        return out

    def lookup(self, target: str, source: str) -> Transform:
        """The transform taking ``source`` coordinates to ``target`` coordinates (through their common ancestor)."""
        up_source, up_target = self.chain(source), self.chain(target)
        common = next((f for f in up_source if f in set(up_target)), None)
        if common is None:
            raise InputError("tf", f"no transform between frames {source!r} and {target!r} (they are in different trees)")
        return self.to_ancestor(target, common).inverse() @ self.to_ancestor(source, common)


def base_link_pose(v: VesselPose) -> tuple[tuple[float, float, float], tuple[float, float, float, float]]:
    """(translation, quaternion) of a vessel's FLU ``base_link`` in its ENU ``odom`` frame: (east, north, up),
    a turn by π/2 − heading about z (up)."""
    return (v.east, v.north, -v.down), quaternion_yaw(math.pi / 2 - v.heading)


def vessel_transforms(topics: TopicConfig, vessel: str, gnss: bool = False) -> list[StaticTransform]:
    """A vessel's fixed frames: ``map`` → ``odom`` (identity; none without ``display_frame``), ``base_link`` →
    ``base_link_frd`` and, with ``gnss``, ``base_link`` → ``gnss`` (the NavSatFix's antenna, at the
    reference point whose position the fix gives)."""
    base = topics.frame("base_frame", vessel)
    out = []
    if topics.display_frame:
        out.append(StaticTransform(topics.display_frame, topics.frame("odom_frame", vessel), (0.0, 0.0, 0.0)))
    out.append(StaticTransform(base, topics.body(vessel), (0.0, 0.0, 0.0), FLU_FRD_ROTATION))
    if gnss:
        out.append(StaticTransform(base, topics.frame("gnss_frame", vessel), (0.0, 0.0, 0.0)))
    return out


def sensor_mount(
    topics: TopicConfig,
    vessel: str,
    sensor_frame: str,
    translation_frd: Sequence[float],
    rotation_frd: ArrayLike,
    roll: float = 0.0,
) -> list[StaticTransform]:
    """A sensor's mount on ``{vessel}/base_link`` (FLU) from its pose in the FRD body frame
    (``v_body = rotation_frd @ v_sensor + translation_frd``).

    With ``roll`` ≠ 0 (the sensor rolled about its own x axis after its yaw and pitch, as
    :func:`seatwin.geo.mount_matrix` composes them) the tree says so: ``{sensor}_upright`` is the mount
    without the roll, and the sensor frame hangs below it turned by ``roll`` about x — the VLP-16's
    180° (upside down) is then visible in the tree, not only in a quaternion.
    """
    base = topics.frame("base_frame", vessel)
    t_flu = tuple(float(x) for x in FLU_TO_FRD @ np.asarray(translation_frd, float))
    r_flu = FLU_TO_FRD @ np.asarray(rotation_frd, float)
    if not roll:
        return [StaticTransform(base, sensor_frame, t_flu, quaternion_from_matrix(r_flu))]  # type: ignore[arg-type]
    c, s = math.cos(roll), math.sin(roll)
    r_roll = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    upright = f"{sensor_frame}_upright"
    return [
        StaticTransform(base, upright, t_flu, quaternion_from_matrix(r_flu @ r_roll.T)),  # type: ignore[arg-type]
        StaticTransform(upright, sensor_frame, (0.0, 0.0, 0.0), (math.sin(roll / 2), 0.0, 0.0, math.cos(roll / 2))),
    ]


def body_mounts(transforms: Iterable[StaticTransform]) -> dict[str, Transform]:
    """Every frame's pose in its vessel's FRD body frame, from a recording's /tf_static.

    A frame's chain is walked up to the first FRD body (a frame named ``…_frd``) or REP-103 body
    (``…base_link``, turned into FRD); a frame with neither above it keeps its own transform (older
    and foreign recordings: the parent taken as the body frame, as perception always did).
    """
    tree = TfTree(transforms)
    out: dict[str, Transform] = {}
    for frame, (_, direct) in tree.parents.items():
        mount = direct
        for above in tree.chain(frame)[1:]:
            if above.endswith("_frd"):
                mount = tree.to_ancestor(frame, above)
                break
            if above.endswith("base_link"):
                mount = Transform(FLU_TO_FRD, np.zeros(3)) @ tree.to_ancestor(frame, above)
                break
        out[frame] = mount
    return out
