"""Radar plot-level terms: the sensor's own output against ground truth, real versus synthetic, unpaired.

The tracker blurs what a user tunes; these terms look at the plots themselves, so each speaks about one
model parameter and says in which direction it is off (docs/fidelity-score.md, *Plot-level terms*). Per
scan of a run (:class:`RadarPlotSample`): the plot nearest to the truthed target within the gate gives the
signed range error (plot range − true range, from the antenna) and bearing error (plot bearing − true
bearing, degrees, positive = clockwise seen from above); the target is detected when it has such a plot;
clutter plots are those farther than the gate from the target and from every don't-care vessel.

Each term (:class:`SignedTerm`) is a statistic of the pooled scans of each side — the real runs and the
synthetic runs (e.g. one per seed) — and their signed difference ``synthetic − real``, each with a
block-bootstrap percentile interval (blocks of scans within each run, their length chosen from the data:
:func:`seatwin.evaluation.bootstrap.runs_block_length`). A term is *resolved* when the interval of the
difference excludes 0.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from functools import partial

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.evaluation.bootstrap import (
    batch_means_inflation,
    circular_block_indices,
    long_memory_inflation,
    percentile_interval,
    runs_block_length,
)
from seatwin.evaluation.score import ScoreOptions, ScoreValue, clutter_mask, with_ci
from seatwin.evaluation.truth import TruthSet
from seatwin.rng import frame_rng

PD_RANGE_EDGES_M = (0.0, 250.0, 500.0, 1000.0, 1500.0, 2500.0)
"""Range bins [m] of the detection-probability and clutter terms; fixed before any result was seen (the radar's
near field, then doubling widths out to the default 2.5 km maximum range)."""

ASPECT_EDGES_DEG = (0.0, 45.0, 135.0, 180.0)
"""Aspect bins [deg] of the detection-probability terms (0 = the target's bow towards the radar): bow-on, beam,
stern-on; fixed before any result was seen."""
ASPECT_NAMES = ("bow", "beam", "stern")
MIN_SPEED_FOR_ASPECT = 0.5
"""[m/s] Below it the target's heading (from its truthed velocity) and so its aspect are undefined."""


@dataclass(frozen=True)
class RadarPlotSample:
    """One run's radar plots against the truthed target, per scan in time order."""

    target_range: NDArray[np.float64]
    """True range [m] of the target from the antenna."""
    range_error: NDArray[np.float64]
    """Plot range − true range [m] of the nearest plot within the gate; NaN when the scan has none."""
    bearing_error: NDArray[np.float64]
    """Plot bearing − true bearing [deg], wrapped to [−180, 180), positive clockwise; NaN when none."""
    clutter: NDArray[np.int64]
    """Plots farther than the gate from the target and from every don't-care vessel."""
    aspect: NDArray[np.float64] | None = None
    """Target aspect [deg, 0–180]: the angle between its heading and the line from it to the antenna (0 = bow-on);
    NaN where it is too slow for a heading; None: not known."""
    clutter_range: tuple[NDArray[np.float64], ...] | None = None
    """Per scan, the ranges [m] from the antenna of its clutter plots; None: not known."""

    @property
    def detected(self) -> NDArray[np.float64]:
        """1.0 where the scan has a plot of the target, 0.0 where not."""
        return np.isfinite(self.range_error).astype(float)


def wrap_deg(a: ArrayLike) -> NDArray[np.float64]:
    """Angles [deg] wrapped to [−180, 180)."""
    return (np.asarray(a, float) + 180.0) % 360.0 - 180.0


def radar_plot_sample(
    times: ArrayLike,
    antenna: ArrayLike,
    plots: Sequence[ArrayLike],
    truth: TruthSet,
    target: str,
    gate: float,
    dont_care: TruthSet | None = None,
) -> RadarPlotSample:
    """The per-scan sample of one run: scans at ``times`` (POSIX), antenna north/east ``antenna`` (n, 2), the
    scans' plots (north/east), the target ``target`` of ``truth``; clutter counted against every vessel of
    ``truth`` and ``dont_care`` (:func:`seatwin.evaluation.score.clutter_counts`)."""
    t = np.asarray(times, float)
    a = np.asarray(antenna, float).reshape(-1, 2)
    tgt = truth[target].state_at(t)[:, [0, 2]]
    n = len(t)
    r_err, b_err = np.full(n, np.nan), np.full(n, np.nan)
    rel_t = tgt - a
    rng_t = np.hypot(rel_t[:, 0], rel_t[:, 1])
    brg_t = np.degrees(np.arctan2(rel_t[:, 1], rel_t[:, 0]))
    vel = truth[target].state_at(t)[:, [1, 3]]
    heading = np.degrees(np.arctan2(vel[:, 1], vel[:, 0]))
    aspect = np.abs(wrap_deg(brg_t + 180.0 - heading))
    aspect[np.hypot(vel[:, 0], vel[:, 1]) < MIN_SPEED_FOR_ASPECT] = np.nan
    for k, p in enumerate(plots):
        p = np.asarray(p, float).reshape(-1, 2)
        if not len(p) or not np.isfinite(tgt[k, 0]):
            continue
        d = np.hypot(p[:, 0] - tgt[k, 0], p[:, 1] - tgt[k, 1])
        j = int(np.argmin(d))
        if d[j] <= gate:
            rel = p[j] - a[k]
            r_err[k] = np.hypot(rel[0], rel[1]) - rng_t[k]
            b_err[k] = wrap_deg(np.degrees(np.arctan2(rel[1], rel[0])) - brg_t[k])
    vessels = truth if dont_care is None else TruthSet({**truth.targets, **dont_care.targets}, truth.source)
    masks = clutter_mask(t, plots, vessels, gate)
    ranges = tuple(
        np.hypot(*(np.asarray(p, float).reshape(-1, 2)[m] - a[k]).T) if m.any() else np.empty(0)
        for k, (p, m) in enumerate(zip(plots, masks))
    )
    counts = np.array([int(m.sum()) for m in masks], dtype=np.int64)
    return RadarPlotSample(rng_t, r_err, b_err, counts, aspect, ranges)


@dataclass
class SignedTerm:
    """A plot-level statistic of each side and their signed difference (synthetic − real), with intervals."""

    name: str
    unit: str
    real: float | None
    synthetic: float | None
    difference: float | None
    real_ci: tuple[float, float] | None = None
    synthetic_ci: tuple[float, float] | None = None
    difference_ci: tuple[float, float] | None = None
    block: int = 1
    """Bootstrap block length [scans] chosen from the data."""
    directions: tuple[str, str] = ("high", "low")
    """What a positive and a negative difference mean (``model is … too <word>``)."""
    reason: str | None = None
    counts: dict[str, float] = field(default_factory=dict)
    difference_replicates: NDArray[np.float64] | None = field(default=None, repr=False)
    detectable: float | None = None
    """The smallest |difference| this data resolves at the interval's level with 80 % power
    (:func:`detectable_difference`): the term's resolution at the length at hand."""

    @property
    def resolved(self) -> bool:
        """The difference's interval excludes 0: the model is off in this term at the interval's level."""
        ci = self.difference_ci
        return ci is not None and (ci[0] > 0.0 or ci[1] < 0.0)

    def sentence(self) -> str:
        """E.g. ``bearing bias: real −1.80° [−2.1, −1.5], model −0.10° [..] → model is 1.70° too far clockwise (resolved)``."""
        if self.difference is None:
            return f"{self.name}: not computed ({self.reason})"
        d, u = self.difference, f" {self.unit}" if self.unit else ""
        word = self.directions[0] if d > 0 else self.directions[1]
        return (
            f"{self.name}: real {self.real:.3g} {_ci(self.real_ci)}, "
            f"model {self.synthetic:.3g} {_ci(self.synthetic_ci)}{u}"
            f" → model is {abs(d):.3g}{u} too {word}, difference {_ci(self.difference_ci)} "
            + ("(resolved)" if self.resolved else "(not resolved: the interval holds 0)")
            + ("" if self.detectable is None else f"; this data resolves ≥ {self.detectable:.2g}{u}")
        )

    def to_dict(self) -> dict:
        d = asdict(self)
        d.pop("difference_replicates")
        return d | {"resolved": self.resolved, "sentence": self.sentence()}


def _ci(ci: tuple[float, float] | None) -> str:
    return "[–]" if ci is None else f"[{ci[0]:.3g}, {ci[1]:.3g}]"


def _pooled(runs: Sequence[NDArray[np.float64]], idx: Sequence[NDArray[np.int64]] | None = None) -> NDArray[np.float64]:
    parts = [r if i is None else r[i] for r, i in zip(runs, idx or [None] * len(runs))]
    x = np.concatenate(parts) if parts else np.empty(0)
    return x[np.isfinite(x)]


def signed_term(
    name: str,
    unit: str,
    real: Sequence[ArrayLike],
    synthetic: Sequence[ArrayLike],
    statistic: Callable[[NDArray[np.float64]], float],
    options: ScoreOptions | None = None,
    directions: tuple[str, str] = ("high", "low"),
    scale: float = 1.0,
    residuals: tuple[Sequence[ArrayLike], Sequence[ArrayLike]] | None = None,
) -> SignedTerm:
    """``statistic`` of each side's pooled finite values (a series per run, one value per scan in time order, NaN
    where the scan has none), times ``scale``, and their difference, each with its block-bootstrap percentile
    interval (``options``: n_boot, level, seed, n_min). Refused when a side has fewer than ``n_min`` values.

    ``residuals`` (a mean only): (real, synthetic) series of the same shapes, the values less a pattern both sides
    share (:meth:`DetectionDesign.residuals`); the bootstrap then resamples them — their memory sets the block length and the
    long-memory inflation, and a side's replicate is its mean plus the resampled residuals' mean less theirs — so the
    shared pattern adds no spread. None: the values themselves."""
    o = options or ScoreOptions()
    rr = [np.asarray(r, float).reshape(-1) for r in real]
    ss = [np.asarray(s, float).reshape(-1) for s in synthetic]
    xr, xs = _pooled(rr), _pooled(ss)
    counts = {"n_real": len(xr), "n_synthetic": len(xs)}
    if min(len(xr), len(xs)) < o.n_min:
        reason = f"fewer than {o.n_min} values ({len(xr)} real, {len(xs)} synthetic)"
        return SignedTerm(name, unit, None, None, None, directions=directions, reason=reason, counts=counts)
    vr, vs = statistic(xr) * scale, statistic(xs) * scale
    if residuals is None:
        mr, ms = rr, ss
    else:
        mr, ms = ([np.asarray(m, float).reshape(-1) for m in side] for side in residuals)
        offsets = (vr - _pooled(mr).mean() * scale, vs - _pooled(ms).mean() * scale)
    block = runs_block_length(mr + ms)
    rng = frame_rng(o.seed, f"plot_terms/{name}", 0)
    reps = np.full((o.n_boot, 2), np.nan)
    means = np.full((o.n_boot, 2), np.nan)
    for b in range(o.n_boot):
        br = _pooled(mr, [circular_block_indices(len(r), block, rng) for r in mr])
        bs = _pooled(ms, [circular_block_indices(len(s), block, rng) for s in ms])
        if min(len(br), len(bs)) >= 2:
            if residuals is None:
                reps[b] = statistic(br) * scale, statistic(bs) * scale
            else:
                reps[b] = offsets[0] + br.mean() * scale, offsets[1] + bs.mean() * scale
            means[b] = br.mean(), bs.mean()
    if o.long_memory:  # widen each side's spread to its long-run variance (docs/fidelity-score.md, *Long memory*)
        for j, side in enumerate((mr, ms)):
            f = long_memory_inflation(side, means[:, j], o.level)
            if o.batch_floor and residuals is not None:
                f = max(f, batch_means_inflation(side, means[:, j], o.level))
            centre = float(np.nanmean(reps[:, j]))
            reps[:, j] = centre + f * (reps[:, j] - centre)
            counts[("memory_inflation_real", "memory_inflation_synthetic")[j]] = f
    diff = reps[:, 1] - reps[:, 0]
    return SignedTerm(
        name,
        unit,
        vr,
        vs,
        vs - vr,
        percentile_interval(reps[:, 0], o.level),
        percentile_interval(reps[:, 1], o.level),
        percentile_interval(diff, o.level),
        block,
        directions,
        None,
        counts,
        diff,
        detectable_difference(diff, o.level),
    )


DETECTION_POWER = 0.8
"""The power at which a term's resolution is stated (:func:`detectable_difference`)."""


def detectable_difference(replicates: ArrayLike, level: float = 0.95, power: float = DETECTION_POWER) -> float | None:
    """The minimum detectable difference of a signed term at the data at hand: ``(z_{(1+level)/2} + z_power) × SD``
    of the difference's bootstrap replicates — a true difference this large is resolved (interval excluding 0) with
    probability ``power`` (docs/fidelity-score.md, *Resolution at the data at hand*). None without two finite
    replicates."""
    from scipy.stats import norm

    x = np.asarray(replicates, float)
    x = x[np.isfinite(x)]
    if len(x) < 2:
        return None
    return float((norm.ppf(0.5 + level / 2) + norm.ppf(power)) * np.std(x, ddof=1))


def _mean(x: NDArray[np.float64]) -> float:
    return float(np.mean(x))


MAD_TO_SIGMA = 1.4826
"""σ of a normal distribution per median absolute deviation."""


def robust_sigma(x: NDArray[np.float64]) -> float:
    """σ from the median absolute deviation (× :data:`MAD_TO_SIGMA`): the gate admits the odd clutter plot
    (errors spread over the whole gate), which would decide a standard deviation and skew its bootstrap."""
    return float(MAD_TO_SIGMA * np.median(np.abs(x - np.median(x))))


CLIP_SIGMAS = 3.0
"""Errors farther than this many robust σ (:func:`robust_sigma`) from their median are left out of
:func:`clipped_mean` and :func:`clipped_sigma` (a clutter plot inside the gate, not noise)."""
CLIP_SIGMA_FACTOR = 0.98658
"""σ of a standard normal truncated to ±3 (:data:`CLIP_SIGMAS`): a clipped standard deviation divided by it is unbiased."""


def _clipped(x: NDArray[np.float64]) -> NDArray[np.float64]:
    s0 = robust_sigma(x)
    if s0 <= 0.0:
        return x
    return x[np.abs(x - np.median(x)) <= CLIP_SIGMAS * s0]


def clipped_mean(x: NDArray[np.float64]) -> float:
    """Mean of the errors within :data:`CLIP_SIGMAS` robust σ of their median: the bias, robust to clutter in the gate
    and nearly as efficient as the mean for Gaussian noise."""
    return float(np.mean(_clipped(x)))


def clipped_sigma(x: NDArray[np.float64]) -> float:
    """Standard deviation (ddof 1) of the errors within :data:`CLIP_SIGMAS` robust σ of their median, divided by
    :data:`CLIP_SIGMA_FACTOR`: robust to clutter in the gate, ~2.5 × as efficient as :func:`robust_sigma` for Gaussian noise."""
    y = _clipped(x)
    return float(np.std(y, ddof=1) / CLIP_SIGMA_FACTOR) if len(y) >= 2 else 0.0


def _in_bin(sample: RadarPlotSample, *, lo: float, hi: float) -> NDArray[np.float64]:
    return np.where((sample.target_range >= lo) & (sample.target_range < hi), sample.detected, np.nan)


def _in_aspect(sample: RadarPlotSample, *, lo: float, hi: float) -> NDArray[np.float64]:
    if sample.aspect is None:
        return np.full(len(sample.target_range), np.nan)
    a = sample.aspect
    inside = (a >= lo) & ((a < hi) | ((hi >= 180.0) & (a <= hi)))
    return np.where(inside, sample.detected, np.nan)


def clutter_in_annuli(sample: RadarPlotSample, edges: Sequence[float] = PD_RANGE_EDGES_M) -> NDArray[np.float64]:
    """(n_scans, n_annuli) clutter plots per scan in each range annulus ``[edges[i], edges[i+1])`` from the antenna;
    NaN when the sample does not know its clutter plots' ranges."""
    if sample.clutter_range is None:
        return np.full((len(sample.clutter), len(edges) - 1), np.nan)
    e = np.asarray(edges, float)
    return np.array([np.histogram(r, e)[0] for r in sample.clutter_range], dtype=float).reshape(-1, len(e) - 1)


def _clutter_in(sample: RadarPlotSample, *, i: int, edges: tuple[float, ...]) -> NDArray[np.float64]:
    return clutter_in_annuli(sample, edges)[:, i]


@dataclass(frozen=True)
class DetectionDesign:
    """What where the target was says of one side's detections: per run, each scan's expected detection — the side's
    detection share (its ``samples`` pooled) in the scan's range bin — and the factor √(N / (N − B)) that gives back
    the degrees of freedom the B shares take (docs/fidelity-score.md, *Design-adjusted memory*, second version). The
    bins hold equal numbers of the side's N scans, B = round(√N) of them. Where the target is — beyond the radar's
    range for a spell, near its minimum range for another — is the trajectory's, which both sides share: it is not
    memory, and adds no sampling spread."""

    expected: list[NDArray[np.float64]]
    dof: float

    def residuals(self, series: Sequence[NDArray[np.float64]]) -> list[NDArray[np.float64]]:
        """Each run's detection ``series`` (a term's 0/1 per scan, NaN where the term has none) less its expected
        detections, times :attr:`dof`: the series whose memory and spread a detection term's interval takes."""
        return [(np.asarray(x, float) - e) * self.dof for x, e in zip(series, self.expected, strict=True)]


@dataclass(frozen=True)
class EqualCountBins:
    """B = round(√N) bins holding equal numbers of N covariate values, the mean of the values in each, and the factor
    √(N / (N − B)) that gives back the degrees of freedom the B means take — a design's expected value by bin."""

    cuts: NDArray[np.float64]
    means: NDArray[np.float64]
    dof: float

    def expected(self, covariate: ArrayLike) -> NDArray[np.float64]:
        """The mean of the bin each of ``covariate`` falls in."""
        return self.means[np.searchsorted(self.cuts, np.asarray(covariate, float), side="right")]


def equal_count_bins(covariate: ArrayLike, values: ArrayLike) -> EqualCountBins:
    """The :class:`EqualCountBins` of ``values`` over ``covariate`` (same length, finite)."""
    c, x = np.asarray(covariate, float), np.asarray(values, float)
    n = len(c)
    n_bins = max(1, round(math.sqrt(n)))
    cuts = np.quantile(c, np.linspace(0.0, 1.0, n_bins + 1)[1:-1]) if n else np.empty(0)
    b = np.searchsorted(cuts, c, side="right")
    means = np.bincount(b, weights=x, minlength=n_bins) / np.maximum(np.bincount(b, minlength=n_bins), 1)
    return EqualCountBins(cuts, means, math.sqrt(n / (n - n_bins)) if n > n_bins else 1.0)


def detection_design(samples: Sequence[RadarPlotSample]) -> DetectionDesign:
    """The :class:`DetectionDesign` of one side's runs."""
    ranges = np.concatenate([s.target_range for s in samples]) if samples else np.empty(0)
    d = np.concatenate([s.detected for s in samples]) if samples else np.empty(0)
    bins = equal_count_bins(ranges, d)
    return DetectionDesign([bins.expected(s.target_range) for s in samples], bins.dof)


@dataclass(frozen=True)
class TermSpec:
    """How one radar plot-level term is computed from a :class:`RadarPlotSample`."""

    label: str
    unit: str
    series: Callable[[RadarPlotSample], NDArray[np.float64]]
    """Per scan, the value the statistic pools (NaN: the scan has none)."""
    statistic: Callable[[NDArray[np.float64]], float]
    directions: tuple[str, str] = ("high", "low")
    scale: float = 1.0
    detection: bool = False
    """A detection term (a mean of 0/1): its interval is the design-adjusted series' (:class:`DetectionDesign`)."""


def radar_term_specs(area_km2: float, range_edges: Sequence[float] = PD_RANGE_EDGES_M) -> dict[str, TermSpec]:
    """The radar plot-level terms: bearing and range bias (mean error), bearing and range σ (:func:`robust_sigma` of
    the error), detection probability over all of ``range_edges`` (``pd_all``: one number for the whole detection process,
    the term with the most scans), per range bin of ``range_edges`` and per aspect bin (:data:`ASPECT_EDGES_DEG`),
    clutter plots per scan and per km² (``area_km2``: the area the radar covers, the same for both sides) and per scan
    in each range annulus of ``range_edges``."""

    def clutter(s: RadarPlotSample) -> NDArray[np.float64]:
        return s.clutter.astype(float)

    specs = {
        "bearing_bias": TermSpec(
            "bearing bias", "°", lambda s: s.bearing_error, clipped_mean, ("far clockwise", "far anticlockwise")
        ),
        "range_bias": TermSpec("range bias", "m", lambda s: s.range_error, clipped_mean, ("far", "near")),
        "bearing_sigma": TermSpec("bearing σ", "°", lambda s: s.bearing_error, clipped_sigma, ("wide", "narrow")),
        "range_sigma": TermSpec("range σ", "m", lambda s: s.range_error, clipped_sigma, ("wide", "narrow")),
    }
    lo_all, hi_all = float(range_edges[0]), float(range_edges[-1])
    specs["pd_all"] = TermSpec(
        f"Pd {lo_all:.0f}–{hi_all:.0f} m (all)", "", partial(_in_bin, lo=lo_all, hi=hi_all), _mean, detection=True
    )
    for lo, hi in zip(range_edges[:-1], range_edges[1:]):
        specs[f"pd_{lo:.0f}_{hi:.0f}m"] = TermSpec(
            f"Pd {lo:.0f}–{hi:.0f} m", "", partial(_in_bin, lo=lo, hi=hi), _mean, detection=True
        )
    for name, lo, hi in zip(ASPECT_NAMES, ASPECT_EDGES_DEG[:-1], ASPECT_EDGES_DEG[1:]):
        specs[f"pd_aspect_{name}"] = TermSpec(
            f"Pd {name} aspect ({lo:.0f}–{hi:.0f}°)", "", partial(_in_aspect, lo=lo, hi=hi), _mean, detection=True
        )
    specs["clutter_per_scan"] = TermSpec("clutter per scan", "plots", clutter, _mean, ("dense", "sparse"))
    specs["clutter_per_km2"] = TermSpec("clutter density", "plots/km²/scan", clutter, _mean, ("dense", "sparse"), 1.0 / area_km2)
    edges = tuple(float(x) for x in range_edges)
    for i, (lo, hi) in enumerate(zip(edges[:-1], edges[1:])):
        specs[f"clutter_{lo:.0f}_{hi:.0f}m"] = TermSpec(
            f"clutter {lo:.0f}–{hi:.0f} m", "plots/scan", partial(_clutter_in, i=i, edges=edges), _mean, ("dense", "sparse")
        )
    return specs


def radar_plot_terms(
    real: Sequence[RadarPlotSample],
    synthetic: Sequence[RadarPlotSample],
    area_km2: float,
    options: ScoreOptions | None = None,
    range_edges: Sequence[float] = PD_RANGE_EDGES_M,
) -> dict[str, SignedTerm]:
    """Every radar plot-level term (:func:`radar_term_specs`) of real runs against synthetic runs (:func:`signed_term`);
    the detection terms' memory design-adjusted (:class:`DetectionDesign`, once per side) unless
    ``options.design_memory`` is off."""
    o = options or ScoreOptions()
    designs = (detection_design(real), detection_design(synthetic)) if o.design_memory else None
    out = {}
    for k, t in radar_term_specs(area_km2, range_edges).items():
        r, s = [t.series(x) for x in real], [t.series(x) for x in synthetic]
        residuals = None
        if t.detection and designs is not None:
            residuals = (designs[0].residuals(r), designs[1].residuals(s))
        out[k] = signed_term(t.label, t.unit, r, s, t.statistic, o, t.directions, t.scale, residuals)
    return out


@dataclass
class Lead:
    """How much closer model A's statistic is to the real one than model B's: ``|B − real| − |A − real|``
    (positive: A is closer), with a bootstrap interval that resamples the real runs once for both models."""

    name: str
    unit: str
    value: float | None
    ci: tuple[float, float] | None = None
    reason: str | None = None

    @property
    def resolved(self) -> bool:
        """A is closer to the real value than B, at the interval's level (the interval is above 0)."""
        return self.ci is not None and self.ci[0] > 0.0

    def to_dict(self) -> dict:
        return asdict(self) | {"resolved": self.resolved}


def lead(
    spec: TermSpec,
    real: Sequence[RadarPlotSample],
    model_a: Sequence[RadarPlotSample],
    model_b: Sequence[RadarPlotSample],
    options: ScoreOptions | None = None,
) -> Lead:
    """The :class:`Lead` of model A over model B in the term ``spec``."""
    o = options or ScoreOptions()
    sides = [[np.asarray(spec.series(s), float) for s in side] for side in (real, model_a, model_b)]
    pooled = [_pooled(side) for side in sides]
    if min(map(len, pooled)) < o.n_min:
        return Lead(spec.label, spec.unit, None, reason=f"fewer than {o.n_min} values ({', '.join(str(len(p)) for p in pooled)})")
    block = runs_block_length([r for side in sides for r in side])
    rng = frame_rng(o.seed, f"plot_terms/lead/{spec.label}", 0)

    def gap(vals: list[float]) -> float:
        return abs(vals[2] - vals[0]) - abs(vals[1] - vals[0])

    reps = np.full(o.n_boot, np.nan)
    for b in range(o.n_boot):
        boot = [_pooled(side, [circular_block_indices(len(r), block, rng) for r in side]) for side in sides]
        if min(map(len, boot)) >= 2:
            reps[b] = gap([spec.statistic(x) * spec.scale for x in boot])
    value = gap([spec.statistic(x) * spec.scale for x in pooled])
    return Lead(spec.label, spec.unit, value, percentile_interval(reps, o.level))


# --- The radar sensor score: the plot-level terms as distances on one scale, combined with fixed weights ---

RADAR_SENSOR_WEIGHTS = {"bearing": 1.0, "range": 1.0, "detection": 1.0, "clutter": 1.0}
"""Weights of the radar sensor score's parts (docs/fidelity-score.md, *Radar sensor score*), fixed before any result:
every part is a Hellinger distance (one scale: H² = 1 − Bhattacharyya coefficient) between the distributions of one
independent part of the radar's output — bearing noise, range noise, the detection process, the clutter process —
so each counts once."""
SIGMA_FLOOR = {"bearing": 1e-3, "range": 1e-2}
"""σ floors [deg, m] of the error Gaussians: keep a (near-)noiseless side's Gaussian proper."""


def gaussian_hellinger_1d(m1: float, s1: float, m2: float, s2: float) -> float:
    """Hellinger distance between N(m1, s1²) and N(m2, s2²):
    ``H² = 1 − √(2 s1 s2 / (s1² + s2²)) exp(−(m1 − m2)² / (4 (s1² + s2²)))``."""
    v = s1 * s1 + s2 * s2
    bc = np.sqrt(2.0 * s1 * s2 / v) * np.exp(-((m1 - m2) ** 2) / (4.0 * v))
    return float(np.sqrt(max(0.0, 1.0 - bc)))


@dataclass(frozen=True)
class _Arrays:
    """One run's per-scan arrays the sensor score resamples (rows = scans)."""

    bearing: NDArray[np.float64]
    range: NDArray[np.float64]
    detected: NDArray[np.float64]
    cell: NDArray[np.int64]
    """Detection cell (range bin × aspect bin) of the scan; −1 outside every bin."""
    clutter: NDArray[np.float64]
    """(n, annuli) clutter plots per scan per range annulus."""

    def take(self, idx: NDArray[np.int64]) -> _Arrays:
        return _Arrays(self.bearing[idx], self.range[idx], self.detected[idx], self.cell[idx], self.clutter[idx])


def _arrays(s: RadarPlotSample, range_edges: Sequence[float], aspect_edges: Sequence[float]) -> _Arrays:
    r_bin = np.digitize(s.target_range, range_edges) - 1
    r_bin[(r_bin < 0) | (r_bin >= len(range_edges) - 1) | ~np.isfinite(s.target_range)] = -1
    n_asp = len(aspect_edges) - 1
    if s.aspect is None:
        a_bin = np.zeros(len(r_bin), dtype=np.int64)
    else:
        a_bin = np.clip(np.digitize(s.aspect, aspect_edges) - 1, 0, n_asp - 1)
        a_bin[~np.isfinite(s.aspect)] = -1
    cell = np.where((r_bin >= 0) & (a_bin >= 0), r_bin * n_asp + a_bin, -1).astype(np.int64)
    clutter = clutter_in_annuli(s, range_edges)
    if not np.isfinite(clutter).all():  # ranges unknown: one annulus holding every clutter plot
        clutter = s.clutter.astype(float)[:, None]
    return _Arrays(s.bearing_error, s.range_error, s.detected, cell, clutter)


def _cat(runs: Sequence[_Arrays]) -> _Arrays:
    return _Arrays(*(np.concatenate([getattr(r, f) for r in runs]) for f in ("bearing", "range", "detected", "cell", "clutter")))


def _error_part(xr: NDArray[np.float64], xs: NDArray[np.float64], floor: float, n_min: int) -> float:
    xr, xs = xr[np.isfinite(xr)], xs[np.isfinite(xs)]
    if min(len(xr), len(xs)) < max(2, n_min):
        return np.nan
    return gaussian_hellinger_1d(clipped_mean(xr), max(clipped_sigma(xr), floor), clipped_mean(xs), max(clipped_sigma(xs), floor))


def _detection_part(r: _Arrays, s: _Arrays, cells: NDArray[np.int64]) -> float:
    """H² = 1 − Σ_c w_c BC_c over the detection cells ``cells``: the Hellinger distance between the joint distributions
    of (cell, detected) when both sides share the cells' weights ``w_c`` (the mean of the two sides' shares)."""
    h2, wsum = 0.0, 0.0
    for c in cells:
        dr, ds = r.detected[r.cell == c], s.detected[s.cell == c]
        if not len(dr) or not len(ds):
            continue
        w = 0.5 * (len(dr) / max(1, int((r.cell >= 0).sum())) + len(ds) / max(1, int((s.cell >= 0).sum())))
        pr, ps = float(dr.mean()), float(ds.mean())
        h2 += w * (1.0 - np.sqrt(pr * ps) - np.sqrt((1.0 - pr) * (1.0 - ps)))
        wsum += w
    return float(np.sqrt(max(0.0, h2 / wsum))) if wsum > 0 else np.nan


def _clutter_part(r: _Arrays, s: _Arrays) -> float:
    """Hellinger distance between the clutter processes as independent Poisson counts per scan per annulus:
    ``H² = 1 − exp(−½ Σ_a (√λ_r,a − √λ_s,a)²)`` (one annulus: S4's Poisson distance)."""
    if not len(r.clutter) or not len(s.clutter):
        return np.nan
    d = np.sqrt(r.clutter.mean(axis=0)) - np.sqrt(s.clutter.mean(axis=0))
    return float(np.sqrt(-np.expm1(-0.5 * float(d @ d))))


def _parts(r: _Arrays, s: _Arrays, cells: NDArray[np.int64], n_min: int) -> dict[str, float]:
    return {
        "bearing": _error_part(r.bearing, s.bearing, SIGMA_FLOOR["bearing"], n_min),
        "range": _error_part(r.range, s.range, SIGMA_FLOOR["range"], n_min),
        "detection": _detection_part(r, s, cells),
        "clutter": _clutter_part(r, s),
    }


def weighted_combine(parts: dict[str, float], weights: dict[str, float]) -> float:
    """``1 − Π (1 − H_i)^(w_i)`` over the finite parts (:func:`seatwin.evaluation.score.combine` with weights)."""
    used = [(v, weights[k]) for k, v in parts.items() if np.isfinite(v)]
    if not used:
        return np.nan
    return float(1.0 - np.prod([(1.0 - min(v, 1.0)) ** w for v, w in used]))


@dataclass
class SensorScore:
    """The radar sensor score: the weighted combination of its parts, each a distance with its interval."""

    overall: ScoreValue
    parts: dict[str, ScoreValue]
    weights: dict[str, float]
    block: int

    def to_dict(self) -> dict:
        return {
            "score": self.overall.to_dict(),
            "parts": {k: v.to_dict() for k, v in self.parts.items()},
            "weights": self.weights,
            "block": self.block,
        }


def _detection_cells(r: _Arrays, s: _Arrays, n_min: int) -> NDArray[np.int64]:
    """The cells with at least ``n_min`` scans on both sides (fixed from the data before resampling)."""
    cells = np.union1d(r.cell[r.cell >= 0], s.cell[s.cell >= 0])
    return np.array([c for c in cells if min((r.cell == c).sum(), (s.cell == c).sum()) >= n_min], dtype=np.int64)


def _prepared(runs: Sequence[RadarPlotSample], range_edges: Sequence[float], aspect_edges: Sequence[float]) -> list[_Arrays]:
    return [_arrays(x, range_edges, aspect_edges) for x in runs]


def sensor_block_length(runs: Sequence[_Arrays]) -> int:
    """The joint bootstrap's block length: the longest :func:`runs_block_length` of the series behind every part
    (bearing and range error, detection, clutter per scan)."""
    series = [x for r in runs for x in (r.bearing, r.range, r.detected, r.clutter.sum(axis=1))]
    return runs_block_length(series)


def radar_sensor_score(
    real: Sequence[RadarPlotSample],
    synthetic: Sequence[RadarPlotSample],
    options: ScoreOptions | None = None,
    weights: dict[str, float] | None = None,
    range_edges: Sequence[float] = PD_RANGE_EDGES_M,
    aspect_edges: Sequence[float] = ASPECT_EDGES_DEG,
) -> SensorScore:
    """The radar sensor score of synthetic runs against real runs (docs/fidelity-score.md, *Radar sensor score*):
    per part a Hellinger distance — bearing and range error (Gaussians from mean and :func:`robust_sigma`), detection
    (Bernoulli per range × aspect cell with ≥ ``n_min`` scans on both sides, the cells' shares shared), clutter
    (Poisson per scan per range annulus) — and their :func:`weighted_combine` (``weights``, default
    :data:`RADAR_SENSOR_WEIGHTS`). One joint circular block bootstrap over scans within each run (block length from
    the data, :func:`sensor_block_length`) gives every part's and the overall interval (bias-shifted,
    :func:`seatwin.evaluation.score.with_ci`). A part with too few values on a side is refused, left out and named."""
    o = options or ScoreOptions()
    w = dict(RADAR_SENSOR_WEIGHTS if weights is None else weights)
    rr, ss = _prepared(real, range_edges, aspect_edges), _prepared(synthetic, range_edges, aspect_edges)
    r_all, s_all = _cat(rr), _cat(ss)
    cells = _detection_cells(r_all, s_all, o.n_min)
    value = _parts(r_all, s_all, cells, o.n_min)
    block = sensor_block_length(rr + ss)
    rng = frame_rng(o.seed, "plot_terms/sensor", 0)
    reps = {k: np.full(o.n_boot, np.nan) for k in value}
    overall_reps = np.full(o.n_boot, np.nan)
    for b in range(o.n_boot):
        br = _cat([r.take(circular_block_indices(len(r.detected), block, rng)) for r in rr])
        bs = _cat([x.take(circular_block_indices(len(x.detected), block, rng)) for x in ss])
        p = _parts(br, bs, cells, 2)
        for k in p:
            reps[k][b] = p[k] if np.isfinite(value[k]) else np.nan
        overall_reps[b] = weighted_combine({k: p[k] for k in p if np.isfinite(value[k])}, w)
    reasons = {
        "bearing": f"fewer than {o.n_min} target plots on a side",
        "range": f"fewer than {o.n_min} target plots on a side",
        "detection": f"no range × aspect cell with {o.n_min} scans on both sides",
        "clutter": "no scans",
    }
    parts = {
        k: with_ci(v, reps[k], o.level, weight=w[k]) if np.isfinite(v) else ScoreValue(None, reason=reasons[k])
        for k, v in value.items()
    }
    total = weighted_combine(value, w)
    counts = {
        "n_scans_real": len(r_all.detected),
        "n_scans_synthetic": len(s_all.detected),
        "detection_cells": len(cells),
    }
    if not np.isfinite(total):
        return SensorScore(ScoreValue(None, reason="no part defined", counts=counts), parts, w, block)
    overall = with_ci(total, overall_reps, o.level, **counts)
    left_out = [k for k, v in parts.items() if v.value is None]
    if left_out:
        overall.reason = "without " + "; ".join(f"{k}: {parts[k].reason}" for k in left_out)
    return SensorScore(overall, parts, w, block)


def sensor_lead(
    real: Sequence[RadarPlotSample],
    model_a: Sequence[RadarPlotSample],
    model_b: Sequence[RadarPlotSample],
    options: ScoreOptions | None = None,
    weights: dict[str, float] | None = None,
) -> Lead:
    """How much lower (better) model A's radar sensor score is than model B's, ``S(B) − S(A)``, with a bootstrap
    interval that resamples the real runs once for both models (:class:`Lead`: resolved when above 0)."""
    o = options or ScoreOptions()
    w = dict(RADAR_SENSOR_WEIGHTS if weights is None else weights)
    sides = [_prepared(x, PD_RANGE_EDGES_M, ASPECT_EDGES_DEG) for x in (real, model_a, model_b)]
    r, a, b = (_cat(x) for x in sides)
    cells = np.intersect1d(_detection_cells(r, a, o.n_min), _detection_cells(r, b, o.n_min))

    def gap(r_: _Arrays, a_: _Arrays, b_: _Arrays, n_min: int) -> float:
        return weighted_combine(_parts(r_, b_, cells, n_min), w) - weighted_combine(_parts(r_, a_, cells, n_min), w)

    value = gap(r, a, b, o.n_min)
    if not np.isfinite(value):
        return Lead("radar sensor score", "", None, reason="no part defined")
    block = sensor_block_length([x for side in sides for x in side])
    rng = frame_rng(o.seed, "plot_terms/sensor_lead", 0)
    reps = np.array(
        [
            gap(*(_cat([x.take(circular_block_indices(len(x.detected), block, rng)) for x in side]) for side in sides), 2)
            for _ in range(o.n_boot)
        ]
    )
    return Lead("radar sensor score", "", value, percentile_interval(reps, o.level))
