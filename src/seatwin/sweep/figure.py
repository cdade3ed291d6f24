"""The sweep figure: the fidelity score (and AHED) against strength per kind, the per-seed spread, the floor."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from seatwin.sweep.degradations import degradation
from seatwin.sweep.results import SweepResult, spearman_by_kind, summarise


def _rho_text(by_dir: dict) -> str:
    parts = []
    for direction, r in by_dir.items():
        band = "" if r.seed_min is None else f" (seeds {r.seed_min:.2f}–{r.seed_max:.2f})"
        parts.append(f"{direction} ρ={r.rho_points:.2f}{band}" if r.rho_points is not None else f"{direction} ρ –")
    return "; ".join(parts)


def sweep_figure(result: SweepResult) -> Any:
    """The figure of :func:`plot_sweep` (a matplotlib ``Figure``): constrained layout, the title on two lines and
    the legend below the panels, so that neither is cut nor covers a point."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kinds = result.kinds
    ncols = min(len(kinds), 2)
    nrows = math.ceil(len(kinds) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.4 * ncols, 3.9 * nrows + 0.9), squeeze=False, layout="constrained")
    rho = spearman_by_kind(result, "score")
    floor = result.floor("score")
    for ax, kind in zip(axes.flat, kinds):
        rows = [r for r in result.kind_rows(kind) if r.score is not None]
        summary = [s for s in summarise(rows, "score") if s.mean is not None]
        x = [s.strength for s in summary]
        mean = [s.mean for s in summary]
        lo = [m - s.min for m, s in zip(mean, summary)]
        hi = [s.max - m for m, s in zip(mean, summary)]
        if floor:
            ax.axhspan(min(floor), max(floor), color="0.88", zorder=0, label="floor (reference model, other seed)")
        ax.axvline(degradation(kind).reference, color="0.5", ls=":", lw=1, label="reference")
        ax.errorbar(x, mean, yerr=[lo, hi], fmt="o-", capsize=4, color="C0", label="score: mean, min–max over seeds")
        ax.scatter([r.strength for r in rows], [r.score for r in rows], s=10, color="C1", alpha=0.7, zorder=3, label="each seed")
        ahed = [s for s in summarise(result.kind_rows(kind), "ahed") if s.mean is not None]
        ax.plot([s.strength for s in ahed], [s.mean for s in ahed], "s--", color="0.55", ms=3, lw=1, label="AHED mean")
        ax.set_title(f"{kind}: {_rho_text(rho[kind])}", fontsize=8, wrap=True)
        ax.set_xlabel(degradation(kind).label)
        ax.set_ylabel("fidelity score vs reference run")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(kinds) :]:
        ax.set_visible(False)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2 if ncols == 1 else 3, fontsize=7)
    s = result.settings
    fig.suptitle(
        f"Fidelity sweep: {s.scenario}, {s.duration:g} s, tuning {s.tuning}\n"
        f"seeds {', '.join(str(x) for x in s.seeds)}; reference run: seed + {s.reference_seed_offset}",
        fontsize=10,
    )
    return fig


def plot_sweep(result: SweepResult, path: str | Path) -> Path:
    """One panel per kind: the mean fidelity score over seeds (line) with min–max bars, every seed's point,
    the reference strength (dotted) and the floor band (the reference model against the reference run
    of another seed); AHED's mean in grey for comparison."""
    import matplotlib.pyplot as plt

    fig = sweep_figure(result)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
