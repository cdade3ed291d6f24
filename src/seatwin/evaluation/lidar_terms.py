"""Lidar sensor-level terms: each truthed target's returns against ground truth, real versus synthetic, unpaired.

The tracker averages a cluster to a centroid, which hides most of what a lidar model gets wrong (range noise
below ~0.4 m does not move a track measurably). These terms look at the clusters themselves, ranged to the
ground truth (docs/fidelity-score.md, *Lidar sensor-level terms*). Per scan of a run and per truthed target
(:class:`LidarReturnSample`): every cluster whose centroid lies within :data:`LIDAR_RETURN_GATE_M` of the
target, and nearer to it than to any other vessel (truthed or don't-care), is part of the target's *return*;
the return's point count, and its horizontal spread along the line of sight (*depth*), across it (*width*)
and along its smallest principal axis (*thickness*), are taken from the clusters' pooled moments. The target
is *detected* when it has a return.

Terms (:func:`lidar_term_specs`), per range bin of the target (:data:`LIDAR_RANGE_EDGES_M`): detection
probability, and the mean points, depth, width and thickness of the returns; each shown as real, model and
signed difference with block-bootstrap intervals (:func:`seatwin.evaluation.plot_terms.signed_term`). For
the overall score (:func:`lidar_returns_score`) each term is also a distance in [0, 1] (Bernoulli Hellinger
for Pd; the Hellinger distance of 1-D Gaussians fitted to the log feature otherwise), and their weighted mean
(:data:`FAMILY_WEIGHTS`) is one plot-level part of S5.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial

import numpy as np
from numpy.typing import NDArray

from seatwin.evaluation.bootstrap import circular_block_indices, runs_block_length
from seatwin.evaluation.plot_terms import SignedTerm, TermSpec, equal_count_bins, signed_term
from seatwin.evaluation.score import ScoreOptions, ScoreValue, _refused, _replicates, _with_ci, in_window
from seatwin.evaluation.tracks_io import PlotLog, Tracks
from seatwin.evaluation.truth import TruthSet

LIDAR_RANGE_EDGES_M = (0.0, 25.0, 50.0, 100.0)
"""Range bins [m] of the target from the lidar; fixed before any result was seen: doubling widths out to the
VLP-16's 100 m (its ring spacing puts one ring on a 2 m hull near 50 m, so the point count changes regime there)."""
LIDAR_RETURN_GATE_M = 10.0
"""A cluster whose centroid is within this [m] of a target (and nearest to it) is part of its return: the
evaluation's lidar association gate; the scenarios' vessels are at most ~15 m long, so the centroid of any
visible part of the hull lies within it."""
SPREAD_FLOOR_M = 0.01
"""Added to a spread [m] before its logarithm (as the S6 shape term: a noiseless flat return has ~0 thickness)."""
FAMILY_WEIGHTS = {"pd": 0.2, "points": 0.2, "depth": 0.2, "width": 0.2, "thickness": 0.2}
"""Weight of each family of terms in the combined lidar distance, split equally over the family's defined range
bins; fixed before any result was seen: every family speaks about a different parameter (Pd: ray drop and
dissipation; points: ray drop, dissipation, beam layout; depth and thickness: range noise; width: angular
sampling and the beam model), and no family is known to matter more."""
FEATURES = ("points", "depth", "width", "thickness")


@dataclass(frozen=True)
class LidarReturnSample:
    """One run's returns from one truthed target, per lidar scan in time order."""

    target_range: NDArray[np.float64]
    """True range [m] of the target from the lidar (NaN outside the target's truth span)."""
    points: NDArray[np.float64]
    """Points in the target's return; 0 when it has none."""
    depth: NDArray[np.float64]
    """σ [m] of the return's points along the line of sight (lidar → return centroid); NaN without a return."""
    width: NDArray[np.float64]
    """σ [m] across the line of sight (horizontal); NaN without a return."""
    thickness: NDArray[np.float64]
    """σ [m] along the return's smallest principal axis; NaN without a return."""

    @property
    def detected(self) -> NDArray[np.float64]:
        """1.0 where the scan has a return from the target, 0.0 where not, NaN outside its truth span."""
        return np.where(np.isfinite(self.target_range), (self.points > 0).astype(float), np.nan)


