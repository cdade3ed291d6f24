"""Ground-truth 2-D boxes of the vessels in a camera image (auto-labels).

A vessel's box is the extent of its 3-D model's vertices, posed at the image's time exactly as
the renderer and the lidar pose it, projected through the camera (pinhole plus the plumb-bob
distortion of the image), then clipped to the image. Alongside:

* ``truncation`` = 1 − (clipped box area) / (full box area): how much of the box lies outside
  the image;
* ``visible_fraction`` = (pixels of the vessel in the rendered object-id image) / (pixels it
  covers in the image when drawn alone): how much of it the other objects leave in sight;
* ``instance`` = the vessel's name (the instance id across images).

Boxes use continuous pixel coordinates (OpenCV convention: the image spans [−½, W − ½] ×
[−½, H − ½]).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.geo import yaw_matrix
from seatwin.sensors.camera.intrinsics import project


@dataclass(frozen=True)
class BoxLabel:
    """One vessel's ground-truth box in one image (pixels)."""

    instance: str
    label: str
    object_id: int
    x_min: float
    y_min: float
    x_max: float
    y_max: float
    truncation: float
    visible_fraction: float
    visible_pixels: int
    distance_m: float

    @property
    def center(self) -> tuple[float, float]:
        return 0.5 * (self.x_min + self.x_max), 0.5 * (self.y_min + self.y_max)

    @property
    def size(self) -> tuple[float, float]:
        return self.x_max - self.x_min, self.y_max - self.y_min

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


def clip_segments(a: NDArray[np.float64], b: NDArray[np.float64], f_a: NDArray, f_b: NDArray) -> tuple[NDArray, NDArray]:
    """Segments a–b cut to the half-space f ≤ 0 (f linear along a segment, given at its ends)."""
    keep = (f_a <= 0) | (f_b <= 0)
    a, b, f_a, f_b = a[keep], b[keep], f_a[keep], f_b[keep]
    s_a = np.where(f_a > 0, f_a / np.where(f_a > 0, f_a - f_b, 1.0), 0.0)[:, None]
    s_b = np.where(f_b > 0, f_b / np.where(f_b > 0, f_b - f_a, 1.0), 0.0)[:, None]
    return a + s_a * (b - a), b + s_b * (a - b)


def waterline_segments(vertices: NDArray[np.float64], faces: NDArray[np.int64]) -> tuple[NDArray, NDArray]:
    """Where faces cross the waterline z = 0: one segment per crossing face (the cut's new edge)."""
    tri = vertices[faces]  # (F, 3, 3)
    a, b = tri, np.roll(tri, -1, axis=1)
    za, zb = a[..., 2], b[..., 2]
    cross = (za > 0) != (zb > 0)
    two = cross.sum(axis=1) == 2
    s = np.where(cross, za / np.where(cross, za - zb, 1.0), 0.0)
    hits = a + s[..., None] * (b - a)
    hits, cross = hits[two], cross[two]
    order = np.argsort(~cross, axis=1, kind="stable")[:, :2]
    rows = np.arange(len(hits))[:, None]
    pair = hits[rows, order]
    return pair[:, 0], pair[:, 1]


