"""Checking the thesis's claim (4.11, 4.24): with the spherical projection filter a depth-buffer
point lies within ``ε_max`` of the exact point of its beam; without it the error grows with range.

A lidar stands still in the default harbour with vessels at several ranges; the scene is
frozen at one time (a depth buffer is one rendering). For every beam the exact point comes
from casting the beam itself (the ``raycast`` model), the depth-buffer point from
:class:`~seatwin.sensors.depthbuffer.model.DepthBufferLidar`; both are cut at the water.

A beam *straddles an edge* when its exact ray and the pixel-centre ray it is sampled by do
not see the same surface: one returns and the other not (silhouette, water line, far
plane), they hit different objects (occlusion), or the surface normals differ by more than
``edge_normal_deg`` (a crease or self-occlusion within one object). These are counted and
reported apart — the thesis's error analysis assumes one smooth surface per pixel.

Beams at grazing incidence (beyond ``grazing_deg`` from the normal) stay in the statistics
but are counted: there a sub-pixel shift of the ray moves the hit along the surface by
``Δα·r / cos(incidence)``, more than the point-representation error 4.22 bounds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from seatwin.sensors.depthbuffer.errors import c1, c2, max_error
from seatwin.sensors.depthbuffer.filter import AzimuthGrid
from seatwin.sensors.depthbuffer.model import DepthBufferConfig, DepthBufferLidar

DEFAULT_TARGETS: tuple[tuple[float, float, float, str], ...] = (
    # (range [m], bearing [deg, clockwise from north], heading [deg], model)
    (8.0, 60.0, 150.0, "finn"),
    (15.0, -40.0, 30.0, "havfruen"),
    (25.0, 150.0, 90.0, "finn"),
    (35.0, 20.0, 200.0, "havfruen"),
    (50.0, -165.0, 10.0, "havfruen"),
    (65.0, 8.0, 120.0, "havfruen"),
    (80.0, 175.0, 60.0, "havfruen"),
    (95.0, -3.0, 0.0, "havfruen"),
)
"""Target vessels around the sensor (at north 0, east 0, 3 m above the water)."""

SENSOR_HEIGHT = 3.0


def verification_scene(
    targets: tuple[tuple[float, float, float, str], ...] = DEFAULT_TARGETS, harbour: object = "default"
) -> object:
    """The default harbour with stationary vessels at the given ranges/bearings from the origin."""
    from seatwin.scenario.model import Trajectory
    from seatwin.world.harbour import build_harbour
    from seatwin.world.scene import Scene
    from seatwin.world.vessels import vessel_model

    vessels = {}
    for i, (rng, brg, hdg, model) in enumerate(targets):
        b = math.radians(brg)
        n, e = rng * math.cos(b), rng * math.sin(b)
        traj = Trajectory(np.array([0.0, 100.0]), np.array([n, n]), np.array([e, e]), np.radians([hdg, hdg]))
        vessels[f"target{i}_{int(rng)}m"] = (vessel_model(model), traj)
    return Scene(build_harbour(harbour), vessels)


@dataclass
class ModeResult:
    """Per-beam comparison of one sampling mode (filter or legacy) with the exact beams."""

    name: str
    eps_max: float
    range: NDArray[np.float64]
    """Exact range of each compared beam (both returned, no edge)."""
    distance: NDArray[np.float64]
    """3-D distance depth-buffer point ↔ exact point, same beams."""
    local_bound: NDArray[np.float64]
    """``ε^v`` at the beam's point with the worst pixel-step signs (4.22 with ``|x|+C_2``)."""
    n_beams: int
    n_compared: int
    edges: dict[str, int] = field(default_factory=dict)
    all_distance: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    """Distances including edge beams (both returned)."""
    cos_incidence: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    """|cos| of the angle between each compared beam and the surface normal."""
    grazing_deg: float = 80.0
    """Incidence beyond which a beam counts as grazing (reported, not excluded)."""
    fallback: int | None = None
    """Plane mode: returns that fell back to the thesis point (an edge), among ``n_returns``."""
    n_returns: int = 0

    def summary(self) -> dict:
        d, a = self.distance, self.all_distance
        steep = self.cos_incidence >= math.cos(math.radians(self.grazing_deg))
        q = lambda x, p: float(np.percentile(x, p)) if x.size else float("nan")  # noqa: E731
        return {
            "mode": self.name,
            "eps_max": self.eps_max,
            "beams": self.n_beams,
            "compared": self.n_compared,
            "edge_beams": int(sum(self.edges.values())),
            "edges": dict(self.edges),
            "p50": q(d, 50),
            "p99": q(d, 99),
            "max": float(d.max()) if d.size else float("nan"),
            "within_eps_max": float(np.mean(d <= self.eps_max)) if d.size else float("nan"),
            "within_local_bound": float(np.mean(d <= self.local_bound)) if d.size else float("nan"),
            "grazing_beams": int((~steep).sum()),
            "max_non_grazing": float(d[steep].max()) if steep.any() else float("nan"),
            "p99_with_edges": q(a, 99),
            "max_with_edges": float(a.max()) if a.size else float("nan"),
            **({"fallback_share": self.fallback / max(self.n_returns, 1)} if self.fallback is not None else {}),
        }

    def binned(self, edges: NDArray[np.float64]) -> dict[str, list[float]]:
        """Median / 99th percentile / max distance per range bin (NaN for empty bins)."""
        idx = np.digitize(self.range, edges) - 1
        out: dict[str, list[float]] = {"median": [], "p99": [], "max": [], "count": []}
        for k in range(len(edges) - 1):
            d = self.distance[idx == k]
            out["count"].append(float(d.size))
            out["median"].append(float(np.median(d)) if d.size else float("nan"))
            out["p99"].append(float(np.percentile(d, 99)) if d.size else float("nan"))
            out["max"].append(float(d.max()) if d.size else float("nan"))
        return out