def pooled_return(
    rows: NDArray[np.float64], centroids: NDArray[np.float64]
) -> tuple[float, NDArray[np.float64], NDArray[np.float64]]:
    """Point count, centroid and (population) covariance of the union of clusters ``rows`` (K, 4: count, nn, ne,
    ee) with centroids (K, 2): the parallel-axis sum of their moments."""
    n = rows[:, 0]
    total = float(n.sum())
    c = (n[:, None] * centroids).sum(axis=0) / total
    d = centroids - c
    cov = np.zeros((2, 2))
    cov[0, 0] = (n * (rows[:, 1] + d[:, 0] ** 2)).sum()
    cov[0, 1] = cov[1, 0] = (n * (rows[:, 2] + d[:, 0] * d[:, 1])).sum()
    cov[1, 1] = (n * (rows[:, 3] + d[:, 1] ** 2)).sum()
    return total, c, cov / total


def return_spreads(
    cov: NDArray[np.float64], centroid: NDArray[np.float64], sensor: NDArray[np.float64]
) -> tuple[float, float, float]:
    """Depth (σ along the line of sight ``sensor`` → ``centroid``), width (σ across it) and thickness (smallest
    principal σ) [m] of a horizontal covariance ``cov``."""
    los = centroid - sensor
    norm = float(np.hypot(los[0], los[1]))
    u = los / norm if norm > 0 else np.array([1.0, 0.0])
    v = np.array([-u[1], u[0]])
    ev = np.linalg.eigvalsh(cov)
    return (float(np.sqrt(max(u @ cov @ u, 0.0))), float(np.sqrt(max(v @ cov @ v, 0.0))), float(np.sqrt(max(ev[0], 0.0))))


def lidar_return_samples(
    plots: PlotLog,
    truth: TruthSet,
    dont_care: TruthSet | None = None,
    gate: float = LIDAR_RETURN_GATE_M,
    window: tuple[float, float] | None = None,
) -> dict[str, LidarReturnSample] | None:
    """Per truthed target, one run's :class:`LidarReturnSample` from its plot log (lidar scans within ``window``);
    None when the log keeps no cluster moments (a radar, a track file). Clusters nearer to a vessel of
    ``dont_care`` than to every target are nobody's return."""
    if plots.clusters is None or plots.sensor is None:
        return None
    scans = [k for k in np.flatnonzero(in_window(plots.times, window)) if plots.clusters[k] is not None]
    if not scans:
        return None
    t = plots.times[scans]
    names = list(truth.names)
    others = [] if dont_care is None else [n for n in dont_care.names if n not in truth.targets]
    vessel_pos = [truth[n].state_at(t)[:, [0, 2]] for n in names] + [dont_care[n].state_at(t)[:, [0, 2]] for n in others]  # type: ignore[index]
    pos = np.stack(vessel_pos, axis=1) if vessel_pos else np.zeros((len(t), 0, 2))
    sensor = plots.sensor[scans]
    out = {n: {f: np.full(len(t), np.nan) for f in ("target_range", *FEATURES)} for n in names}
    for j, n in enumerate(names):
        rel = pos[:, j] - sensor
        out[n]["target_range"] = np.hypot(rel[:, 0], rel[:, 1])
        out[n]["points"] = np.where(np.isfinite(pos[:, j, 0]), 0.0, np.nan)
    for i, k in enumerate(scans):
        rows = np.asarray(plots.clusters[k], float).reshape(-1, 4)  # type: ignore[index]
        cents = np.asarray(plots.positions[k], float).reshape(-1, 2)
        if not len(rows) or not len(names):
            continue
        d = np.hypot(cents[:, None, 0] - pos[i, None, :, 0], cents[:, None, 1] - pos[i, None, :, 1])
        d = np.where(np.isfinite(d), d, np.inf)
        near = d.argmin(axis=1)
        owned = d[np.arange(len(cents)), near] <= gate
        for j, n in enumerate(names):
            mine = owned & (near == j)
            if not mine.any():
                continue
            total, c, cov = pooled_return(rows[mine], cents[mine])
            depth, width, thick = return_spreads(cov, c, sensor[i])
            out[n]["points"][i], out[n]["depth"][i], out[n]["width"][i], out[n]["thickness"][i] = total, depth, width, thick
    return {n: LidarReturnSample(**v) for n, v in out.items()}


