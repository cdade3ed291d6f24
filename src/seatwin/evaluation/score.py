"""An unpaired fidelity score: how far a synthetic dataset's *error distributions* are from the real one's.

Why not AHED alone (docs/fidelity-score.md has the derivation): AHED pairs the real and the
synthetic estimate instant by instant. Their noise is independent, so the paired distance has a
floor that shrinks when the synthetic sensor is *less* noisy than reality — a too-clean model
scores better than a faithful one. This score compares distributions instead, and never pairs
instants, so the two datasets need not share draws, seeds or even scan times.

Per target (S1–S3), over the truth-defined instants of a window, pooled over a dataset's runs
(the synthetic seeds):

* (S1) ``H = HED(N(ē_r, Σ_r), N(ē_s, Σ_s))``: the Hellinger distance (5.30, standard form) between
  Gaussians fitted to the tracker's position errors ``e = estimate − truth`` (north, east) of the
  real and of the synthetic runs;
* (S2) the coverage term ``|c_r − c_s|``, ``c`` = share of the instants with an associated track;
* (S3) ``S = 1 − (1 − H)(1 − |c_r − c_s|)``: 0 when both agree, 1 when either term is 1.

Plot level (what no track-level score sees, e.g. clutter the tracker rejects), per dataset a
Poisson rate per scan: clutter plots, and false tracks alive (per scan, not per run: a per-run
count compared between single runs has a sampling floor H ≈ 0.47 whatever its size):

* (S4) ``H²(λ_r, λ_s) = 1 − exp(−(√λ_r − √λ_s)² / 2)``: the Hellinger distance between two
  Poisson distributions;
* (S6) cluster shape: HED between Gaussians fitted to the lidar clusters' (log point count,
  log thickness) — what range noise, ray drop and dissipation change long before the tracks do.

:mod:`seatwin.evaluation.sensor_score` builds on this module: false tracks each counted once, per minute
(S4b, replacing the per-scan count here), and the lidar sensor-level terms (S7).

Overall (S5): ``S = 1 − (1 − S̄)(1 − H_clutter)(1 − H_false)(1 − H_shape)(1 − H_lidar)``, ``S̄`` the mean of the
defined target scores; terms that are undefined (no plots given, e.g. track files; no lidar
clusters) are left out and named.

Every value comes with a circular block bootstrap interval (blocks of consecutive instants or
scans within each run) and the numbers behind
it. A value is *refused* — None, with the reason — when too few instants support it.
Intervals are bias-shifted (see :func:`_with_ci`). The target terms with ≥ 2 synthetic runs take their interval
from the runs' spread instead (:mod:`seatwin.evaluation.run_spread`; a tracker behaves differently from run to run,
which no within-run resampling sees), with a test-inverted lower bound (``ScoreValue.null_replicates``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.evaluation.bootstrap import circular_block_indices, percentile_interval, runs_block_length
from seatwin.evaluation.evaluate import Evaluation, TargetSeries
from seatwin.evaluation.hellinger import hellinger
from seatwin.evaluation.run_spread import (
    GAUSSIAN_PARAMS,
    RunSpread,
    gaussian_from_params,
    gaussian_params,
    run_effects,
    run_spread,
    t_scales,
)
from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet
from seatwin.rng import frame_rng

ERROR_FLOOR_M = 0.01
"""σ floor [m] added to fitted error covariances: keeps a (near-)noiseless run's Gaussian proper."""


