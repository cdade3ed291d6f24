"""Matplotlib figures of the comparison report (thesis Figs. 5.3–5.5, 5.7, 5.10), returned as PNG bytes."""

from __future__ import annotations

import datetime as dt
import io
from types import ModuleType

import numpy as np
from numpy.typing import NDArray

from seatwin.evaluation.compare import Comparison, ComparisonSeries

COLORS = {"real": "#1f77b4", "synthetic": "#d62728", "truth": "#2ca02c"}


def _plt() -> ModuleType:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


FIGURE_DPI = 144
"""Pixels per inch of the report's figures: a figure 8 inches wide is 1152 pixels, shown 960 CSS pixels wide
(:data:`seatwin.report.html.PIXELS_PER_CSS_PX`), sharp on high-density screens."""


def to_png(fig) -> bytes:  # noqa: ANN001
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=FIGURE_DPI, bbox_inches="tight", pad_inches=0.08)
    _plt().close(fig)
    return buf.getvalue()


def _clock(t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Seconds since the first instant (axes in s; the start is printed in the title)."""
    return t - t[0] if len(t) else t


def _start(t: NDArray[np.float64]) -> str:
    if not len(t):
        return ""
    return dt.datetime.fromtimestamp(float(t[0]), dt.UTC).strftime("%Y-%m-%d %H:%M:%S UTC")


def hellinger_figure(series: ComparisonSeries, title: str) -> bytes:
    """Fig. 5.4: HED and COVDIFF (5.31), with |NEES| and |RMSE| differences of synthetic − real over time."""
    plt = _plt()
    t = _clock(series.time)
    fig, ax = plt.subplots(3, 1, figsize=(8, 6.5), sharex=True)
    ax[0].plot(t, series.hed, ".-", ms=3, label="HED (5.30)")
    ax[0].plot(t, series.covdiff, ".-", ms=3, label="COVDIFF (5.31)")
    ax[0].set_ylim(-0.02, 1.02)
    ax[0].set_ylabel("distance")
    ax[0].legend(loc="best", fontsize=8)
    ax[1].plot(t, np.abs(series.nees_synthetic - series.nees_real), ".-", ms=3, color="#9467bd")
    ax[1].set_ylabel("|ΔNEES|")
    ax[2].plot(t, np.abs(series.rmse_synthetic - series.rmse_real), ".-", ms=3, color="#8c564b")
    ax[2].set_ylabel("|ΔRMSE|")
    ax[2].set_xlabel(f"time [s] from {_start(series.time)}")
    only = series.has_real ^ series.has_synthetic
    for a in ax:
        a.grid(alpha=0.3)
        if only.any():
            a.fill_between(
                t,
                0,
                1,
                where=only,
                transform=a.get_xaxis_transform(),
                color="orange",
                alpha=0.15,
                step="mid",
                label="only one dataset has a track",
            )
    ax[0].legend(loc="best", fontsize=8)  # again, now with the shaded band's entry
    fig.suptitle(title)
    return to_png(fig)


def metrics_figure(comp: Comparison, target: str, title: str) -> bytes:
    """Figs. 5.5/5.9: NEES (log) and RMSE of each dataset over time."""
    plt = _plt()
    fig, ax = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    t0 = min([s.time[0] for s in (comp.real.series[target], comp.synthetic.series[target]) if len(s.time)], default=0.0)
    for name, ev in (("real", comp.real), ("synthetic", comp.synthetic)):
        s = ev.series[target]
        ax[0].semilogy(s.time - t0, s.nees, ".-", ms=3, color=COLORS[name], label=name)
        ax[1].plot(s.time - t0, s.rmse, ".-", ms=3, color=COLORS[name], label=name)
    ax[0].set_ylabel("NEES (5.26)")
    ax[1].set_ylabel("RMSE (5.25)")
    ax[1].set_xlabel("time [s]" + (f" from {_start(np.array([t0]))}" if t0 else ""))
    for a in ax:
        a.grid(alpha=0.3, which="both")
        a.legend(loc="best", fontsize=8)
    fig.suptitle(title)
    return to_png(fig)


def _ellipse(mean: NDArray[np.float64], cov: NDArray[np.float64], k: float = 2.0, n: int = 48) -> NDArray[np.float64]:
    """Points (n, 2) of the k-σ ellipse of a 2-D Gaussian in (east, north) plot coordinates."""
    w, v = np.linalg.eigh(0.5 * (cov + cov.T))
    w = np.sqrt(np.maximum(w, 0.0))
    a = np.linspace(0, 2 * np.pi, n)
    circle = np.stack([np.cos(a), np.sin(a)], axis=1)
    return mean + k * (circle * w) @ v.T


def _land(ax, mask, extent: tuple[float, float, float, float]) -> None:  # noqa: ANN001
    """Grey land from a water mask (``is_water(north, east)``) over ``extent`` = (e0, e1, n0, n1)."""
    e0, e1, n0, n1 = extent
    res = max((e1 - e0), (n1 - n0)) / 400.0
    ee, nn = np.meshgrid(np.arange(e0, e1, res), np.arange(n0, n1, res))
    water = np.asarray(mask.is_water(nn, ee), dtype=bool)
    ax.imshow(
        np.where(water, np.nan, 1.0),
        origin="lower",
        extent=(e0, e1, n0, n1),
        cmap="Greys",
        vmin=0,
        vmax=2.5,
        interpolation="nearest",
        zorder=0,
    )


def tracks_figure(comp: Comparison, truth, target: str, title: str, mask=None, ellipse_every: int = 5) -> bytes:  # noqa: ANN001
    """Fig. 5.7: ground truth, both datasets' estimates and 2σ position ellipses over the harbour map."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.5), sharex=True, sharey=True)
    tr = truth[target]
    pts = [np.column_stack([tr.east, tr.north])]
    for ax, (name, ev) in zip(axes, (("real", comp.real), ("synthetic", comp.synthetic))):
        s = ev.series[target]
        ok = s.valid
        ax.plot(tr.east, tr.north, "-", color=COLORS["truth"], lw=1.5, label="ground truth", zorder=3)
        if ok.any():
            ax.plot(s.state[ok, 2], s.state[ok, 0], ".", ms=3, color=COLORS[name], label=f"{name} estimate", zorder=4)
            pts.append(np.column_stack([s.state[ok, 2], s.state[ok, 0]]))
            for i in np.flatnonzero(ok)[:: max(ellipse_every, 1)]:
                c = s.covariance[i][np.ix_([2, 0], [2, 0])]
                e = _ellipse(np.array([s.state[i, 2], s.state[i, 0]]), c)
                ax.plot(e[:, 0], e[:, 1], "-", color="#17becf", lw=0.7, zorder=2)
        ax.set_title(name)
        ax.set_xlabel("east [m]")
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.legend(loc="best", fontsize=8)
    axes[0].set_ylabel("north [m]")
    allp = np.concatenate(pts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = max(20.0, 0.1 * float(np.max(hi - lo)))
    extent = (lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad)
    for ax in axes:
        if mask is not None:
            _land(ax, mask, extent)
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
    fig.suptitle(title + f" — 2σ position ellipses (every {max(ellipse_every, 1):d}-th instant), land grey")
    return to_png(fig)


def clouds_figure(
    real_xy: NDArray[np.float64],
    synthetic_xy: NDArray[np.float64],
    title: str,
    ownship: tuple[float, float] | None = None,
    targets: list[tuple[str, float, float]] | None = None,
    radius: float = 10.0,
) -> bytes:
    """Fig. 5.10: both datasets' point clouds (north, east) at one time; ownship and targets circled.

    The view spans the ownship and the targets with a margin (all points if neither is given).
    """
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.5), sharex=True, sharey=True)
    marks = ([ownship] if ownship is not None else []) + [(n, e) for _, n, e in (targets or [])]
    for ax, (name, xy) in zip(axes, (("synthetic", synthetic_xy), ("real", real_xy))):
        xy = np.asarray(xy, float).reshape(-1, 2)
        ax.plot(xy[:, 1], xy[:, 0], ".", ms=1.5, color=COLORS[name])
        if ownship is not None:
            ax.add_patch(plt.Circle((ownship[1], ownship[0]), 5.0, fill=False, color="navy", lw=1.5))
        for label, n, e in targets or []:
            ax.add_patch(plt.Circle((e, n), radius, fill=False, color="deepskyblue", lw=1.5))
            ax.plot(e, n, "o", color=COLORS["truth"], ms=4)
            ax.annotate(label, (e, n), xytext=(6, 6), textcoords="offset points", fontsize=8)
        ax.set_title(f"{name}: {len(xy)} points")
        ax.set_aspect("equal")
        ax.set_xlabel("east [m]")
        ax.grid(alpha=0.3)
    if marks:
        m = np.asarray(marks, float)
        lo, hi = m.min(axis=0), m.max(axis=0)
        pad = max(40.0, 0.3 * float(np.max(hi - lo)))
        axes[0].set_xlim(lo[1] - pad, hi[1] + pad)
        axes[0].set_ylim(lo[0] - pad, hi[0] + pad)
    axes[0].set_ylabel("north [m]")
    fig.suptitle(title)
    return to_png(fig)


