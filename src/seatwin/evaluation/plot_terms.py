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

from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from functools import partial

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.evaluation.bootstrap import circular_block_indices, percentile_interval, runs_block_length
from seatwin.evaluation.score import ScoreOptions, clutter_counts
from seatwin.evaluation.truth import TruthSet
from seatwin.rng import frame_rng

PD_RANGE_EDGES_M = (0.0, 250.0, 500.0, 1000.0, 1500.0, 2500.0)
"""Range bins [m] of the detection-probability terms; fixed before any result was seen (the radar's
near field, then doubling widths out to the default 2.5 km maximum range)."""


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
    return RadarPlotSample(rng_t, r_err, b_err, clutter_counts(t, plots, vessels, gate))


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
) -> SignedTerm:
    """``statistic`` of each side's pooled finite values (a series per run, one value per scan in time order, NaN
    where the scan has none), times ``scale``, and their difference, each with its block-bootstrap percentile
    interval (``options``: n_boot, level, seed, n_min). Refused when a side has fewer than ``n_min`` values."""
    o = options or ScoreOptions()
    rr = [np.asarray(r, float).reshape(-1) for r in real]
    ss = [np.asarray(s, float).reshape(-1) for s in synthetic]
    xr, xs = _pooled(rr), _pooled(ss)
    counts = {"n_real": len(xr), "n_synthetic": len(xs)}
    if min(len(xr), len(xs)) < o.n_min:
        reason = f"fewer than {o.n_min} values ({len(xr)} real, {len(xs)} synthetic)"
        return SignedTerm(name, unit, None, None, None, directions=directions, reason=reason, counts=counts)
    block = runs_block_length(rr + ss)
    rng = frame_rng(o.seed, f"plot_terms/{name}", 0)
    reps = np.full((o.n_boot, 2), np.nan)
    for b in range(o.n_boot):
        br = _pooled(rr, [circular_block_indices(len(r), block, rng) for r in rr])
        bs = _pooled(ss, [circular_block_indices(len(s), block, rng) for s in ss])
        if min(len(br), len(bs)) >= 2:
            reps[b] = statistic(br) * scale, statistic(bs) * scale
    vr, vs = statistic(xr) * scale, statistic(xs) * scale
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
    )


def _mean(x: NDArray[np.float64]) -> float:
    return float(np.mean(x))


MAD_TO_SIGMA = 1.4826
"""σ of a normal distribution per median absolute deviation."""


def robust_sigma(x: NDArray[np.float64]) -> float:
    """σ from the median absolute deviation (× :data:`MAD_TO_SIGMA`): the gate admits the odd clutter plot
    (errors spread over the whole gate), which would decide a standard deviation and skew its bootstrap."""
    return float(MAD_TO_SIGMA * np.median(np.abs(x - np.median(x))))


def _in_bin(sample: RadarPlotSample, *, lo: float, hi: float) -> NDArray[np.float64]:
    return np.where((sample.target_range >= lo) & (sample.target_range < hi), sample.detected, np.nan)


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


def radar_term_specs(area_km2: float, range_edges: Sequence[float] = PD_RANGE_EDGES_M) -> dict[str, TermSpec]:
    """The radar plot-level terms: bearing and range bias (mean error), bearing and range σ (:func:`robust_sigma` of
    the error), detection probability per range bin of ``range_edges``, clutter plots per scan and per km²
    (``area_km2``: the area the radar covers, the same for both sides)."""

    def clutter(s: RadarPlotSample) -> NDArray[np.float64]:
        return s.clutter.astype(float)

    specs = {
        "bearing_bias": TermSpec("bearing bias", "°", lambda s: s.bearing_error, _mean, ("far clockwise", "far anticlockwise")),
        "range_bias": TermSpec("range bias", "m", lambda s: s.range_error, _mean, ("far", "near")),
        "bearing_sigma": TermSpec("bearing σ", "°", lambda s: s.bearing_error, robust_sigma, ("wide", "narrow")),
        "range_sigma": TermSpec("range σ", "m", lambda s: s.range_error, robust_sigma, ("wide", "narrow")),
    }
    for lo, hi in zip(range_edges[:-1], range_edges[1:]):
        specs[f"pd_{lo:.0f}_{hi:.0f}m"] = TermSpec(f"Pd {lo:.0f}–{hi:.0f} m", "", partial(_in_bin, lo=lo, hi=hi), _mean)
    specs["clutter_per_scan"] = TermSpec("clutter per scan", "plots", clutter, _mean, ("dense", "sparse"))
    specs["clutter_per_km2"] = TermSpec("clutter density", "plots/km²/scan", clutter, _mean, ("dense", "sparse"), 1.0 / area_km2)
    return specs


def radar_plot_terms(
    real: Sequence[RadarPlotSample],
    synthetic: Sequence[RadarPlotSample],
    area_km2: float,
    options: ScoreOptions | None = None,
    range_edges: Sequence[float] = PD_RANGE_EDGES_M,
) -> dict[str, SignedTerm]:
    """Every radar plot-level term (:func:`radar_term_specs`) of real runs against synthetic runs (:func:`signed_term`)."""
    return {
        k: signed_term(
            t.label,
            t.unit,
            [t.series(s) for s in real],
            [t.series(s) for s in synthetic],
            t.statistic,
            options,
            t.directions,
            t.scale,
        )
        for k, t in radar_term_specs(area_km2, range_edges).items()
    }


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
