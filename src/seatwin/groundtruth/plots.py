"""Figures like thesis Figs. 3.14–3.17, drawn with matplotlib's Agg canvas (no display)."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np


def _new_figure(w: float = 6.4, h: float = 4.8) -> Any:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(w, h), dpi=100)
    FigureCanvasAgg(fig)
    return fig


_BEST_FIRST = ("rtk_fixed", "fix", "rtk_float", "float", "ppp", "dgps", "sbas", "pps", "gps", "single")


def _quality_rank(name: str) -> int:
    """0 for the best fix quality; unknown names last."""
    return _BEST_FIRST.index(name) if name in _BEST_FIRST else len(_BEST_FIRST)


def _slug(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name) or "vessel"


PLOT_KINDS = ("relative_positions", "eps_gnss", "fix_quality")


def plot_names(vessel_names: list[str]) -> list[str]:
    """The file names :func:`write_plots` may write for these vessels (numbered V1, V2, … in order)."""
    return [f"V{n}_{_slug(name)}_{kind}.png" for n, name in enumerate(vessel_names, start=1) for kind in PLOT_KINDS]


def write_plots(result: Any, folder: str | Path) -> list[Path]:
    """Write the figures of ``result`` (a ``GroundTruthResult``) into ``folder``; return their paths."""
    from seatwin.groundtruth.log import quality_name

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    t0 = float(result.time[0])
    for number, v in enumerate(result.vessels, start=1):
        stem = f"V{number}_{_slug(v.name)}"
        t = v.time - t0
        if v.eps_gnss is not None:
            # Fig. 3.14: bow − stern positions around the baseline circle.
            fig = _new_figure(5.5, 5.5)
            ax = fig.add_subplot()
            bad = v.eps_gnss > v.eps_threshold_m
            ax.scatter(v.rel_east[~bad], v.rel_north[~bad], s=3, label=r"$\varepsilon_{gnss}$ ≤ threshold")
            if bad.any():
                ax.scatter(
                    v.rel_east[bad], v.rel_north[bad], s=3, color="tab:red", label=r"flagged ($\varepsilon_{gnss}$ > threshold)"
                )
            a = np.linspace(0, 2 * np.pi, 361)
            ax.plot(v.baseline_m * np.sin(a), v.baseline_m * np.cos(a), "k-", lw=1, label=f"$|Q_r|$ = {v.baseline_m:.2f} m")
            ax.set_aspect("equal")
            ax.set_xlabel(r"$y_{sb} - y_{ss}$ (east) [m]")
            ax.set_ylabel(r"$x_{sb} - x_{ss}$ (north) [m]")
            ax.set_title(f"{v.name}: relative antenna positions")
            # Below the axes: in a corner it covered the baseline circle's arc.
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncols=2, fontsize=7, frameon=False)
            fig.set_layout_engine("constrained")
            path = folder / f"{stem}_relative_positions.png"
            fig.savefig(path)
            written.append(path)
            # Figs. 3.15/3.16: ε_gnss over time.
            fig = _new_figure(8, 3.5)
            ax = fig.add_subplot()
            ax.plot(t, v.eps_gnss, lw=0.8)
            ax.axhline(v.eps_threshold_m, color="tab:red", ls="--", lw=1, label=f"threshold {v.eps_threshold_m:g} m")
            ax.set_xlabel(f"time since {t0:.1f} (POSIX) [s]")
            ax.set_ylabel(r"$\varepsilon_{gnss}$ [m] (eq. 3.7)")
            ax.set_title(f"{v.name}: relative error between GNSS receivers")
            ax.legend(fontsize=7)
            fig.tight_layout()
            path = folder / f"{stem}_eps_gnss.png"
            fig.savefig(path)
            written.append(path)
        with_quality = [a for a in v.antennas if a.quality is not None]
        if with_quality:
            # Fig. 3.17: fix quality state over time.
            fig = _new_figure(8, 3.0)
            ax = fig.add_subplot()
            labelled = [
                (role, [quality_name(a.log.quality_scheme, c) for c in a.quality])
                for role, a in zip(("bow", "stern") if len(v.antennas) == 2 else ("antenna",), v.antennas)
                if a.quality is not None
            ]
            names = sorted({n for _, ns in labelled for n in ns}, key=lambda n: (_quality_rank(n), n), reverse=True)
            level = {n: i for i, n in enumerate(names)}  # best quality at the top
            for role, ns in labelled:
                ax.step(t, [level[n] for n in ns], where="post", label=role, lw=1)
            ax.set_yticks(range(len(names)))
            ax.set_yticklabels(names)
            ax.set_xlabel(f"time since {t0:.1f} (POSIX) [s]")
            ax.set_title(f"{v.name}: GNSS fix quality")
            ax.legend(fontsize=7)
            fig.tight_layout()
            path = folder / f"{stem}_fix_quality.png"
            fig.savefig(path)
            written.append(path)
    return written