def ahed_axis_top(values: list[float | None]) -> float:
    """The AHED axis' top: AHED lies in [0, 1], but small values must stay visible — 1.3 × the largest defined
    value, at least 0.01, at most 1."""
    defined = [v for v in values if v is not None and np.isfinite(v)]
    return float(min(1.0, max(0.01, 1.3 * max(defined, default=1.0))))


def ahed_figure(rows: list[dict], title: str) -> bytes:
    """Fig. 5.3: AHED per scenario × target, one bar per tuning."""
    plt = _plt()
    groups = sorted({(r["scenario"], r["target"]) for r in rows})
    tunings = sorted({r["tuning"] for r in rows})
    fig, ax = plt.subplots(figsize=(max(6, 0.9 * len(groups) * max(len(tunings), 1)), 4))
    width = 0.8 / max(len(tunings), 1)
    for j, tun in enumerate(tunings):
        vals = []
        for g in groups:
            v = next((r["ahed"] for r in rows if (r["scenario"], r["target"]) == g and r["tuning"] == tun), None)
            vals.append(np.nan if v is None else v)
        x = np.arange(len(groups)) + (j - (len(tunings) - 1) / 2) * width
        ax.bar(x, vals, width, label=tun or "(untitled)")
        for xi, v in zip(x, vals):
            if np.isnan(v):  # undefined: no common instant — shown as such, never as a zero bar
                ax.text(xi, 0.02, "undefined", rotation=90, ha="center", va="bottom", fontsize=7, color="0.4")
    ax.set_xticks(np.arange(len(groups)), [f"{s}\n{t}" for s, t in groups], fontsize=8)
    ax.set_ylim(0, ahed_axis_top([r["ahed"] for r in rows]))
    ax.set_ylabel("AHED (5.34)")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    ax.set_title(title)
    return to_png(fig)


