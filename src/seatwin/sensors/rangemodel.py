"""The range-model interface: per-beam ranges for beams posed in the world.

The lidar pipeline (:mod:`seatwin.sensors.lidar`) poses the beams, draws the ray drop,
and after ranging applies intensity, noise and packing; a *range model* only answers
"how far does each of these beams go, what does it hit, with which surface normal".
Two models:

* ``raycast`` (here): exact ray casting with :mod:`seatwin.engine`; vessels are hit in
  their body frames at each beam's own time (vessels move during a sweep).
* ``depthbuffer``: the thesis's depth-buffer method (4.1), in
  ``seatwin.sensors.depthbuffer``; it must expose ``range_model(scene, batch) -> BeamRanges``
  (``depthbuffer-legacy``: without the filter; ``depthbuffer-plane``: rasterised by OpenGL, each
  beam intersected with its pixel's surface plane).

Register others with :func:`register_range_model`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError
from seatwin.geo.angles import wrap_to_pi
from seatwin.world.scene import Scene


@dataclass(frozen=True)
class BeamBatch:
    """Beams of one sweep to range, in the world frame (NED, z down).

    The beams are those of the sweep's columns × rings that survived the ray drop, in
    azimuth-major order (``beam = column · rings + ring``).
    """

    origins: NDArray[np.float32]
    """(M, 3) sensor position at each beam's firing time."""
    directions: NDArray[np.float32]
    """(M, 3) unit directions."""
    max_range: NDArray[np.float32]
    """(M,) the sensor's maximum range, or less where the beam meets the water first."""
    beam: NDArray[np.intp]
    """(M,) index of each beam in the sweep (azimuth-major)."""
    column: NDArray[np.intp]
    """(M,) column index of each beam."""
    column_times: NDArray[np.float64]
    """(C,) POSIX firing time of each column: a beam's time is ``column_times[column]``."""
    column_origins: NDArray[np.float64]
    """(C, 3) sensor position per column."""
    column_bearing: NDArray[np.float64]
    """(C,) world bearing (rad, clockwise from north) of the middle of each column's beams."""
    column_halfwidth: NDArray[np.float64]
    """(C,) half the horizontal bearing spread of a column's beams (0 for a level sensor)."""
    rings: int
    """Lasers per column."""
    lidar_directions: NDArray[np.float32]
    """(C·rings, 3) every beam of the sweep in the sensor frame (REP-103)."""
    exclude: tuple[str, ...] = ()
    """Vessels the model must not range (the sensor's carrier: the pipeline adds its self-returns)."""

    def __len__(self) -> int:
        return int(self.origins.shape[0])

    @property
    def ring(self) -> NDArray[np.intp]:
        """(M,) ring (laser) index of each beam."""
        return self.beam % self.rings

    @property
    def sensor_directions(self) -> NDArray[np.float32]:
        """(M, 3) the beams in the sensor frame (REP-103)."""
        return self.lidar_directions[self.beam]


@dataclass(frozen=True)
class BeamRanges:
    """Per-beam results: range [m] (inf = nothing within ``max_range``), object id (−1), and the
    hit surface's normal in the world frame (any length, zero on a miss)."""

    range: NDArray[np.float32]
    object_id: NDArray[np.int32]
    normal: NDArray[np.float32]


RangeModel = Callable[[Scene, BeamBatch], BeamRanges]

_MODELS: dict[str, RangeModel] = {}
_LAZY = {
    "depthbuffer": ("seatwin.sensors.depthbuffer", "range_model"),
    "depthbuffer-legacy": ("seatwin.sensors.depthbuffer", "legacy_range_model"),
    "depthbuffer-plane": ("seatwin.sensors.depthbuffer", "plane_range_model"),
}


def register_range_model(name: str, model: RangeModel) -> None:
    """Make ``model`` selectable as ``range_model=name``."""
    _MODELS[name] = model


def range_model_names() -> list[str]:
    return sorted({*_MODELS, *_LAZY})


def get_range_model(name: str) -> RangeModel:
    """The range model called ``name`` (``raycast``, ``depthbuffer`` or a registered one)."""
    if name not in _MODELS and name in _LAZY:
        try:
            module_name, attr = _LAZY[name]
            _MODELS[name] = getattr(importlib.import_module(module_name), attr)
        except (ImportError, AttributeError) as exc:
            raise InputError(None, f"range model {name!r} is not available: {exc}", where="range_model") from exc
    if name not in _MODELS:
        raise InputError(None, f"unknown range model {name!r}; known: {range_model_names()}", where="range_model")
    return _MODELS[name]


