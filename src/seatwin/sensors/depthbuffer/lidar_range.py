"""The ``depthbuffer`` range model for :mod:`seatwin.sensors.lidar` (``range_model(scene, batch)``).

For each beam of a :class:`~seatwin.sensors.rangemodel.BeamBatch` the filter (or the legacy
grid) picks a pixel; the ray through that pixel's centre is ranged with the ``raycast``
model's own machinery (static geometry in the world, vessels in their body frames at each
column's time), and the hit is quantised and back-projected as a depth buffer stores it
(:class:`~seatwin.sensors.depthbuffer.model.DepthBufferLidar`).

The batch gives each beam's direction in the sensor and in the world frame, but not the
sensor's rotation, which the pixel ray needs; it is recovered per column by a least-squares
fit (TRIAD) of two of the column's beams (all beams of a column share one pose). A column left
with a single beam after the ray drop borrows the nearest fitted column's rotation,
corrected by the smallest rotation that maps that beam exactly.

The returned :class:`DepthBufferRanges` is a :class:`BeamRanges` (range = distance of the
back-projected point) that also carries ``sensor_points``, the back-projected points: the
lidar pipeline places points along the beam at ``range``, which keeps the depth error but
not the pixel's direction error; using ``sensor_points`` keeps both.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.sensors.depthbuffer.filter import AzimuthGrid, sensor_angles
from seatwin.sensors.depthbuffer.model import DepthBufferConfig, DepthBufferLidar
from seatwin.sensors.lidar_physics import water_limit
from seatwin.sensors.rangemodel import BeamBatch, BeamRanges, RangeModel, raycast_ranges
from seatwin.world.scene import Scene


@dataclass(frozen=True)
class DepthBufferRanges(BeamRanges):
    """:class:`BeamRanges` plus the back-projected points (sensor frame, NaN = no return)."""

    sensor_points: NDArray[np.float32] | None = None


def _smallest_rotation(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """(N, 3, 3) rotations taking unit vectors ``a`` to ``b`` about ``a × b`` (Rodrigues)."""
    v = np.cross(a, b)
    c = np.einsum("ij,ij->i", a, b)
    k = np.zeros((len(a), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -v[:, 2], v[:, 1], -v[:, 0]
    k -= np.transpose(k, (0, 2, 1))
    f = np.where(c > -1 + 1e-12, 1.0 / (1.0 + c), 0.0)
    return np.eye(3) + k + np.einsum("nij,njk->nik", k, k) * f[:, None, None]


def _triad(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """(N, 3, 3) orthonormal frames with columns ``a``, ``a × b``, ``a × (a × b)`` (normalised)."""
    t2 = np.cross(a, b)
    t2 /= np.linalg.norm(t2, axis=1, keepdims=True)
    return np.stack([a, t2, np.cross(a, t2)], axis=2)


def column_rotations(batch: BeamBatch) -> NDArray[np.float64]:
    """Sensor → world rotation of every beam (M, 3, 3), fitted per column (see module doc).

    Per column the two beams with the most different directions (its first and last, the
    batch being azimuth-major) give the rotation exactly (TRIAD); a column with one beam
    borrows its nearest fitted neighbour's rotation, turned to map that beam exactly.
    """
    cols, first, inv = np.unique(batch.column, return_index=True, return_inverse=True)
    last = np.append(first[1:], len(batch)) - 1

    def unit(v: NDArray[np.float32]) -> NDArray[np.float64]:
        w = v.astype(np.float64)
        return w / np.linalg.norm(w, axis=1, keepdims=True)

    sd = batch.sensor_directions
    s_f, s_l = unit(sd[first]), unit(sd[last])
    d_f, d_l = unit(batch.directions[first]), unit(batch.directions[last])
    good = np.linalg.norm(np.cross(s_f, s_l), axis=1) > 1e-6
    rot = np.tile(np.eye(3), (len(cols), 1, 1))
    if good.any():
        g = np.flatnonzero(good)
        rot[g] = np.einsum("nij,nkj->nik", _triad(d_f[g], d_l[g]), _triad(s_f[g], s_l[g]))
        if not good.all():
            pos = np.searchsorted(cols[g], cols[~good]).clip(1, len(g) - 1) if len(g) > 1 else np.zeros((~good).sum(), int)
            left, right = g[np.maximum(pos - 1, 0)], g[pos]
            near = np.where(np.abs(cols[left] - cols[~good]) <= np.abs(cols[right] - cols[~good]), left, right)
            rot[~good] = rot[near]
            # make the borrowed rotation map the column's beam exactly
            bad = ~good
            rot[bad] = np.einsum(
                "nij,njk->nik", _smallest_rotation(np.einsum("nij,nj->ni", rot[bad], s_f[bad]), d_f[bad]), rot[bad]
            )
    elif len(cols):
        rot = _smallest_rotation(s_f, d_f)
    return rot[inv]


_CACHE: dict[tuple, tuple[NDArray[np.float32], DepthBufferLidar]] = {}


def lidar_grid(lidar_directions: NDArray[np.float32], rings: int) -> AzimuthGrid | None:
    """The integer azimuth grid of a lidar's beams (``LidarConfig.sensor_directions``: column
    ``k`` at ``−2πk/C``), or None when the directions are not laid out that way."""
    n = len(lidar_directions)
    if rings < 1 or n % rings:
        return None
    grid = AzimuthGrid.lidar(n // rings, rings)
    return grid if grid.matches(sensor_angles(lidar_directions)[0]) else None


def sampler_for(config: DepthBufferConfig, lidar_directions: NDArray[np.float32], rings: int = 1) -> DepthBufferLidar:
    """The precomputed filter for a sensor's full beam set (cached per direction array: the
    filter is a constant of the sensor; a lidar passes the same array every sweep). Beams on
    the lidar's column grid (:func:`lidar_grid`) get their cameras from the column index."""
    key = (config, id(lidar_directions), lidar_directions.shape, rings)
    hit = _CACHE.get(key)
    if hit is None or hit[0] is not lidar_directions:
        if len(_CACHE) > 16:
            _CACHE.clear()
        hit = (lidar_directions, DepthBufferLidar(lidar_directions, config, lidar_grid(lidar_directions, rings)))
        _CACHE[key] = hit
    return hit[1]