def _local_bound(points_sensor: NDArray[np.float64], db: DepthBufferLidar, sel: NDArray[np.bool_]) -> NDArray[np.float64]:
    """``ε^v`` of 4.22 at each point in its camera's view space, signs chosen for the worst case."""
    cam = db.camera
    q_v = np.einsum("nji,nj->ni", db._rot[sel], points_sensor)  # noqa: SLF001 - sensor → camera c view (Rᵀ)
    k1, k2 = c1(cam), c2(cam)
    z = q_v[:, 2]
    return np.abs(z / (k1 + z)) * np.sqrt((np.abs(q_v[:, 0]) + k2) ** 2 + (np.abs(q_v[:, 1]) + k2) ** 2 + z**2)


def _exact(
    caster: object, directions: NDArray[np.float64], origin: NDArray[np.float64], rotation: NDArray[np.float64], far: float
) -> tuple[object, NDArray[np.float64], NDArray[np.bool_]]:
    """The exact cast of every beam (world frame), its world directions and where it returns (cut at the water)."""
    from seatwin.sensors.lidar_physics import water_limit

    o = np.broadcast_to(origin, (len(directions), 3))
    beam_w = directions @ rotation.T
    exact = caster.cast(o, beam_w, max_range=far)  # type: ignore[attr-defined]
    wl = water_limit(o[:, 2].astype(np.float32), beam_w[:, 2].astype(np.float32), far)
    return exact, beam_w, (exact.object_id >= 0) & (exact.range <= wl)


def compare_mode(
    caster: object,
    directions: NDArray[np.float64],
    origin: NDArray[np.float64],
    rotation: NDArray[np.float64],
    config: DepthBufferConfig,
    edge_normal_deg: float = 30.0,
    grid: AzimuthGrid | None = None,
) -> ModeResult:
    """Compare depth-buffer points with exact beam points for one configuration (``grid``: the
    beams' integer azimuth grid, see :class:`DepthBufferLidar`)."""
    from seatwin.sensors.lidar_physics import water_limit

    db = DepthBufferLidar(directions, config, grid)
    n = len(db)
    exact, beam_w, e_hit = _exact(caster, db.directions, origin, rotation, config.far)

    def cut(oo: NDArray[np.float64], uu: NDArray[np.float64]) -> NDArray[np.float64]:
        # the same limits as the exact beams: the water, and the lidar's range f
        return water_limit(oo[:, 2].astype(np.float32), uu[:, 2].astype(np.float32), config.far).astype(np.float64)

    dbh = db.cast(caster, origin, rotation, cut=cut)
    both = e_hit & dbh.hit
    p_exact = np.where(e_hit, exact.range, np.nan)[:, None].astype(np.float64) * db.directions
    dist_all = np.linalg.norm(dbh.points - p_exact, axis=1)
    cosn = np.einsum("ij,ij->i", exact.normal.astype(np.float64), dbh.normal.astype(np.float64))
    one_side = e_hit != dbh.hit
    other_obj = both & (exact.object_id != dbh.object_id)
    crease = both & ~other_obj & (cosn < math.cos(math.radians(edge_normal_deg)))
    keep = both & ~other_obj & ~crease
    cam = db.camera
    return ModeResult(
        name="filter" if config.use_filter else "legacy",
        eps_max=max_error(cam),
        range=exact.range[keep].astype(np.float64),
        distance=dist_all[keep],
        local_bound=_local_bound(p_exact[keep], db, keep),
        n_beams=n,
        n_compared=int(keep.sum()),
        edges={
            "one_returns": int(one_side.sum()),
            "different_object": int(other_obj.sum()),
            "crease": int(crease.sum()),
        },
        all_distance=dist_all[both],
        cos_incidence=np.abs(np.einsum("ij,ij->i", exact.normal[keep].astype(np.float64), beam_w[keep])),
    )