def tracking_figure(tracks, truth, mask, title: str) -> bytes:  # noqa: ANN001 - Tracks, TruthSet | None, water mask | None
    """A tracking run from above: every confirmed track (a line, its start a dot), the targets' ground truth (green,
    named at their start) and the land of ``mask`` (grey), east to the right and north up."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(8.0, 7.0), layout="constrained")
    conf = tracks.confirmed_only()
    pts = [np.empty((0, 2))]
    ids = np.unique(conf.track_id)
    cmap = plt.get_cmap("tab10")
    for i, k in enumerate(ids):
        rows = conf.track_id == k
        e, n = conf.state[rows, 2], conf.state[rows, 0]
        ax.plot(e, n, "-", color=cmap(i % 10), lw=1.4, zorder=3, label="confirmed tracks" if i == 0 else None)
        ax.plot(e[:1], n[:1], "o", color=cmap(i % 10), ms=4, zorder=4)
        pts.append(np.column_stack([e, n]))
    if truth is not None:
        for j, (name, tr) in enumerate(truth.targets.items()):
            ax.plot(tr.east, tr.north, "--", color=COLORS["truth"], lw=1.2, zorder=2, label="ground truth" if j == 0 else None)
            start = (tr.east[0], tr.north[0])
            ax.annotate(name, start, fontsize=8, color=COLORS["truth"], xytext=(4, 4), textcoords="offset points")
            pts.append(np.column_stack([tr.east, tr.north]))
    allp = np.concatenate(pts)
    if len(allp):
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        pad = max(20.0, 0.1 * float(np.max(hi - lo)))
        extent = (lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad)
        if mask is not None:
            _land(ax, mask, extent)
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize=8)
    land = ", land grey" if mask is not None else ""
    ax.set_title(f"{title}\n{len(ids)} confirmed tracks{land}", fontsize=10)
    return to_png(fig)
