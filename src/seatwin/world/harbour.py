"""Static harbour geometry (3-D): from a :class:`~seatwin.layout.HarbourLayout` or a :class:`~seatwin.layout.LandRaster`.

Water is the plane z = 0 and is *not* a mesh: a ray that reaches it returns nothing (calm
water reflects the laser away), which the sensors model by cutting rays at the surface.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import trimesh

from seatwin.errors import InputError
from seatwin.geo.frames import yaw_matrix
from seatwin.layout import DEFAULT_LAYOUT, HarbourLayout, LandRaster, MooredBoat, harbour_map
from seatwin.world.objects import WorldObject
from seatwin.world.shapes import block, blocks, merge
from seatwin.world.vessels import REFLECTIVITY, generic

QUAY_BASE = -2.0
"""Quays and land reach this far below the water (hidden; keeps the quay faces closed)."""


def harbour_from_layout(layout: HarbourLayout = DEFAULT_LAYOUT) -> list[WorldObject]:
    """Quays on both sides of the channel, piers, buildings and moored boats of ``layout``."""
    w, d = layout.half_width, layout.land_depth
    n0, n1 = layout.north_min, layout.north_max
    objs = [
        WorldObject("quay_west", "quay", block(n0, n1, -w - d, -w, layout.quay_height, QUAY_BASE), REFLECTIVITY["quay"]),
        WorldObject("quay_east", "quay", block(n0, n1, w, w + d, layout.quay_height, QUAY_BASE), REFLECTIVITY["quay"]),
    ]
    for p in layout.piers:
        objs.append(
            WorldObject(
                p.name, "pier", block(p.north_min, p.north_max, p.east_min, p.east_max, p.top, p.base), REFLECTIVITY["pier"]
            )
        )
    for b in layout.buildings:
        # Buildings stand on the quay: start them at its top so no face hides inside it.
        base = max(b.base, 0.0)
        objs.append(
            WorldObject(
                b.name, "building", block(b.north_min, b.north_max, b.east_min, b.east_max, b.top, base), REFLECTIVITY["building"]
            )
        )
    return objs + moored_objects(layout.moored_boats)


def moored_objects(boats: Sequence[MooredBoat]) -> list[WorldObject]:
    """Each moored boat as a generic hull of its size, posed in the world."""
    objs = []
    for m in boats:
        boat = generic(m.length, m.beam, m.height, name=m.name).mesh.copy()
        boat.vertices = boat.vertices @ yaw_matrix(np.radians(m.heading_deg)).T + [m.north, m.east, 0.0]
        objs.append(WorldObject(m.name, "moored_boat", boat, REFLECTIVITY["moored_boat"]))
    return objs


def merge_cells(mask: np.ndarray) -> list[tuple[int, int, int, int]]:
    """Cover the True cells of ``mask`` with rectangles ``(r0, r1, c0, c1)`` (end-exclusive).

    Each row is cut into runs; a run identical to one in the row before extends that
    rectangle. Exact cover, far fewer pieces than cells.
    """
    open_rects: dict[tuple[int, int], int] = {}  # (c0, c1) -> start row
    out: list[tuple[int, int, int, int]] = []
    rows, cols = mask.shape
    padded = np.zeros(cols + 2, dtype=np.int8)
    for r in range(rows + 1):
        runs: set[tuple[int, int]] = set()
        if r < rows:
            padded[1:-1] = mask[r]
            edges = np.flatnonzero(np.diff(padded))
            runs = {(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])}
        for key in [k for k in open_rects if k not in runs]:
            out.append((open_rects.pop(key), r, key[0], key[1]))
        for key in runs:
            open_rects.setdefault(key, r)
    return out


def _boxes(raster: LandRaster, mask: np.ndarray, top: float, base: float) -> trimesh.Trimesh | None:
    rects = merge_cells(mask)
    if not rects:
        return None
    res = raster.resolution
    r = np.asarray(rects, float)
    extents = np.c_[raster.origin_north + r[:, :2] * res, raster.origin_east + r[:, 2:] * res]
    return blocks(extents, top, base)


@dataclass(frozen=True)
class Skyline:
    """Buildings along a raster harbour's shore (made up: the raster knows only land and water).

    Land whose distance to the water is ``setback_m`` … ``setback_m + depth_m`` is cut by a grid of
    streets (``street_m`` wide, every ``block_m``) into blocks; each block rises from the quay top to a
    height drawn from ``heights_m`` by a hash of its grid cell (the same raster gives the same
    skyline). Defaults: 3–5-storey wharf buildings, 7–16 m, one row deep behind an 8 m quay apron
    (typical of Trondheim's harbour front; no data on the real ones).
    """

    setback_m: float = 8.0
    depth_m: float = 30.0
    block_m: float = 24.0
    street_m: float = 4.0
    heights_m: tuple[float, ...] = (7.0, 9.0, 10.0, 12.0, 13.0, 16.0)

    def mask_by_height(self, land: np.ndarray, resolution: float) -> dict[float, np.ndarray]:
        """Height → the land cells of the blocks of that height."""
        from scipy.ndimage import distance_transform_edt

        inland = (distance_transform_edt(land) - 1.0) * resolution  # from the water's edge to the cell's near side
        band = land & (inland >= self.setback_m - 1e-9) & (inland < self.setback_m + self.depth_m)
        rows, cols = np.indices(land.shape)
        b = max(int(round(self.block_m / resolution)), 1)
        street = max(int(round(self.street_m / resolution)), 0)
        band &= (rows % b >= street) & (cols % b >= street)
        key = ((rows // b) * 73856093) ^ ((cols // b) * 19349663)
        pick = np.asarray(self.heights_m)[key % len(self.heights_m)]
        return {float(h): band & (pick == h) for h in sorted(set(self.heights_m)) if (band & (pick == h)).any()}


SHORE_SKYLINE = Skyline()
"""The skyline a raster harbour gets by default (:func:`build_harbour`)."""


def harbour_from_raster(
    raster: LandRaster,
    quay_height: float = DEFAULT_LAYOUT.quay_height,
    building_setback: float | None = None,
    building_height: float = 10.0,
    skyline: Skyline | None = None,
) -> list[WorldObject]:
    """Land cells extruded to ``quay_height`` (their faces at the water are the quay walls); with
    ``building_setback``, land at least that far from the water is raised further to ``building_height``
    (a crude city block); with ``skyline``, blocks of buildings along the shore (:class:`Skyline`). The
    blocks are built in the raster's frame and placed in the scenario frame by its alignment; the
    raster's moored boats are added."""
    land = ~raster.water
    objs: list[WorldObject] = []
    quay = _boxes(raster, land, quay_height, QUAY_BASE)
    if quay is not None:
        objs.append(WorldObject("land", "quay", quay, REFLECTIVITY["quay"]))
    if building_setback is not None:
        from scipy.ndimage import distance_transform_edt

        dist = distance_transform_edt(land) * raster.resolution
        blocks = _boxes(raster, land & (dist >= building_setback), building_height, quay_height)
        if blocks is not None:
            objs.append(WorldObject("buildings", "building", blocks, REFLECTIVITY["building"]))
    if skyline is not None:
        parts = [_boxes(raster, mask, h, quay_height) for h, mask in skyline.mask_by_height(land, raster.resolution).items()]
        meshes = [m for m in parts if m is not None]
        if meshes:
            objs.append(WorldObject("shore_buildings", "building", merge(meshes), REFLECTIVITY["building"]))
    if not raster.alignment.is_identity:
        rot, offset = raster.alignment.from_map_matrix()
        for o in objs:
            o.mesh.vertices = np.asarray(o.mesh.vertices) @ rot.T + offset
    return objs + moored_objects(raster.moored())


def build_harbour(spec: object = "default") -> list[WorldObject]:
    """Harbour objects for a scenario's ``environment['harbour']``: ``"default"``, ``"ravnkloa"``,
    ``"none"``, a :class:`HarbourLayout`, a :class:`LandRaster`, or a raster path (``.bin``/``.yaml``)
    (:func:`seatwin.layout.harbour_map`); a raster gets the :data:`SHORE_SKYLINE`."""
    try:
        m = harbour_map(spec)
    except InputError as exc:
        raise InputError(exc.source, exc.detail, where=exc.where or "environment.harbour") from exc
    if m is None:
        return []
    return harbour_from_layout(m) if isinstance(m, HarbourLayout) else harbour_from_raster(m, skyline=SHORE_SKYLINE)