def frozen_batch(
    directions: NDArray[np.float64],
    origin: NDArray[np.float64],
    rotation: NDArray[np.float64],
    t: float,
    rings: int,
    reach: float,
) -> object:
    """A :class:`~seatwin.sensors.rangemodel.BeamBatch` of one sweep fired at one instant from a
    sensor at rest (``directions``: azimuth-major, ``rings`` per column), cut at the water."""
    from seatwin.sensors.lidar import _column_bearings
    from seatwin.sensors.lidar_physics import water_limit
    from seatwin.sensors.rangemodel import BeamBatch

    d32 = np.asarray(directions, np.float32)
    dw = (d32.astype(np.float64) @ np.asarray(rotation).T).astype(np.float32)
    o = np.broadcast_to(np.asarray(origin, np.float32), dw.shape).copy()
    cols = len(dw) // rings
    bearing, half = _column_bearings(dw, rings)
    beam = np.arange(len(dw))
    return BeamBatch(
        o, dw, water_limit(o[:, 2], dw[:, 2], reach), beam, beam // rings, np.full(cols, float(t)),
        np.tile(np.asarray(origin, np.float64), (cols, 1)), bearing, half, rings, d32,
    )  # fmt: skip


def compare_plane(
    scene: object,
    caster: object,
    directions: NDArray[np.float64],
    origin: NDArray[np.float64],
    rotation: NDArray[np.float64],
    config: DepthBufferConfig,
    t: float,
    rings: int,
    linear_depth: bool = True,
) -> ModeResult:
    """The ``depthbuffer-plane`` model (rasterised, OpenGL) against the exact beams, scene frozen at ``t``.

    Its points lie on the beams, so the distance is the range error. Compared: beams where both
    return the same object and the plane was used; returns that fell back to the thesis point
    (edges) are counted and kept in ``all_distance``.
    """
    from seatwin.sensors.depthbuffer.errors import range_error_bound
    from seatwin.sensors.depthbuffer.plane_range import plane_ranges

    exact, beam_w, e_hit = _exact(caster, directions, origin, rotation, config.far)
    batch = frozen_batch(directions, origin, rotation, t, rings, config.far)
    res = plane_ranges(scene, batch, config, linear_depth)  # type: ignore[arg-type]
    hit = res.object_id >= 0
    both = e_hit & hit
    p_exact = np.where(e_hit, exact.range, np.nan)[:, None] * directions
    dist = np.linalg.norm(res.sensor_points.astype(np.float64) - p_exact, axis=1)
    same = both & (exact.object_id == res.object_id)
    fb = np.asarray(res.fallback)
    keep = same & ~fb
    cos_i = np.abs(np.einsum("ij,ij->i", exact.normal[keep].astype(np.float64), beam_w[keep]))
    cos_i /= np.maximum(np.linalg.norm(exact.normal[keep].astype(np.float64), axis=1), 1e-12)
    cam = config.camera()
    return ModeResult(
        name="plane" if linear_depth else "plane_24bit",
        eps_max=max_error(cam),
        range=exact.range[keep].astype(np.float64),
        distance=dist[keep],
        local_bound=range_error_bound(exact.range[keep], np.arccos(np.clip(cos_i, 0.0, 1.0)), cam, plane=True),
        n_beams=len(directions),
        n_compared=int(keep.sum()),
        edges={
            "one_returns": int((e_hit != hit).sum()),
            "different_object": int((both & ~same).sum()),
            "fallback": int((same & fb).sum()),
        },
        all_distance=dist[both],
        cos_incidence=cos_i,
        fallback=int((fb & hit).sum()),
        n_returns=int(hit.sum()),
    )