def vessel_box(
    vertices_world: ArrayLike,
    edges: ArrayLike,
    rotation: ArrayLike,
    position: ArrayLike,
    k: ArrayLike,
    d: tuple[float, ...] | None,
    width: int,
    height: int,
    near: float = 0.08,
    faces: ArrayLike | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """(full box, box in the image) of a posed mesh's edges (x_min, y_min, x_max, y_max) seen by a camera
    (optical → world ``rotation``, centre ``position``); None when nothing of it is in front.

    The edges are cut at the waterline (the sea hides what is below; with ``faces``, the cut's new
    edges along the waterline are added) and at the near plane, then
    projected; the box in the image is the extent of the edges cut to the image rectangle (exact
    unless a face covers an image corner).
    """
    v = np.asarray(vertices_world, float)
    e = np.asarray(edges, np.int64)
    a, b = clip_segments(v[e[:, 0]], v[e[:, 1]], v[e[:, 0], 2], v[e[:, 1], 2])
    if faces is not None:
        wa, wb = waterline_segments(v, np.asarray(faces, np.int64))
        a, b = np.concatenate([a, wa]), np.concatenate([b, wb])
    r = np.asarray(rotation, float)
    c = np.asarray(position, float)
    a, b = (a - c) @ r, (b - c) @ r  # world → optical: Rᵀ (x − c)
    a, b = clip_segments(a, b, near - a[:, 2], near - b[:, 2])
    if not len(a):
        return None
    ua, ub = project(a, k, d), project(b, k, d)
    pts = np.concatenate([ua, ub])
    full = np.array([pts[:, 0].min(), pts[:, 1].min(), pts[:, 0].max(), pts[:, 1].max()])
    lo, hi = (-0.5, -0.5), (width - 0.5, height - 0.5)
    for axis in (0, 1):
        ua, ub = clip_segments(ua, ub, lo[axis] - ua[:, axis], lo[axis] - ub[:, axis])
        ua, ub = clip_segments(ua, ub, ua[:, axis] - hi[axis], ub[:, axis] - hi[axis])
    if not len(ua):
        return full, np.array([0.0, 0.0, 0.0, 0.0])
    pts = np.concatenate([ua, ub])
    return full, np.array([pts[:, 0].min(), pts[:, 1].min(), pts[:, 0].max(), pts[:, 1].max()])


def truncation(full: ArrayLike, inside: ArrayLike) -> float:
    """1 − (area of the box in the image) / (area of the full box)."""
    f, i = np.asarray(full, float), np.asarray(inside, float)
    area_f = max(f[2] - f[0], 0.0) * max(f[3] - f[1], 0.0)
    area_i = max(i[2] - i[0], 0.0) * max(i[3] - i[1], 0.0)
    return float(min(max(1.0 - area_i / area_f, 0.0), 1.0)) if area_f > 0 else 1.0


def ground_truth_boxes(
    scene: Any,
    t: float,
    rotation: ArrayLike,
    position: ArrayLike,
    k: ArrayLike,
    d: tuple[float, ...] | None,
    width: int,
    height: int,
    ids: NDArray[np.int32],
    unoccluded: Mapping[str, int],
    *,
    exclude: tuple[str, ...] = (),
    near: float = 0.08,
    min_visible_pixels: int = 1,
) -> list[BoxLabel]:
    """Every vessel of ``scene`` in view at ``t`` (but ``exclude``), moving or moored (the harbour's
    :attr:`~seatwin.world.scene.Scene.moored_boats`), as a :class:`BoxLabel` (label ``vessel``).

    ``ids``: the camera's pinhole object-id image (−1 background); ``unoccluded``: each vessel's
    pixel count drawn alone (:attr:`seatwin.render.RenderedFrame.unoccluded`).
    """
    counts = np.bincount(ids.reshape(-1) + 1, minlength=len(scene.objects) + 1)
    c = np.asarray(position, float)
    out = []
    for name, oid, mesh, verts, ref in _posed_vessels(scene, t, exclude):
        boxes = vessel_box(verts, mesh.edges_unique, rotation, c, k, d, width, height, near, faces=mesh.faces)
        if boxes is None:
            continue
        full, clipped = boxes
        trunc = truncation(full, clipped)
        if clipped[2] <= clipped[0] or clipped[3] <= clipped[1]:
            continue
        vis = int(counts[oid + 1])
        if vis < min_visible_pixels:
            continue
        alone = int(unoccluded.get(name, 0))
        frac = min(vis / alone, 1.0) if alone > 0 else 0.0
        dist = float(np.hypot(ref[0] - c[0], ref[1] - c[1]))
        out.append(
            BoxLabel(name, "vessel", oid, *(float(x) for x in clipped), float(trunc), float(frac), vis, dist)  # type: ignore[arg-type]
        )
    return out


def _posed_vessels(scene: Any, t: float, exclude: tuple[str, ...]) -> list[tuple[str, int, Any, NDArray[np.float64], Any]]:
    """(name, object id, mesh, world-frame vertices, (north, east) of its reference point) of every vessel at ``t``
    (but ``exclude``; none outside its trajectory), then of every moored boat (its mesh is already in the world
    frame; its reference point the middle of its extent)."""
    out = []
    for name in scene.vessel_names:
        if name in exclude:
            continue
        try:
            pose = scene.pose(name, t)
        except InputError:
            continue
        mesh = scene.vessel_models[name].mesh
        rot = yaw_matrix(float(pose.heading))
        verts = np.asarray(mesh.vertices, float) @ rot.T + [float(pose.north), float(pose.east), 0.0]
        out.append((name, scene.vessel_ids[name], mesh, verts, (float(pose.north), float(pose.east))))
    for name, oid in getattr(scene, "moored_boats", {}).items():
        if name not in exclude:
            mesh = scene.static_objects[oid].mesh
            v = np.asarray(mesh.vertices, float)
            mid = 0.5 * (v.min(axis=0) + v.max(axis=0))
            out.append((name, oid, mesh, v, (float(mid[0]), float(mid[1]))))
    return out
