"""Top-view figure of one lidar sweep over the harbour (like thesis Fig. 5.10)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from seatwin.geo.frames import yaw_rotate
from seatwin.sensors.lidar import LidarSweep
from seatwin.world.scene import Scene


def _footprint(vertices: NDArray[np.float64]) -> NDArray[np.float64] | None:
    from scipy.spatial import ConvexHull, QhullError

    xy = np.unique(np.round(vertices[:, :2], 3), axis=0)
    try:
        ring = xy[ConvexHull(xy).vertices]
    except (QhullError, ValueError):
        return None
    return np.vstack([ring, ring[:1]])


def plot_sweep_top_view(
    scene: Scene,
    sweep: LidarSweep,
    world_points: NDArray[np.float64],
    output: str | Path,
    extent: float = 110.0,
    ownship: str | None = None,
    title: str = "",
) -> None:
    """Write a PNG: points (east right, north up) coloured by intensity, harbour footprints in
    grey, every vessel's outline at the sweep's middle time with its name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t_mid = sweep.stamp + 0.5 * (float(sweep.time.max()) if len(sweep) else 0.0)
    centre = np.zeros(2)
    if ownship is not None:
        p = scene.pose(ownship, t_mid)
        centre = np.array([float(p.north), float(p.east)])
    fig, ax = plt.subplots(figsize=(8, 8), dpi=120)
    for obj in scene.static_objects:
        if len(obj.mesh.faces) <= 200:
            ring = _footprint(np.asarray(obj.mesh.vertices))
            if ring is not None:
                ax.fill(ring[:, 1], ring[:, 0], color="0.88", zorder=0)
    sc = ax.scatter(
        world_points[:, 1],
        world_points[:, 0],
        c=sweep.intensity,
        s=3,
        cmap="viridis",
        vmin=0,
        vmax=max(1.0, float(sweep.intensity.max()) if len(sweep) else 1.0),
        zorder=2,
    )
    for name, model in scene.vessel_models.items():
        p = scene.pose(name, t_mid)
        ring = model.outline()
        dn, de = yaw_rotate(float(p.heading), ring[:, 0], ring[:, 1])
        n, e = float(p.north) + dn, float(p.east) + de
        colour = "navy" if name == ownship else "deepskyblue"
        ax.plot(e, n, color=colour, lw=1.2, zorder=3)
        ax.annotate(name, (float(p.east), float(p.north)), xytext=(6, 6), textcoords="offset points", color=colour, fontsize=8)
    ax.set_xlim(centre[1] - extent, centre[1] + extent)
    ax.set_ylim(centre[0] - extent, centre[0] + extent)
    ax.set_aspect("equal")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_title(title, fontsize=9)
    fig.colorbar(sc, ax=ax, label="intensity", shrink=0.8)
    fig.tight_layout()
    from seatwin.outputs import atomic_output

    try:
        with atomic_output(output) as tmp:
            fig.savefig(tmp, format=Path(output).suffix.lstrip(".").lower() or "png")
    finally:
        plt.close(fig)