def depthbuffer_ranges(scene: Scene, batch: BeamBatch, config: DepthBufferConfig = DepthBufferConfig()) -> DepthBufferRanges:
    """Depth-buffer ranges and points of a batch of beams (filter per ``config.use_filter``)."""
    if len(batch) == 0:
        res0 = raycast_ranges(scene, batch)
        return DepthBufferRanges(**_fields(res0), sensor_points=np.zeros((0, 3), np.float32))
    db = sampler_for(config, batch.lidar_directions, batch.rings)
    beam = np.asarray(batch.beam)
    u = np.einsum("nij,nj->ni", column_rotations(batch), db.sample_directions[beam]).astype(np.float32)
    far = config.far * db.depth_scale[beam]
    # The far plane bounds depth, so off-axis pixels see up to f/cos beyond the sensor's
    # maximum range; the lidar's own maximum range (the batch's largest limit) applies too.
    reach = float(batch.max_range.max())
    limit = np.minimum(water_limit(batch.origins[:, 2], u[:, 2], reach), far).astype(np.float32)
    # Widen the columns' bearing intervals by how far a sampled ray turns from its beam
    # (its angle over the cosine of its elevation bounds the bearing change), so the
    # raycast model's per-column vessel culling keeps every vessel a sampled ray may hit.
    cos_el = math.sqrt(max(0.0, 1.0 - float(np.max(u[:, 2].astype(np.float64) ** 2))))
    extra = min(math.pi, float(db.deviation[beam].max()) / max(cos_el, 1e-3))
    sample = dataclasses.replace(
        batch,
        directions=u,
        max_range=limit,
        column_halfwidth=np.asarray(batch.column_halfwidth, dtype=np.float64) + extra + 1e-6,
    )
    res = raycast_ranges(scene, sample)
    pts, ok, _ = db.points(res.range, res.object_id >= 0, beam)
    out = _fields(res)
    for name, value in out.items():  # every per-beam field of the sampled hit, blanked where no return
        if name not in ("range", "object_id"):
            v = np.asarray(value)
            out[name] = np.where(ok.reshape((-1,) + (1,) * (v.ndim - 1)), v, 0).astype(v.dtype)
    rng = np.full(len(beam), np.inf, np.float32)
    rng[ok] = np.sqrt(np.einsum("ij,ij->i", pts[ok], pts[ok]))
    out["range"] = rng
    out["object_id"] = np.where(ok, res.object_id, -1).astype(np.int32)
    return DepthBufferRanges(**out, sensor_points=pts.astype(np.float32))


def _fields(res: BeamRanges) -> dict:
    return {f.name: getattr(res, f.name) for f in dataclasses.fields(BeamRanges)}


def make_range_model(config: DepthBufferConfig) -> RangeModel:
    """A range model with fixed depth-buffer parameters (register it under a name of your choice)."""

    def model(scene: Scene, batch: BeamBatch) -> DepthBufferRanges:
        return depthbuffer_ranges(scene, batch, config)

    return model


range_model: RangeModel = make_range_model(DepthBufferConfig())
"""``range_model="depthbuffer"``: the spherical projection filter, Table 4.1's lidar (row lidar_eq417)."""

legacy_range_model: RangeModel = make_range_model(DepthBufferConfig(use_filter=False))
"""The legacy Autoferry Gemini sampling (no filter), for comparison."""
