"""Mesh building blocks in a NED-style frame (x north/forward, y east/starboard, z down).

Heights are given above the calm water surface and stored as ``z = -height``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import trimesh


def block(x_min: float, x_max: float, y_min: float, y_max: float, top: float, base: float = 0.0) -> trimesh.Trimesh:
    """An axis-aligned box from height ``base`` up to height ``top`` (metres above the water)."""
    if not (x_max > x_min and y_max > y_min and top > base):
        raise ValueError(f"empty block: x {x_min}..{x_max}, y {y_min}..{y_max}, height {base}..{top}")
    box = trimesh.creation.box(extents=[x_max - x_min, y_max - y_min, top - base])
    box.apply_translation([(x_min + x_max) / 2, (y_min + y_max) / 2, -(top + base) / 2])
    return box


def blocks(extents: np.ndarray, top: float, base: float = 0.0) -> trimesh.Trimesh:
    """Many axis-aligned boxes at once, rows of ``extents`` = (x_min, x_max, y_min, y_max), all from height
    ``base`` to ``top``: the same triangles as :func:`merge` of one :func:`block` each, built without a
    mesh per box."""
    ext = np.asarray(extents, float).reshape(-1, 4)
    if not len(ext) or not ((ext[:, 1] > ext[:, 0]).all() and (ext[:, 3] > ext[:, 2]).all() and top > base):
        raise ValueError(f"empty blocks: {len(ext)} extents, height {base}..{top}")
    unit = trimesh.creation.box(extents=[1.0, 1.0, 1.0])  # vertices at ±½, outward winding
    v0, f0 = np.asarray(unit.vertices), np.asarray(unit.faces)
    size = np.c_[ext[:, 1] - ext[:, 0], ext[:, 3] - ext[:, 2], np.full(len(ext), top - base)]
    mid = np.c_[(ext[:, 0] + ext[:, 1]) / 2, (ext[:, 2] + ext[:, 3]) / 2, np.full(len(ext), -(top + base) / 2)]
    verts = v0[None, :, :] * size[:, None, :] + mid[:, None, :]
    faces = f0[None, :, :] + (len(v0) * np.arange(len(ext)))[:, None, None]
    return trimesh.Trimesh(verts.reshape(-1, 3), faces.reshape(-1, 3), process=False)


def prism(outline: Sequence[tuple[float, float]], top: float, base: float = 0.0) -> trimesh.Trimesh:
    """The convex hull of a horizontal ``outline`` (x, y) extruded from ``base`` to ``top``."""
    xy = np.asarray(outline, dtype=float)
    pts = np.vstack([np.c_[xy, np.full(len(xy), -top)], np.c_[xy, np.full(len(xy), -base)]])
    return trimesh.convex.convex_hull(pts)


def hull(
    length: float,
    beam: float,
    freeboard: float,
    draft: float = 0.5,
    bow: float = 0.3,
    stern: float = 0.05,
    sheer: float = 0.0,
) -> trimesh.Trimesh:
    """A convex boat hull centred on the origin: deck outline at ``freeboard`` above the water,
    a narrower keel outline ``draft`` below it.

    ``bow``/``stern``: fraction of the length over which the outline tapers at each end
    (0 = square transom, 0.5 = pointed); ``sheer``: extra height of the bow deck edge.
    """
    h_len, h_beam = length / 2, beam / 2

    def outline(scale: float, taper_tip: float) -> list[tuple[float, float]]:
        xs_b = h_len - bow * length
        xs_s = -h_len + stern * length
        pts = [(xs_s, -h_beam * scale), (xs_s, h_beam * scale), (xs_b, -h_beam * scale), (xs_b, h_beam * scale)]
        pts += [(h_len * scale**0.2, -h_beam * taper_tip), (h_len * scale**0.2, h_beam * taper_tip)]
        pts += [(-h_len * scale**0.2, -h_beam * scale * (1 - stern)), (-h_len * scale**0.2, h_beam * scale * (1 - stern))]
        return pts

    deck = outline(1.0, 0.25 if bow > 0.05 else 1.0)
    keel = outline(0.45, 0.05 if bow > 0.05 else 0.45)
    top = [(x, y, -(freeboard + sheer * max(0.0, x / h_len))) for x, y in deck]
    bottom = [(x, y, draft) for x, y in keel]
    return trimesh.convex.convex_hull(np.asarray(top + bottom, dtype=float))


def merge(parts: Sequence[trimesh.Trimesh]) -> trimesh.Trimesh:
    """One mesh of all ``parts``."""
    return trimesh.util.concatenate(list(parts))