@dataclass(frozen=True)
class ScoreOptions:
    """Conventions of the score (documented in docs/fidelity-score.md)."""

    n_min: int = 10
    """Fewest instants with a track, per dataset, behind an error distribution (else refused)."""
    n_boot: int = 200
    block: int | None = None
    """Bootstrap block length [instants or scans]; None (default): chosen per term from its series
    (:func:`seatwin.evaluation.bootstrap.runs_block_length`, Politis–White)."""
    level: float = 0.95
    seed: int = 0
    run_spread: bool = True
    """Target terms (S1–S3): add the run-to-run spread of the synthetic runs (≥ 2) to the within-run bootstrap
    (:mod:`seatwin.evaluation.run_spread`; docs/fidelity-score.md, *Run-to-run spread*). False: within-run only."""
    long_memory: bool = True
    """Signed plot-level terms: widen each side's block-bootstrap spread to the long-run variance from the series'
    integrated autocorrelation time when that is larger, with a Student-t factor on the effective number of values
    (:func:`seatwin.evaluation.bootstrap.long_memory_inflation`; docs/fidelity-score.md, *Long memory*). False: the
    block bootstrap alone."""
    design_memory: bool = True
    """Radar detection terms: their block length and long-memory inflation from the detections less the side's
    detection share in the scan's range bin — the range pattern a trajectory imposes is not memory
    (:func:`seatwin.evaluation.plot_terms.DetectionDesign`; docs/fidelity-score.md, *Design-adjusted memory*).
    False: from the detections themselves."""
    batch_floor: bool = True
    """Radar detection terms (with ``design_memory``): widen each side's spread to at least what 4 batch means give
    (:func:`seatwin.evaluation.bootstrap.batch_means_inflation`; docs/fidelity-score.md, *Batch-means floor*) — for a
    Pd that drifts in slow spells. On by default since evaluation 13 (the full controlled check with it: true model
    first in 58 of 60 new recordings, Pd ∓ 0.2 resolved in 57 and 58 of 60); False: the bootstrap and the long-memory
    factor alone (a little more power for a Pd known to be stationary)."""
    lidar_design: bool = False
    """Lidar signed terms: their block length, long-memory inflation and replicates from the values less their bin
    mean over the scenario's time (√N equal-count bins of scan index, per side and target) — the range and aspect
    pattern a trajectory imposes on a return is not sampling variation
    (:func:`seatwin.evaluation.lidar_terms.time_design_residuals`; docs/fidelity-score.md, *Time design of the lidar
    terms*). Off until its evaluation (14) has run."""
    clutter_gate: float = 25.0
    """A plot or confirmed track farther than this [m] from every target is clutter or a false track
    (vessels are up to ~30 m long; a radar's plots scatter further: the joyride method uses 60 m)."""


def in_window(times: ArrayLike, window: tuple[float, float] | None) -> NDArray[np.bool_]:
    """Which ``times`` (POSIX) lie in ``window`` (inclusive, 1 ns slack); all of them when ``window`` is None."""
    t = np.asarray(times, float)
    if window is None:
        return np.ones(t.shape, bool)
    return (t >= window[0] - 1e-9) & (t <= window[1] + 1e-9)


@dataclass(frozen=True)
class TargetErrors:
    """One run's view of one target: position error [m] (north, east) per truth-defined instant, NaN without a track."""

    error: NDArray[np.float64]

    @classmethod
    def from_series(cls, series: TargetSeries, window: tuple[float, float] | None = None) -> TargetErrors:
        """The errors of an evaluated target (:class:`TargetSeries`), optionally within ``window`` (POSIX, inclusive)."""
        keep = np.isfinite(series.truth[:, 0]) & in_window(series.time, window)
        e = series.state[:, [0, 2]] - series.truth[:, [0, 2]]
        e[~series.valid] = np.nan
        return cls(e[keep])