def _bin_mask(s: LidarReturnSample, lo: float, hi: float) -> NDArray[np.bool_]:
    r = np.nan_to_num(s.target_range, nan=-1.0)
    return (r >= lo) & (r < hi)


def _detected_in_bin(s: LidarReturnSample, *, lo: float, hi: float) -> NDArray[np.float64]:
    return np.where(_bin_mask(s, lo, hi), s.detected, np.nan)


def _feature_in_bin(s: LidarReturnSample, *, feature: str, lo: float, hi: float) -> NDArray[np.float64]:
    x = getattr(s, feature)
    return np.where(_bin_mask(s, lo, hi) & (s.points > 0), x, np.nan)


def _mean(x: NDArray[np.float64]) -> float:
    return float(np.mean(x))


_FEATURE_TEXT = {
    "points": ("points per return", "points", ("many", "few")),
    "depth": ("depth along the line of sight", "m", ("deep", "shallow")),
    "width": ("width across the line of sight", "m", ("wide", "narrow")),
    "thickness": ("thickness", "m", ("thick", "thin")),
}


def lidar_term_specs(range_edges: Sequence[float] = LIDAR_RANGE_EDGES_M) -> dict[str, TermSpec]:
    """The lidar sensor-level terms per range bin of ``range_edges``: ``pd_<lo>_<hi>m`` (share of scans with a
    return) and ``<feature>_<lo>_<hi>m`` (mean over the returns) for each of :data:`FEATURES`."""
    specs: dict[str, TermSpec] = {}
    for lo, hi in zip(range_edges[:-1], range_edges[1:]):
        tag = f"{lo:.0f}_{hi:.0f}m"
        specs[f"pd_{tag}"] = TermSpec(f"Pd {lo:.0f}–{hi:.0f} m", "", partial(_detected_in_bin, lo=lo, hi=hi), _mean)
        for f in FEATURES:
            label, unit, words = _FEATURE_TEXT[f]
            specs[f"{f}_{tag}"] = TermSpec(
                f"{label} {lo:.0f}–{hi:.0f} m", unit, partial(_feature_in_bin, feature=f, lo=lo, hi=hi), _mean, words
            )
    return specs


def flatten_samples(samples: Sequence[dict[str, LidarReturnSample]]) -> list[LidarReturnSample]:
    """Every (run, target) series: each is bootstrapped on its own, in blocks of scans."""
    return [s for run in samples for _, s in sorted(run.items())]


def term_series(
    flat: Sequence[LidarReturnSample], range_edges: Sequence[float] = LIDAR_RANGE_EDGES_M
) -> dict[str, list[NDArray[np.float64]]]:
    """Each term's values, one series per (run, target) series of ``flat`` — the input of :func:`combined_distance`."""
    return {k: [t.series(s) for s in flat] for k, t in lidar_term_specs(range_edges).items()}


def returns_block_length(flat: Sequence[LidarReturnSample]) -> int:
    """The lidar terms' bootstrap block length, chosen from the series' detection indicator and point count."""
    return runs_block_length([x for s in flat for x in (s.detected, s.points)])


def lidar_terms(
    real: Sequence[dict[str, LidarReturnSample]],
    synthetic: Sequence[dict[str, LidarReturnSample]],
    options: ScoreOptions | None = None,
    range_edges: Sequence[float] = LIDAR_RANGE_EDGES_M,
) -> dict[str, SignedTerm]:
    """Every lidar sensor-level term (:func:`lidar_term_specs`) of real runs against synthetic runs (each a dict
    target → :class:`LidarReturnSample`), one by one (:func:`seatwin.evaluation.plot_terms.signed_term`)."""
    o = options or ScoreOptions()
    rr, ss = flatten_samples(real), flatten_samples(synthetic)
    names_r, names_s = flatten_names(real), flatten_names(synthetic)
    out = {}
    for k, t in lidar_term_specs(range_edges).items():
        r, s = [t.series(x) for x in rr], [t.series(x) for x in ss]
        residuals = (time_design_residuals(r, names_r), time_design_residuals(s, names_s)) if o.lidar_design else None
        out[k] = signed_term(f"lidar {t.label}", t.unit, r, s, t.statistic, o, t.directions, residuals=residuals)
    return out


