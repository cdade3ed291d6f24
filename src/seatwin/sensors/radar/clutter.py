"""False plots (clutter): a Poisson point process over the radar's coverage annulus.

The density is uniform (plots per km² per scan) or a world-fixed map (plots per m² per
scan on a grid; e.g. fitted from a real recording, where clutter gathers near land). Points
are drawn per map cell and thinned to the annulus ``[min_range, max_range]`` around the
antenna, which is exact for a Poisson process.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from seatwin.sensors.radar.config import ClutterConfig, ClutterMap


def annulus_area(min_range: float, max_range: float) -> float:
    """Area [m²] of the coverage annulus."""
    return float(np.pi * (max_range**2 - min_range**2))


def _uniform_annulus(
    rng: np.random.Generator, density_m2: float, center: tuple[float, float], rmin: float, rmax: float
) -> NDArray[np.float64]:
    n = rng.poisson(density_m2 * annulus_area(rmin, rmax))
    r = np.sqrt(rng.uniform(rmin**2, rmax**2, n))
    b = rng.uniform(0.0, 2 * np.pi, n)
    return np.column_stack([center[0] + r * np.cos(b), center[1] + r * np.sin(b)])


def _map_points(
    rng: np.random.Generator, cmap: ClutterMap, center: tuple[float, float], rmin: float, rmax: float
) -> NDArray[np.float64]:
    d = np.asarray(cmap.density, float)
    rows, cols = d.shape
    n0 = cmap.north0_m + np.arange(rows) * cmap.cell_m
    e0 = cmap.east0_m + np.arange(cols) * cmap.cell_m
    # Only cells that can touch the annulus.
    dn = np.maximum(np.maximum(n0 - center[0], center[0] - (n0 + cmap.cell_m)), 0.0)[:, None]
    de = np.maximum(np.maximum(e0 - center[1], center[1] - (e0 + cmap.cell_m)), 0.0)[None, :]
    near = (np.hypot(dn, de) <= rmax) & (d > 0)
    ri, ci = np.nonzero(near)
    counts = rng.poisson(d[ri, ci] * cmap.cell_m**2)
    ri, ci = np.repeat(ri, counts), np.repeat(ci, counts)
    pts = np.column_stack(
        [
            n0[ri] + rng.uniform(0.0, cmap.cell_m, len(ri)),
            e0[ci] + rng.uniform(0.0, cmap.cell_m, len(ci)),
        ]
    )
    if cmap.outside_density > 0:
        out = _uniform_annulus(rng, cmap.outside_density, center, rmin, rmax)
        inside = (
            (out[:, 0] >= cmap.north0_m)
            & (out[:, 0] < cmap.north0_m + rows * cmap.cell_m)
            & (out[:, 1] >= cmap.east0_m)
            & (out[:, 1] < cmap.east0_m + cols * cmap.cell_m)
        )
        pts = np.vstack([pts, out[~inside]])
    r = np.hypot(pts[:, 0] - center[0], pts[:, 1] - center[1])
    return pts[(r >= rmin) & (r <= rmax)]


def clutter_points(
    rng: np.random.Generator, cfg: ClutterConfig, center: tuple[float, float], min_range: float, max_range: float
) -> NDArray[np.float64]:
    """False plots of one scan as (n, 2) world ``[north, east]``; ``center`` is the antenna position."""
    if cfg.kind == "none":
        return np.empty((0, 2))
    if cfg.kind == "uniform":
        return _uniform_annulus(rng, cfg.density_per_km2 * 1e-6, center, min_range, max_range)
    assert cfg.map is not None
    return _map_points(rng, cfg.map, center, min_range, max_range)


def expected_clutter(
    cfg: ClutterConfig, center: tuple[float, float], min_range: float, max_range: float, n_mc: int = 20000
) -> float:
    """Expected number of false plots per scan at ``center`` (exact for uniform, Monte Carlo for a map)."""
    if cfg.kind == "none":
        return 0.0
    if cfg.kind == "uniform":
        return cfg.density_per_km2 * 1e-6 * annulus_area(min_range, max_range)
    assert cfg.map is not None
    g = np.random.default_rng(0)
    r = np.sqrt(g.uniform(min_range**2, max_range**2, n_mc))
    b = g.uniform(0, 2 * np.pi, n_mc)
    n = center[0] + r * np.cos(b)
    e = center[1] + r * np.sin(b)
    return float(map_density(cfg.map, n, e).mean() * annulus_area(min_range, max_range))


def map_density(cmap: ClutterMap, north: NDArray[np.float64], east: NDArray[np.float64]) -> NDArray[np.float64]:
    """The map's density [plots/m²/scan] at world points."""
    d = np.asarray(cmap.density, float)
    r = np.floor((np.asarray(north) - cmap.north0_m) / cmap.cell_m).astype(np.int64)
    c = np.floor((np.asarray(east) - cmap.east0_m) / cmap.cell_m).astype(np.int64)
    ok = (r >= 0) & (r < d.shape[0]) & (c >= 0) & (c < d.shape[1])
    out = np.full(np.shape(north), cmap.outside_density, float)
    out[ok] = d[r[ok], c[ok]]
    return out