def gaussian_fit(errors: ArrayLike, floor: float = ERROR_FLOOR_M) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Mean and covariance (ddof 1, plus ``floor``² I) of (n, d) error samples, n ≥ 2."""
    e = np.asarray(errors, float)
    return e.mean(axis=0), np.cov(e, rowvar=False, ddof=1).reshape(e.shape[1], e.shape[1]) + floor**2 * np.eye(e.shape[1])


def error_hellinger(real: ArrayLike, synthetic: ArrayLike, floor: float = ERROR_FLOOR_M) -> float:
    """(S1) HED (5.30, standard form) between Gaussians fitted to the real and the synthetic errors."""
    mr, pr = gaussian_fit(real, floor)
    ms, ps = gaussian_fit(synthetic, floor)
    return float(hellinger(ms, ps, mr, pr, "standard"))


def error_hellinger_floor(n_real: int, n_synthetic: int, dim: int = 2) -> float:
    """(S1') The distance (S1) expected from sampling alone when both error sets come from one Gaussian:
    ``H² ≈ k/8 · (1/n_r + 1/n_s)``, ``k = d + d(d+1)/2`` fitted parameters (H² ≈ δθᵀ I δθ / 8 for
    small parameter errors δθ, Fisher information I). Counts independent instants: with autocorrelated
    tracker errors the real floor is higher."""
    k = dim + dim * (dim + 1) // 2
    return float(np.sqrt(k / 8.0 * (1.0 / n_real + 1.0 / n_synthetic)))


def combine(*terms: float) -> float:
    """(S3, S5) ``1 − Π(1 − tᵢ)`` of distances in [0, 1]: 0 only when every term is 0, 1 when any is 1."""
    return float(1.0 - np.prod([1.0 - t for t in terms]))


def poisson_hellinger(rate_real: float, rate_synthetic: float) -> float:
    """(S4) Hellinger distance between Poisson(λ_r) and Poisson(λ_s): ``sqrt(1 − exp(−(√λ_r − √λ_s)²/2))``."""
    d = np.sqrt(rate_real) - np.sqrt(rate_synthetic)
    return float(np.sqrt(-np.expm1(-0.5 * d * d)))


@dataclass
class ScoreValue:
    """A score term: its value (None when refused, with ``reason``), bootstrap interval and the numbers behind it."""

    value: float | None
    ci_low: float | None = None
    ci_high: float | None = None
    reason: str | None = None
    counts: dict[str, float] = field(default_factory=dict)
    replicates: NDArray[np.float64] | None = field(default=None, repr=False)
    null_replicates: NDArray[np.float64] | None = field(default=None, repr=False)
    """Replicates of the distance two datasets of one model would show (run-to-run spread; None: not drawn)."""

    def to_dict(self) -> dict:
        d = asdict(self)
        d.pop("replicates")
        d.pop("null_replicates")
        return d


def _refused(reason: str, **counts: float) -> ScoreValue:
    return ScoreValue(None, reason=reason, counts=dict(counts))


def _with_ci(
    value: float, replicates: NDArray[np.float64], level: float, nulls: NDArray[np.float64] | None = None, **counts: float
) -> ScoreValue:
    """``value`` with the bias-shifted percentile interval of its bootstrap ``replicates``.

    A distance is biased upwards by sampling noise, and a bootstrap replicate (noise on noise) twice
    over: the replicates' percentile interval is shifted down by the bootstrap's own bias estimate
    (mean replicate − value), clipped to [0, 1] and widened to hold the value. With ``nulls`` (replicates of the
    distance between two datasets of one model) the lower bound is instead the test-inverted one,
    ``max(0, value − q_level(nulls))``: 0 exactly when the value is within what one model gives ``level`` of the time."""
    ci = percentile_interval(replicates, level)
    if ci is None:
        return ScoreValue(value, None, None, None, dict(counts), replicates, nulls)
    bias = float(np.mean(replicates[np.isfinite(replicates)])) - value
    lo, hi = (float(np.clip(c - bias, 0.0, 1.0)) for c in ci)
    if nulls is not None and np.isfinite(nulls).any():
        q = float(np.quantile(nulls[np.isfinite(nulls)], level))
        lo = max(0.0, value - q)
        counts = {**counts, "null_quantile": q}
    return ScoreValue(value, min(lo, value), max(hi, value), None, dict(counts), replicates, nulls)


with_ci = _with_ci
"""Public name of :func:`_with_ci`, for score terms defined in other modules (e.g. the radar sensor score)."""


def _replicates(o: ScoreOptions, stream: str, replicate: Callable[[np.random.Generator], float]) -> NDArray[np.float64]:
    """``o.n_boot`` bootstrap replicates, each ``replicate(rng)``, drawn from the stream ``stream`` under ``o.seed``."""
    rng = frame_rng(o.seed, stream, 0)
    return np.array([replicate(rng) for _ in range(o.n_boot)], dtype=float)


def _block(o: ScoreOptions, series: Sequence[ArrayLike]) -> int:
    """The bootstrap block length of a term: ``o.block``, or chosen from the term's ``series`` (one per run) when None."""
    return o.block if o.block is not None else runs_block_length(series)


def _pool(runs: Sequence[TargetErrors], idx: Sequence[NDArray[np.int64]] | None = None) -> tuple[NDArray[np.float64], int]:
    """Errors at the instants with a track, pooled over runs (resampled at ``idx`` per run), and the instant count."""
    parts = [r.error if idx is None else r.error[i] for r, i in zip(runs, idx or [None] * len(runs))]
    e = np.concatenate(parts) if parts else np.empty((0, 2))
    return e[np.isfinite(e[:, 0])], len(e)


def _target_value(real: tuple[NDArray[np.float64], int], synth: tuple[NDArray[np.float64], int]) -> float:
    (er, nr), (es, ns) = real, synth
    c_r, c_s = len(er) / nr, len(es) / ns
    h = 1.0 if min(len(er), len(es)) < 2 else error_hellinger(er, es)
    return combine(h, abs(c_r - c_s))


_Stats = tuple[NDArray[np.float64] | None, float]
"""One side's (or run's) target statistic: its error Gaussian's parameters (None below 2 tracked instants) and coverage."""


def _stats(pooled: tuple[NDArray[np.float64], int]) -> _Stats:
    errors, instants = pooled
    return (gaussian_params(*gaussian_fit(errors)) if len(errors) >= 2 else None), len(errors) / instants


def _stats_value(real: _Stats, synthetic: _Stats) -> float:
    """(S3) from both sides' statistics (:func:`_target_value` on the fitted Gaussians)."""
    (pr, cr), (ps, cs) = real, synthetic
    h = 1.0
    if pr is not None and ps is not None:
        (mr, cov_r), (ms, cov_s) = gaussian_from_params(pr), gaussian_from_params(ps)
        h = float(hellinger(ms, cov_s, mr, cov_r, "standard"))
    return combine(h, abs(cr - cs))


def _side_effects(
    spread: RunSpread | None, n_real: int, n: int, dim: int, rng: np.random.Generator
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``n`` run effects for the real side (``n_real`` runs pooled) and the synthetic side (``spread.runs`` runs),
    sharing one t-factor per replicate; zeros without a spread."""
    if spread is None:
        return np.zeros((n, dim)), np.zeros((n, dim))
    u = t_scales(spread.dof, n, rng)
    return run_effects(spread, 1 / np.sqrt(n_real), u, rng), run_effects(spread, 1 / np.sqrt(spread.runs), u, rng)


def _run_spread_replicates(
    real: Sequence[TargetErrors], synthetic: Sequence[TargetErrors], o: ScoreOptions, stream: str
) -> tuple[NDArray[np.float64], NDArray[np.float64], dict[str, float]]:
    """Replicates and null replicates of (S3) from the run-to-run spread of the K ≥ 2 synthetic runs
    (docs/fidelity-score.md, *Run-to-run spread*).

    Each run's statistic — its error Gaussian's parameters (runs with ≥ ``n_min`` tracked instants) and its coverage —
    is one draw of what a run of the model gives; their sample covariance (ddof 1) estimates the sampling covariance
    of one run's statistic, within-run noise and run-level tracker events together. A replicate adds to each side's
    statistic a run effect with that covariance (scaled 1/√R for the R real runs pooled, 1/√K for the K synthetic
    runs) times a Student-t factor (ν = K − 1: the covariance is itself estimated from K runs); a *null* replicate
    adds the same effects to the synthetic statistic on both sides — the distance two datasets of one model would
    show. The real side borrows the model's spread: under the hypothesis that the model is right, its runs vary as
    the model's do."""
    per_run = [_stats(_pool([s])) for s in synthetic]
    tracked = [np.isfinite(s.error[:, 0]).sum() for s in synthetic]
    gauss = [p for (p, _), m in zip(per_run, tracked) if p is not None and m >= o.n_min]
    cover = [c for (_, c), s in zip(per_run, synthetic) if len(s.error)]
    g_spread = run_spread(np.array(gauss)) if len(gauss) >= 2 else None
    c_spread = run_spread(np.array(cover)[:, None]) if len(cover) >= 2 else None
    n_real = max(1, sum(1 for r in real if len(r.error)))
    rng = frame_rng(o.seed, f"score/target-runs/{stream}", 0)
    g_r, g_s = _side_effects(g_spread, n_real, o.n_boot, 5, rng)
    c_r, c_s = _side_effects(c_spread, n_real, o.n_boot, 1, rng)
    at_r, at_s = _stats(_pool(real)), _stats(_pool(synthetic))

    def moved(st: _Stats, dg: NDArray[np.float64], dc: NDArray[np.float64]) -> _Stats:
        return (None if st[0] is None else st[0] + dg), float(np.clip(st[1] + dc[0], 0.0, 1.0))

    reps = np.array([_stats_value(moved(at_r, g_r[b], c_r[b]), moved(at_s, g_s[b], c_s[b])) for b in range(o.n_boot)])
    null_r = (at_s[0] if at_r[0] is not None else None, at_s[1])  # the real side at the model's statistic
    nulls = np.array([_stats_value(moved(null_r, g_r[b], c_r[b]), moved(at_s, g_s[b], c_s[b])) for b in range(o.n_boot)])
    counts: dict[str, float] = {"between_runs": 0 if g_spread is None else g_spread.runs}
    if g_spread is not None:
        counts |= {f"between_sd_{n}": float(v) for n, v in zip(GAUSSIAN_PARAMS, g_spread.sd)}
    if c_spread is not None:
        counts["between_sd_coverage"] = float(c_spread.sd[0])
    return reps, nulls, counts


def target_score(
    real: Sequence[TargetErrors], synthetic: Sequence[TargetErrors], options: ScoreOptions | None = None, stream: str = ""
) -> ScoreValue:
    """(S1–S3) The score of one target from its real runs and its synthetic runs (pooled; e.g. one per seed).

    Refused when both sides have fewer than ``n_min`` instants with a track. When only one side has
    (and the truth has at least ``n_min`` instants), that side's error distribution cannot be
    estimated while the other's can: the target is as good as never tracked there — total
    disagreement, S = 1 (``counts.one_sided``)."""
    o = options or ScoreOptions()
    er, nr = _pool(real)
    es, ns = _pool(synthetic)
    counts = {"n_real": len(er), "n_synthetic": len(es), "instants_real": nr, "instants_synthetic": ns}
    if nr == 0 or ns == 0:
        return _refused("no ground-truth instants in the window", **counts)
    if not len(er) and not len(es):
        return _refused("neither dataset tracked the target", **counts)
    if max(len(er), len(es)) < o.n_min or min(nr, ns) < o.n_min:
        return _refused(f"fewer than {o.n_min} instants with a track ({len(er)} real, {len(es)} synthetic)", **counts)
    if min(len(er), len(es)) < o.n_min:
        return ScoreValue(1.0, 1.0, 1.0, None, counts | {"one_sided": True}, np.ones(o.n_boot))
    value = _target_value((er, nr), (es, ns))
    # Block length from the errors' components and the track indicator, each run a series (NaN: no track).
    nulls = None
    if o.run_spread and sum(np.isfinite(s.error[:, 0]).sum() >= o.n_min for s in synthetic) >= 2:
        reps, nulls, spread_counts = _run_spread_replicates(real, synthetic, o, stream)
        counts |= spread_counts
    else:
        block = _block(o, [x for r in [*real, *synthetic] for x in (r.error[:, 0], r.error[:, 1], np.isfinite(r.error[:, 0]))])
        reps = _replicates(
            o,
            f"score/target/{stream}",
            lambda rng: _target_value(
                _pool(real, [circular_block_indices(len(r.error), block, rng) for r in real]),
                _pool(synthetic, [circular_block_indices(len(s.error), block, rng) for s in synthetic]),
            ),
        )
        counts["between_runs"] = 0
    counts |= {"coverage_real": len(er) / nr, "coverage_synthetic": len(es) / ns}
    if min(len(er), len(es)) >= 2:
        counts["error_hellinger"] = error_hellinger(er, es)
        counts["error_hellinger_floor"] = error_hellinger_floor(len(er), len(es))
    return _with_ci(value, reps, o.level, nulls, **counts)


def rate_score(
    real: Sequence[ArrayLike], synthetic: Sequence[ArrayLike], options: ScoreOptions | None = None, stream: str = ""
) -> ScoreValue:
    """(S4) Poisson Hellinger distance of per-scan counts (e.g. clutter plots per scan), one array per run
    in time order; bootstrap: circular blocks of consecutive scans within each run."""
    o = options or ScoreOptions()
    rr = [np.asarray(c, float) for c in real if len(c)]
    ss = [np.asarray(c, float) for c in synthetic if len(c)]
    n_r, n_s = sum(map(len, rr)), sum(map(len, ss))
    if n_r < o.n_min or n_s < o.n_min:
        return _refused(f"fewer than {o.n_min} scans ({n_r} real, {n_s} synthetic)", n_scans_real=n_r)

    def rate(parts: list[NDArray[np.float64]], idx: list[NDArray[np.int64]] | None = None) -> float:
        tot = sum(float(p.sum() if idx is None else p[i].sum()) for p, i in zip(parts, idx or [None] * len(parts)))
        return tot / sum(map(len, parts))

    lam_r, lam_s = rate(rr), rate(ss)
    block = _block(o, rr + ss)
    reps = _replicates(
        o,
        f"score/rate/{stream}",
        lambda rng: poisson_hellinger(
            rate(rr, [circular_block_indices(len(p), block, rng) for p in rr]),
            rate(ss, [circular_block_indices(len(p), block, rng) for p in ss]),
        ),
    )
    counts = {"rate_real_per_scan": lam_r, "rate_synthetic_per_scan": lam_s, "n_scans_real": n_r, "n_scans_synthetic": n_s}
    return _with_ci(poisson_hellinger(lam_r, lam_s), reps, o.level, **counts)


def shape_score(
    real: Sequence[Sequence[ArrayLike]], synthetic: Sequence[Sequence[ArrayLike]], options: ScoreOptions | None = None
) -> ScoreValue:
    """(S6) Hellinger distance between Gaussians fitted to the plots' shape features (lidar clusters: log point
    count, log thickness; :func:`seatwin.perception.lidar.cluster_shape_features`), pooled over scans and runs;
    ``real``/``synthetic``: per run, per scan in time order, an (M, 2) array. Bootstrap: blocks of scans."""
    o = options or ScoreOptions()
    rr = [[np.asarray(f, float).reshape(-1, 2) for f in run] for run in real]
    ss = [[np.asarray(f, float).reshape(-1, 2) for f in run] for run in synthetic]

    def pool(runs: list[list[NDArray[np.float64]]], idx: list[NDArray[np.int64]] | None = None) -> NDArray[np.float64]:
        parts = [f for k, run in enumerate(runs) for f in (run if idx is None else [run[i] for i in idx[k]])]
        return np.concatenate(parts) if parts else np.zeros((0, 2))

    fr, fs = pool(rr), pool(ss)
    counts = {"n_plots_real": len(fr), "n_plots_synthetic": len(fs)}
    if not len(fr) and not len(fs):
        return _refused("no cluster shapes (not a lidar)", **counts)
    if min(len(fr), len(fs)) < o.n_min:
        return _refused(f"fewer than {o.n_min} plots with a shape ({len(fr)} real, {len(fs)} synthetic)", **counts)

    # Block length from each run's per-scan mean features (NaN for a scan without clusters).
    block = _block(o, [[f[:, j].mean() if len(f) else np.nan for f in run] for run in rr + ss for j in range(2)])

    def replicate(rng: np.random.Generator) -> float:
        br = pool(rr, [circular_block_indices(len(run), block, rng) for run in rr])
        bs = pool(ss, [circular_block_indices(len(run), block, rng) for run in ss])
        return error_hellinger(br, bs, 0.0) if min(len(br), len(bs)) >= 2 else np.nan

    reps = _replicates(o, "score/shape", replicate)
    counts |= {"mean_real": fr.mean(axis=0).tolist(), "mean_synthetic": fs.mean(axis=0).tolist()}  # type: ignore[dict-item]
    return _with_ci(error_hellinger(fr, fs, 0.0), reps, o.level, **counts)


@dataclass
class FidelityScore:
    """(S5) The overall score and its parts."""

    overall: ScoreValue
    targets: dict[str, ScoreValue]
    plots: dict[str, ScoreValue]
    """Plot-level terms by name: ``clutter``, ``false_tracks``, ``shape`` (and ``lidar_returns``:
    :mod:`seatwin.evaluation.sensor_score`); sensor scores (:func:`with_sensor_score`)."""
    not_combined: dict[str, str] = field(default_factory=dict)
    """Plot-level terms reported but left out of the overall score, with why (measured inside a sensor score)."""

    def to_dict(self) -> dict:
        out = {
            "score": self.overall.to_dict(),
            "targets": {k: v.to_dict() for k, v in self.targets.items()},
            **{k: v.to_dict() for k, v in self.plots.items()},
        }
        return out | ({"not_combined": dict(self.not_combined)} if self.not_combined else {})


def _null_part(v: ScoreValue) -> NDArray[np.float64]:
    """A part's null replicates for S5's test-inverted lower bound: its own, else ``clip(replicate − value, 0, 1)``."""
    if v.null_replicates is not None:
        return v.null_replicates
    return np.clip(np.asarray(v.replicates, float) - float(v.value), 0.0, 1.0)  # type: ignore[arg-type]


def overall_score(
    targets: dict[str, ScoreValue], plots: dict[str, ScoreValue], options: ScoreOptions | None = None
) -> ScoreValue:
    """(S5) ``1 − (1 − S̄) Π(1 − H_plot)`` over the defined parts (S̄: mean target score; plot terms: clutter,
    false tracks, cluster shape); its interval from the parts' bootstrap replicates taken together
    (replicate b of every part)."""
    o = options or ScoreOptions()
    defined = [v for v in targets.values() if v.value is not None]
    if not defined:
        reasons = "; ".join(f"{k}: {v.reason}" for k, v in targets.items()) or "no targets"
        return _refused(f"no target score is defined ({reasons})")
    used = [v for v in plots.values() if v.value is not None]
    mean_t = float(np.mean([v.value for v in defined]))
    value = combine(mean_t, *(v.value for v in used))
    parts = [np.mean([v.replicates for v in defined], axis=0), *(v.replicates for v in used)]
    reps = np.array([combine(*(p[b] for p in parts)) for b in range(o.n_boot)])
    counts = {"n_targets": len(defined), "n_targets_refused": len(targets) - len(defined), "targets_mean": mean_t}
    nulls = None
    if any(v.null_replicates is not None for v in defined):
        # What one model gives: each target's null replicates; a part without them, its replicates' excess over its
        # value (the bootstrap's image of the distance sampling adds, as in the bias shift).
        null = [np.mean([_null_part(v) for v in defined], axis=0), *(_null_part(v) for v in used)]
        nulls = np.array([combine(*(p[b] for p in null)) for b in range(o.n_boot)])
    out = _with_ci(value, reps, o.level, nulls, **counts)
    left_out = [k for k, v in plots.items() if v.value is None]
    if left_out:
        out.reason = "without " + "; ".join(f"{k}: {plots[k].reason}" for k in left_out)
    return out


def with_sensor_score(
    score: FidelityScore, name: str, sensor: ScoreValue, replaces: Sequence[str] = (), options: ScoreOptions | None = None
) -> FidelityScore:
    """(S5 with a sensor score) ``score`` with the sensor-level score ``sensor`` (e.g. the radar sensor score,
    :func:`seatwin.evaluation.plot_terms.radar_sensor_score`, weight 1) as one more factor of the overall score; the
    plot terms ``replaces`` (measured again inside it, e.g. S4's clutter rate) are still reported but not combined,
    so nothing counts twice. ``sensor``'s replicates must come from ``options.n_boot`` resamples like the others'."""
    plots = {**score.plots, name: sensor}
    combined = {k: v for k, v in plots.items() if k not in replaces and k not in score.not_combined}
    why = {k: f"measured inside {name}" for k in replaces if k in plots}
    return FidelityScore(overall_score(score.targets, combined, options), score.targets, plots, {**score.not_combined, **why})


def _plot_window(tr: Tracks, window: tuple[float, float] | None) -> NDArray[np.int64]:
    return np.flatnonzero(in_window(tr.plots.times, window))  # type: ignore[union-attr]


def run_shapes(tracks: Sequence[Tracks], window: tuple[float, float] | None = None) -> list[list[NDArray[np.float64]]] | None:
    """Per run, the plots' shape features of each scan (within ``window``); None if any run has no plot log."""
    if any(tr.plots is None or tr.plots.shapes is None for tr in tracks):
        return None
    return [[tr.plots.shapes[i] for i in _plot_window(tr, window)] for tr in tracks]  # type: ignore[union-attr,index]


def run_clutter(
    tracks: Sequence[Tracks], truth: TruthSet, gate: float, window: tuple[float, float] | None = None
) -> list[NDArray[np.int64]] | None:
    """Per run, the clutter count of each scan (:func:`clutter_counts`) from the runs' plot logs; None if any run has none."""
    out = []
    for tr in tracks:
        if tr.plots is None:
            return None
        idx = _plot_window(tr, window)
        out.append(clutter_counts(tr.plots.times[idx], [tr.plots.positions[i] for i in idx], truth, gate))
    return out


def run_far_tracks(
    tracks: Sequence[Tracks], truth: TruthSet, gate: float, window: tuple[float, float] | None = None
) -> list[NDArray[np.int64]]:
    """Per run, at each of its scan instants (within ``window``), the confirmed tracks farther than ``gate`` [m]
    from every target: false tracks by the same rule as clutter plots (a track of a target that is merely
    poor, beyond the evaluation's association gate, is not one)."""
    out = []
    for tr in tracks:
        times = tr.scan_times[in_window(tr.scan_times, window)]
        conf = tr.confirmed
        at = np.searchsorted(tr.time[conf], times, side="left"), np.searchsorted(tr.time[conf], times, side="right")
        pos = tr.state[conf][:, [0, 2]]
        out.append(clutter_counts(times, [pos[a:b] for a, b in zip(*at)], truth, gate))
    return out


NO_PLOTS = "no plots (track files carry none)"


def score_runs(
    real: Sequence[Tracks],
    synthetic: Sequence[Tracks],
    truth: TruthSet,
    real_evaluations: Sequence[Evaluation],
    synthetic_evaluations: Sequence[Evaluation],
    options: ScoreOptions | None = None,
    window: tuple[float, float] | None = None,
    dont_care: TruthSet | None = None,
) -> FidelityScore:
    """The score of synthetic runs (e.g. one per seed) against real runs, within ``window`` when given:
    the target terms from the runs' evaluations against ``truth``, the plot terms from their tracks and
    plot logs (:func:`run_clutter`, :func:`run_far_tracks`, :func:`run_shapes`; a run without a plot log,
    e.g. read from a track file, leaves the clutter and shape terms refused). Plots and tracks near a vessel of
    ``dont_care`` (vessels without ground truth, e.g. followed by the real tracker) are neither clutter nor false
    tracks: they are not scored at all (a "don't care" region that moves with the vessel)."""
    o = options or ScoreOptions()
    vessels = truth if dont_care is None else TruthSet({**truth.targets, **dont_care.targets}, truth.source)
    names = [s.target for s in real_evaluations[0].summaries] if real_evaluations else []
    targets = {
        name: target_score(
            [TargetErrors.from_series(e.series[name], window) for e in real_evaluations],
            [TargetErrors.from_series(e.series[name], window) for e in synthetic_evaluations],
            o,
            stream=name,
        )
        for name in names
    }
    clutter_r, clutter_s = (
        run_clutter(real, vessels, o.clutter_gate, window),
        run_clutter(synthetic, vessels, o.clutter_gate, window),
    )
    shapes_r, shapes_s = run_shapes(real, window), run_shapes(synthetic, window)
    plots = {
        "clutter": _refused(NO_PLOTS)
        if clutter_r is None or clutter_s is None
        else rate_score(clutter_r, clutter_s, o, stream="clutter"),
        "false_tracks": rate_score(
            run_far_tracks(real, vessels, o.clutter_gate, window),
            run_far_tracks(synthetic, vessels, o.clutter_gate, window),
            o,
            stream="false_tracks",
        ),
        "shape": _refused(NO_PLOTS) if shapes_r is None or shapes_s is None else shape_score(shapes_r, shapes_s, o),
    }
    return FidelityScore(overall_score(targets, plots, o), targets, plots)


def clutter_mask(times: ArrayLike, plots: Sequence[ArrayLike], truth: TruthSet, gate: float) -> list[NDArray[np.bool_]]:
    """Per scan (at ``times``, POSIX), which plots (north/east) lie farther than ``gate`` [m] from every target of ``truth``."""
    tt = np.asarray(times, float)
    targets = np.stack([truth[n].state_at(tt)[:, [0, 2]] for n in truth.names], axis=1) if truth.names else None
    out = []
    for k, p in enumerate(plots):
        p = np.asarray(p, float).reshape(-1, 2)
        t = np.empty((0, 2)) if targets is None else targets[k][np.isfinite(targets[k][:, 0])]
        if len(p) and len(t):
            out.append(np.hypot(p[:, None, 0] - t[None, :, 0], p[:, None, 1] - t[None, :, 1]).min(axis=1) > gate)
        else:
            out.append(np.ones(len(p), bool))
    return out


def clutter_counts(times: ArrayLike, plots: Sequence[ArrayLike], truth: TruthSet, gate: float) -> NDArray[np.int64]:
    """Per scan (at ``times``, POSIX), the plots (north/east) farther than ``gate`` [m] from every target of ``truth``."""
    return np.array([int(m.sum()) for m in clutter_mask(times, plots, truth, gate)], dtype=np.int64)