def flatten_names(samples: Sequence[dict[str, LidarReturnSample]]) -> list[str]:
    """The target of each series of :func:`flatten_samples`, in its order."""
    return [name for run in samples for name in sorted(run)]


def time_design_residuals(series: Sequence[NDArray[np.float64]], names: Sequence[str]) -> list[NDArray[np.float64]]:
    """Per (run, target) ``series`` of one term on one side, each of target ``names[i]``: the values less their mean
    over the side's series of that target in the same time bin (:func:`~seatwin.evaluation.plot_terms.equal_count_bins`
    of the scan index, √N bins), times the bins' dof factor; NaN where the term has none. Where the target is, and how
    it is turned, along the trajectory is what both sides share, not sampling variation (docs/fidelity-score.md,
    *Time design of the lidar terms*)."""
    out = [np.full(len(x), np.nan) for x in series]
    for name in dict.fromkeys(names):
        mine = [i for i, n in enumerate(names) if n == name]
        where = {i: np.flatnonzero(np.isfinite(series[i])) for i in mine}
        bins = equal_count_bins(
            np.concatenate([where[i] for i in mine]).astype(float), np.concatenate([series[i][where[i]] for i in mine])
        )
        for i in mine:
            out[i][where[i]] = (series[i][where[i]] - bins.expected(where[i])) * bins.dof
    return out


def bernoulli_hellinger(p: float, q: float) -> float:
    """Hellinger distance between Bernoulli(p) and Bernoulli(q)."""
    bc = np.sqrt(p * q) + np.sqrt((1.0 - p) * (1.0 - q))
    return float(np.sqrt(max(0.0, 1.0 - bc)))


def log_feature(feature: str, x: NDArray[np.float64]) -> NDArray[np.float64]:
    """The log scale a feature's distance is taken on: log count, log(σ + 1 cm)."""
    return np.log(x) if feature == "points" else np.log(x + SPREAD_FLOOR_M)


def gaussian_hellinger_1d(x: NDArray[np.float64], y: NDArray[np.float64], floor: float) -> float:
    """Hellinger distance between 1-D Gaussians fitted to ``x`` and ``y`` (mean; variance with ddof 1 plus
    ``floor``²) — :func:`seatwin.evaluation.score.error_hellinger` in one dimension, in closed form:
    ``H² = 1 − sqrt(2 σ_x σ_y / (σ_x² + σ_y²)) · exp(−(μ_x − μ_y)² / (4 (σ_x² + σ_y²)))``."""
    vx, vy = float(np.var(x, ddof=1)) + floor**2, float(np.var(y, ddof=1)) + floor**2
    d = float(np.mean(x) - np.mean(y))
    bc = np.sqrt(2.0 * np.sqrt(vx * vy) / (vx + vy)) * np.exp(-d * d / (4.0 * (vx + vy)))
    return float(np.sqrt(max(0.0, 1.0 - bc)))


def term_distance(key: str, real: NDArray[np.float64], synthetic: NDArray[np.float64]) -> float:
    """A term's distance in [0, 1] from each side's pooled finite values: Bernoulli Hellinger of the Pd, else the
    Hellinger distance of 1-D Gaussians fitted to the log feature (σ floor 0.01 in log units)."""
    family = key.split("_", 1)[0]
    if family == "pd":
        return bernoulli_hellinger(float(np.mean(real)), float(np.mean(synthetic)))
    return gaussian_hellinger_1d(log_feature(family, real), log_feature(family, synthetic), 0.01)


def _pool(series: Sequence[NDArray[np.float64]], idx: Sequence[NDArray[np.int64]] | None = None) -> NDArray[np.float64]:
    parts = [x if idx is None else x[i] for x, i in zip(series, idx or [None] * len(series))]
    x = np.concatenate(parts) if parts else np.empty(0)
    return x[np.isfinite(x)]