def run_verification(
    config: DepthBufferConfig = DepthBufferConfig(),
    columns: int = 1800,
    t: float = 1.0,
    scene: object | None = None,
    plane: bool = False,
) -> dict[str, ModeResult]:
    """Filter and legacy results on the verification scene (VLP-16 beams, ``columns`` per turn); with
    ``plane``, also the ``depthbuffer-plane`` model rasterised by OpenGL (``plane``: float32 view
    depth; ``plane_24bit``: the points rebuilt from the 24-bit depth buffer)."""
    from seatwin.engine import make_caster
    from seatwin.sensors.lidar_config import VLP16, LidarMount

    scene = scene if scene is not None else verification_scene()
    caster = make_caster(scene.posed_meshes(t))  # type: ignore[attr-defined]
    mount = LidarMount(z=-SENSOR_HEIGHT)
    dirs = VLP16.with_(columns=columns).sensor_directions().astype(np.float64)
    grid = AzimuthGrid.lidar(columns, VLP16.rings)
    out = {}
    for use_filter in (True, False):
        cfg = DepthBufferConfig(**{**config.__dict__, "use_filter": use_filter})
        res = compare_mode(caster, dirs, mount.translation, mount.rotation(), cfg, grid=grid)
        out[res.name] = res
    if plane:
        for linear in (True, False):
            res = compare_plane(scene, caster, dirs, mount.translation, mount.rotation(), config, t, VLP16.rings, linear)
            out[res.name] = res
    return out


def ground_rings(n_c: int = 4, height: float = 3.0, columns: int = 1800, far: float = 100.0) -> dict[str, NDArray[np.float64]]:
    """Sensor-frame points of a VLP-16 over a flat ground plane, with and without the filter (Fig. 4.7).

    Without the filter each ring is an ``N_c``-gon (the beam shape error); with it a circle.
    """
    from seatwin.engine import MeshData, make_caster
    from seatwin.sensors.lidar_config import VLP16, LidarMount

    s = 2.0 * far
    plane = MeshData(np.array([[-s, -s, 0.0], [s, -s, 0.0], [s, s, 0.0], [-s, s, 0.0]]), np.array([[0, 1, 2], [0, 2, 3]]), 0)
    caster = make_caster([plane])
    mount = LidarMount(z=-height)
    dirs = VLP16.with_(columns=columns).sensor_directions().astype(np.float64)
    grid = AzimuthGrid.lidar(columns, VLP16.rings)
    out = {}
    for use_filter in (True, False):
        db = DepthBufferLidar(dirs, DepthBufferConfig(n_c=n_c, far=far, use_filter=use_filter), grid)
        h = db.cast(caster, mount.translation, mount.rotation())
        out["filter" if use_filter else "legacy"] = h.points[h.hit]
    return out


def verification_report(columns: int = 1800, plot: str | Path | None = None, plane: bool = True) -> dict[str, dict]:
    """The part-5 numbers per mode (``filter``, ``legacy``, and with ``plane`` the rasterised
    ``plane`` and ``plane_24bit``): :meth:`ModeResult.summary` plus the distances in 10 m range
    bins; with ``plot``, also the verification figure (PNG) there.

    ``seatwin errors --verify`` prints this as JSON. Without an EGL/GL driver the plane modes are
    left out and ``plane_error`` says why.
    """
    from seatwin.errors import InputError

    try:
        res = run_verification(columns=columns, plane=plane)
        skipped = None
    except InputError as exc:  # no headless OpenGL here: the ray-cast modes still stand
        res, skipped = run_verification(columns=columns), str(exc)
    bins = np.arange(0.0, 101.0, 10.0)
    out: dict[str, dict] = {name: {**r.summary(), "bins_m": bins.tolist(), "binned": r.binned(bins)} for name, r in res.items()}
    if skipped is not None:
        out["plane_error"] = {"error": skipped}
    if plot is not None:
        from seatwin.sensors.depthbuffer.plots import fig_verification

        fig_verification(Path(plot), {k: v for k, v in res.items() if k in ("filter", "legacy")}, ground_rings())
    return out