def _beams_of_columns(selected: NDArray[np.bool_], column: NDArray[np.intp]) -> NDArray[np.intp]:
    """Indices of the beams whose (sorted) ``column`` is ``selected``: runs of selected
    columns become ranges of beams, found by binary search instead of a per-beam mask."""
    edges = np.flatnonzero(np.diff(np.concatenate(([False], selected, [False])).astype(np.int8)))
    if not edges.size:
        return np.zeros(0, np.intp)
    lo = np.searchsorted(column, edges[::2], "left")
    hi = np.searchsorted(column, edges[1::2], "left")
    if len(lo) == 1:
        return np.arange(lo[0], hi[0])
    return np.concatenate([np.arange(a, b) for a, b in zip(lo, hi)])


def raycast_ranges(scene: Scene, batch: BeamBatch) -> BeamRanges:
    """Exact ranges: static geometry in the world frame, then each vessel in its body frame.

    A vessel is only cast for the columns whose bearing interval meets its bounding circle
    (grown by the sweep's motion), and only up to the range already found, so the nearest
    hit wins and far-away vessels cost almost nothing. Rays go into the vessel's body frame
    with the vessel posed at each column's own time.
    """
    hits = scene.static_caster.cast(batch.origins, batch.directions, batch.max_range)
    rng, oid, nrm = hits.range, hits.object_id, hits.geometric_normal
    if not len(batch):
        return BeamRanges(rng, oid, nrm)
    col_o = batch.column_origins
    reach = float(batch.max_range.max())
    times = batch.column_times
    t0, t1 = float(times.min()), float(times.max())
    sensor_mid = 0.5 * (col_o[0, :2] + col_o[-1, :2])
    sensor_spread = float(np.hypot(col_o[:, 0] - sensor_mid[0], col_o[:, 1] - sensor_mid[1]).max())
    for name in scene.vessel_names:
        if name in batch.exclude:
            continue
        # Coarse cull on the whole sweep: a circle holding the vessel throughout, seen from
        # the middle of the sensor's path, grown by how far the sensor strays from there.
        cn, ce, grow = scene.motion_circle(name, t0, t1)
        mid = np.array([cn - sensor_mid[0], ce - sensor_mid[1]])
        grow += sensor_spread
        dist = float(np.hypot(*mid))
        if dist - grow > reach:
            continue
        half = np.pi if dist <= grow else float(np.arcsin(grow / dist))
        off = np.abs(wrap_to_pi(batch.column_bearing - np.arctan2(mid[1], mid[0])))
        cols = np.flatnonzero(off <= half + batch.column_halfwidth + 1e-6)
        if not cols.size:
            continue
        sel = np.zeros(len(times), bool)
        sel[cols] = True
        idx = _beams_of_columns(sel, batch.column)
        if not idx.size:
            continue
        # Exact: the vessel's pose at each selected column's own time.
        pose = scene.pose(name, times[cols])
        rel_n = pose.north - col_o[cols, 0]
        rel_e = pose.east - col_o[cols, 1]
        ch, sh = np.cos(pose.heading), np.sin(pose.heading)
        # World → body: move to the vessel's origin, rotate by −heading about z (down).
        ob = np.empty((len(cols), 3), np.float32)
        ob[:, 0] = -(ch * rel_n + sh * rel_e)
        ob[:, 1] = sh * rel_n - ch * rel_e
        ob[:, 2] = col_o[cols, 2]
        c = np.searchsorted(cols, batch.column[idx])  # position of each beam's column in ``cols``
        d = batch.directions[idx]
        chc, shc = ch[c].astype(np.float32), sh[c].astype(np.float32)
        db = np.empty_like(d)
        db[:, 0] = chc * d[:, 0] + shc * d[:, 1]
        db[:, 1] = chc * d[:, 1] - shc * d[:, 0]
        db[:, 2] = d[:, 2]
        limit = np.minimum(rng[idx], batch.max_range[idx])
        vh = scene.vessel_caster(name).cast(np.take(ob, c, axis=0), db, limit)
        closer = np.flatnonzero(vh.object_id >= 0)
        if closer.size:
            j = idx[closer]
            rng[j] = vh.range[closer]
            oid[j] = vh.object_id[closer]
            nb = vh.geometric_normal[closer]
            cc, sc = chc[closer], shc[closer]
            nrm[j, 0] = cc * nb[:, 0] - sc * nb[:, 1]
            nrm[j, 1] = sc * nb[:, 0] + cc * nb[:, 1]
            nrm[j, 2] = nb[:, 2]
    return BeamRanges(rng, oid, nrm)


register_range_model("raycast", raycast_ranges)
