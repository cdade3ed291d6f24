"""The sweep figure: AHED against strength per kind, the per-seed spread, and the seed-to-seed floor."""

from __future__ import annotations

import math
from pathlib import Path

from seatwin.sweep.degradations import degradation
from seatwin.sweep.results import SweepResult, spearman_by_kind, summarise


def plot_sweep(result: SweepResult, path: str | Path) -> Path:
    """One panel per kind: mean AHED over seeds (line) with min–max bars, every seed's point, and the
    band of AHED between reference runs of different seeds (differences below it are draw noise)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kinds = result.kinds
    ncols = min(len(kinds), 2)
    nrows = math.ceil(len(kinds) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 3.8 * nrows), squeeze=False)
    rho = spearman_by_kind(result)
    floor = result.floor
    for ax, kind in zip(axes.flat, kinds):
        rows = [r for r in result.kind_rows(kind) if r.ahed is not None]
        summary = [s for s in summarise(rows) if s.ahed_mean is not None]
        x = [s.strength for s in summary]
        mean = [s.ahed_mean for s in summary]
        lo = [m - s.ahed_min for m, s in zip(mean, summary)]
        hi = [s.ahed_max - m for m, s in zip(mean, summary)]
        if floor:
            ax.axhspan(min(floor), max(floor), color="0.85", zorder=0, label=f"seed-to-seed ({len(floor)} pairs)")
            ax.axhline(sum(floor) / len(floor), color="0.6", lw=0.8, zorder=0)
        ax.errorbar(x, mean, yerr=[lo, hi], fmt="o-", capsize=4, color="C0", label="mean, min–max over seeds")
        ax.scatter([r.strength for r in rows], [r.ahed for r in rows], s=10, color="C1", alpha=0.7, zorder=3, label="each seed")
        r = rho[kind].rho_points
        ax.set_title(f"{kind}: Spearman ρ = {r:.2f}" if r is not None else f"{kind}: ρ undefined")
        ax.set_xlabel(degradation(kind).label + " (leftmost: reference)")
        ax.set_ylabel("AHED vs seed-matched reference")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(kinds) :]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=7, loc="upper left")
    s = result.settings
    fig.suptitle(f"Fidelity sweep: {s.scenario}, {s.duration:g} s, tuning {s.tuning}, seeds {list(s.seeds)}", fontsize=10)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