def combined_distance(
    real: dict[str, list[NDArray[np.float64]]],
    synthetic: dict[str, list[NDArray[np.float64]]],
    n_min: int,
    idx_r: Sequence[NDArray[np.int64]] | None = None,
    idx_s: Sequence[NDArray[np.int64]] | None = None,
) -> tuple[float, dict[str, float]]:
    """The weighted mean (:data:`FAMILY_WEIGHTS`, equal within a family) of the terms' distances that have at
    least ``n_min`` values on both sides, and each of those distances; NaN when none has."""
    d: dict[str, float] = {}
    for key in real:
        xr, xs = _pool(real[key], idx_r), _pool(synthetic[key], idx_s)
        if min(len(xr), len(xs)) >= n_min:
            d[key] = term_distance(key, xr, xs)
    if not d:
        return float("nan"), d
    # a dict, not a set: the families' order (and so the float sum below) must not depend on PYTHONHASHSEED,
    # or a Ray worker and the driver differ in the last digit
    fams = dict.fromkeys(k.split("_", 1)[0] for k in d)
    per_family = {f: [v for k, v in d.items() if k.split("_", 1)[0] == f] for f in fams}
    w = sum(FAMILY_WEIGHTS[f] for f in fams)
    return float(sum(FAMILY_WEIGHTS[f] * np.mean(v) for f, v in per_family.items()) / w), d


def lidar_returns_score(
    real: Sequence[dict[str, LidarReturnSample]],
    synthetic: Sequence[dict[str, LidarReturnSample]],
    options: ScoreOptions | None = None,
    range_edges: Sequence[float] = LIDAR_RANGE_EDGES_M,
) -> ScoreValue:
    """The combined lidar sensor-level distance (:func:`combined_distance`) with its block-bootstrap interval; the
    terms' distances are in ``counts`` (``d_<term>``). Bootstrap: circular blocks of scans within each (run,
    target) series, the block length chosen from the data (detection indicator and point count); every term of a
    replicate uses the same resample."""
    o = options or ScoreOptions()
    rr, ss = flatten_samples(real), flatten_samples(synthetic)
    if not rr or not ss:
        return _refused("no lidar returns (no truthed target, or not a lidar)")
    ser_r, ser_s = term_series(rr, range_edges), term_series(ss, range_edges)
    value, dist = combined_distance(ser_r, ser_s, o.n_min)
    counts: dict[str, float] = {"n_series_real": len(rr), "n_series_synthetic": len(ss)}
    counts |= {f"d_{k}": v for k, v in dist.items()}
    if not np.isfinite(value):
        return _refused(f"no lidar term has {o.n_min} values on both sides", **counts)
    block = o.block if o.block is not None else returns_block_length(rr + ss)
    counts["block"] = block
    reps = _replicates(
        o,
        "score/lidar_returns",
        _replicate_fn(ser_r, ser_s, [len(s.points) for s in rr], [len(s.points) for s in ss], block, o.n_min),
    )
    return _with_ci(value, reps, o.level, **counts)


def _replicate_fn(
    ser_r: dict[str, list[NDArray[np.float64]]],
    ser_s: dict[str, list[NDArray[np.float64]]],
    len_r: list[int],
    len_s: list[int],
    block: int,
    n_min: int,
) -> Callable[[np.random.Generator], float]:
    def replicate(rng: np.random.Generator) -> float:
        ir = [circular_block_indices(n, block, rng) for n in len_r]
        js = [circular_block_indices(n, block, rng) for n in len_s]
        return combined_distance(ser_r, ser_s, n_min, ir, js)[0]

    return replicate


def run_lidar_samples(
    tracks: Sequence[Tracks], truth: TruthSet, dont_care: TruthSet | None = None, window: tuple[float, float] | None = None
) -> list[dict[str, LidarReturnSample]] | None:
    """:func:`lidar_return_samples` of every run; None when any run keeps no lidar cluster moments."""
    out = []
    for tr in tracks:
        s = None if tr.plots is None else lidar_return_samples(tr.plots, truth, dont_care, window=window)
        if s is None:
            return None
        out.append(s)
    return out
