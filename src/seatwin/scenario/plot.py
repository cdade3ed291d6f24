"""Plot a scenario's tracks like thesis Fig. 3.11: circles at the start, stars at the end.

East is to the right and north up (a map). In the default harbour the water outline, the
piers and the moored boats are drawn under the tracks; in a raster harbour (``ravnkloa``) its land, placed
by the harbour's alignment, and its moored boats.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from seatwin.errors import InputError
from seatwin.geo.frames import yaw_matrix
from seatwin.layout import DEFAULT_LAYOUT, HarbourLayout, LandRaster, MooredBoat
from seatwin.scenario.model import Role, Scenario
from seatwin.scenario.summary import scenario_harbour_map, water_fraction

if TYPE_CHECKING:
    from collections.abc import Sequence

    from matplotlib.axes import Axes

LAND = "#d9d2c3"
WATER = "#e3f0fa"


def _draw_harbour(ax: Axes, layout: HarbourLayout) -> None:
    from matplotlib.patches import Rectangle

    w, n0, n1, depth = layout.half_width, layout.north_min, layout.north_max, layout.land_depth
    ax.add_patch(Rectangle((-w, n0), 2 * w, n1 - n0, facecolor=WATER, edgecolor="#5b8db8", lw=1.0, zorder=0))
    for e0 in (-w - depth, w):
        ax.add_patch(Rectangle((e0, n0), depth, n1 - n0, facecolor=LAND, edgecolor="none", zorder=0))
    for box in layout.piers:
        ax.add_patch(
            Rectangle(
                (box.east_min, box.north_min),
                box.east_max - box.east_min,
                box.north_max - box.north_min,
                facecolor="#a89f8c",
                edgecolor="#6f6757",
                lw=0.6,
                zorder=1,
            )
        )
    _draw_moored(ax, layout.moored_boats)


def _draw_moored(ax: Axes, boats: Sequence[MooredBoat]) -> None:
    from matplotlib.patches import Polygon

    for boat in boats:
        rot = yaw_matrix(np.radians(boat.heading_deg))[:2, :2]  # body (forward, starboard) → (north, east)
        corners = [rot @ (a * boat.length / 2, b * boat.beam / 2) for a, b in ((1, 1), (1, -1), (-1, -1), (-1, 1))]
        xy = [(boat.east + c[1], boat.north + c[0]) for c in corners]
        ax.add_patch(Polygon(xy, closed=True, facecolor="#8c8c8c", edgecolor="none", zorder=1))


def _draw_raster(ax: Axes, raster: LandRaster) -> None:
    from matplotlib.colors import ListedColormap

    h, w = raster.water.shape
    extent = (
        raster.origin_east,
        raster.origin_east + w * raster.resolution,
        raster.origin_north,
        raster.origin_north + h * raster.resolution,
    )
    im = ax.imshow(raster.water, origin="lower", extent=extent, cmap=ListedColormap([LAND, WATER]), vmin=0, vmax=1, zorder=0)
    al = raster.alignment
    if not al.is_identity:  # the raster placed in the scenario frame (plot x = east, y = north)
        from matplotlib.transforms import Affine2D

        place = (
            Affine2D()
            .translate(-(al.centre_east + al.shift_east), -(al.centre_north + al.shift_north))
            .rotate_deg(al.rotation_deg)
            .translate(al.centre_east, al.centre_north)
        )
        im.set_transform(place + ax.transData)
    _draw_moored(ax, raster.moored())


def plot_scenario(scenario: Scenario, out: str | os.PathLike[str], tick_s: float = 10.0) -> Path:
    """Draw ``scenario`` to a PNG at ``out``; dots mark every ``tick_s`` seconds. Returns the path."""
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    out = Path(out)
    if out.suffix.lower() != ".png":
        raise InputError(out, "the plot is written as PNG: give a file name ending in .png")
    start, end = scenario.start, scenario.end
    fig, ax = plt.subplots(figsize=(7.0, 8.0), dpi=120)
    try:
        lo, hi = np.array([np.inf, np.inf]), np.array([-np.inf, -np.inf])
        on_water = []
        harbour = scenario_harbour_map(scenario)
        colours = plt.get_cmap("tab10").colors
        for i, v in enumerate(scenario.vessels):
            tr = v.trajectory
            times = np.concatenate([[start], tr.time[(tr.time > start) & (tr.time < end)], [end]])
            s = tr.state_at(times)
            colour = colours[i % len(colours)]
            label = f"{v.name} ({v.role.value})" if v.role == Role.OWNSHIP else v.name
            ax.plot(s.east, s.north, "-", color=colour, lw=1.8, label=label, zorder=3)
            ticks = tr.state_at(np.arange(start, end, tick_s))
            ax.plot(ticks.east, ticks.north, ".", color=colour, ms=4, zorder=3)
            ax.plot(s.east[0], s.north[0], "o", color=colour, ms=9, mec="black", mew=0.8, zorder=4)
            ax.plot(s.east[-1], s.north[-1], "*", color=colour, ms=15, mec="black", mew=0.8, zorder=4)
            if harbour is not None:
                on_water.append(water_fraction(s.north, s.east, harbour))
            lo = np.minimum(lo, [s.east.min(), s.north.min()])
            hi = np.maximum(hi, [s.east.max(), s.north.max()])
        margin = max(20.0, 0.08 * float(np.max(hi - lo)))
        lo, hi = lo - margin, hi + margin
        note = ""
        if isinstance(harbour, LandRaster):
            _draw_raster(ax, harbour)
            lo_pc, hi_pc = f"{100 * min(on_water):.0f}", f"{100 * max(on_water):.0f}"
            span = lo_pc if lo_pc == hi_pc else f"{lo_pc}–{hi_pc}"
            note = f"\n(land: {Path(harbour.source).stem}; vessels {span} % on water)"
        elif harbour is DEFAULT_LAYOUT and min(on_water) < 0.95:
            note = "\n(tracks leave the default harbour's water: its outline is not drawn)"
        elif harbour is DEFAULT_LAYOUT:
            _draw_harbour(ax, DEFAULT_LAYOUT)
            lo[0] = min(lo[0], -DEFAULT_LAYOUT.half_width - 15.0)
            hi[0] = max(hi[0], DEFAULT_LAYOUT.half_width + 15.0)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_aspect("equal")
        ax.set_xlabel("east [m]")
        ax.set_ylabel("north [m]")
        ax.set_title(
            f"{scenario.name}  ({end - start:.0f} s; circle: start, star: end, dots every {tick_s:g} s){note}", fontsize=10
        )
        ax.grid(True, lw=0.3, alpha=0.6)
        ax.legend(loc="best", fontsize=8)
        fig.tight_layout()
        from seatwin.outputs import atomic_output

        with atomic_output(out) as tmp:
            fig.savefig(tmp, format="png")
    finally:
        plt.close(fig)
    return out
