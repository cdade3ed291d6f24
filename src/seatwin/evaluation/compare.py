"""Compare a real and a synthetic tracker run (thesis 5.2.1): per target, HED (5.30) over time and AHED (5.34).

Each run is first associated with the same ground truth (5.1.4), so "the target" is the
track each dataset's tracker has on that vessel. The two runs' instants are matched in time
(mutual nearest neighbours within ``time_tolerance``); at an instant where both have the
target, HED and COVDIFF (5.31) of their Gaussians are computed. Conventions, all explicit:

* AHED averages HED over the *common* instants (the thesis's choice: "only considering the
  occasions where there are common ground between the datasets").
* ``both_missing`` — instants (inside the truth's span) where neither dataset has the target:
  ``"skip"`` (default): always skipped, so a target without common instants has AHED
  *undefined* (None) and is left out of every mean, whose target count is stated;
  ``"never"`` (the thesis's scenario 7): skipped, except that a target neither dataset ever
  tracked gets AHED 0 ("full agreement"); ``"zero"``: each such instant counts as HED 0.
* AHED cannot see track loss, so the instants where only one dataset has the target are
  reported beside it (counts and the fraction of the instants where either has it).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import ParameterError
from seatwin.evaluation.association import DEFAULT_GATE_M
from seatwin.evaluation.evaluate import Evaluation, evaluate
from seatwin.evaluation.hellinger import FORMS, HellingerForm, covdiff, hellinger
from seatwin.evaluation.metrics import rms
from seatwin.evaluation.score import FidelityScore, ScoreOptions
from seatwin.evaluation.sensor_score import score_runs_with_sensor_terms
from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet

BothMissing = Literal["never", "zero", "skip"]
BOTH_MISSING: tuple[str, ...] = ("never", "zero", "skip")
DEFAULT_TIME_TOLERANCE_S = 0.05


@dataclass(frozen=True)
class CompareOptions:
    """Every convention of the comparison (see the module docstring)."""

    gate: float = DEFAULT_GATE_M
    confirmed_only: bool = True
    time_tolerance: float = DEFAULT_TIME_TOLERANCE_S
    form: HellingerForm = "standard"
    both_missing: BothMissing = "skip"
    confidence: float = 0.95
    score: ScoreOptions | None = field(default_factory=ScoreOptions)
    """Conventions of the unpaired fidelity score (:mod:`seatwin.evaluation.score`); None: not computed
    (its bootstrap is most of a comparison's cost, wasted where only HED/AHED are used)."""

    def __post_init__(self) -> None:
        if self.form not in FORMS:
            raise ParameterError("form", f"expected one of {', '.join(FORMS)}, got {self.form!r}")
        if self.both_missing not in BOTH_MISSING:
            raise ParameterError("both_missing", f"expected one of {', '.join(BOTH_MISSING)}, got {self.both_missing!r}")
        if not self.time_tolerance >= 0:
            raise ParameterError("time_tolerance", f"must be >= 0, got {self.time_tolerance}")
        if not self.gate > 0:
            raise ParameterError("gate", f"must be positive, got {self.gate}")


def match_times(a: NDArray[np.float64], b: NDArray[np.float64], tolerance: float) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Merge two sorted time grids: index pairs ``(ia, ib)`` per merged instant, −1 where one has none.

    Two instants are the same when each is the other's nearest neighbour and they are at most
    ``tolerance`` apart. The merged instants are in time order.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)

    def nearest(x: NDArray[np.float64], grid: NDArray[np.float64]) -> NDArray[np.int64]:
        if len(grid) == 0:
            return np.full(len(x), -1, dtype=np.int64)
        j = np.clip(np.searchsorted(grid, x), 1, max(len(grid) - 1, 1))
        j0 = np.clip(j - 1, 0, len(grid) - 1)
        j1 = np.clip(j, 0, len(grid) - 1)
        return np.where(np.abs(grid[j0] - x) <= np.abs(grid[j1] - x), j0, j1).astype(np.int64)

    na, nb = nearest(a, b), nearest(b, a)
    ia = np.arange(len(a))
    pair = (na >= 0) & (nb[np.maximum(na, 0)] == ia) if len(b) else np.zeros(len(a), bool)
    pair &= np.abs(b[np.maximum(na, 0)] - a) <= tolerance if len(b) else pair
    matched_b = np.zeros(len(b), bool)
    matched_b[na[pair]] = True
    idx_a = np.concatenate([ia, np.full(np.count_nonzero(~matched_b), -1)])
    idx_b = np.concatenate([np.where(pair, na, -1), np.flatnonzero(~matched_b)])
    t = np.concatenate([a, b[~matched_b]])
    order = np.argsort(t, kind="stable")
    return idx_a[order].astype(np.int64), idx_b[order].astype(np.int64)


@dataclass
class ComparisonSeries:
    """One target over the merged instants; NaN where not both datasets have it."""

    target: str
    time: NDArray[np.float64]
    has_real: NDArray[np.bool_]
    has_synthetic: NDArray[np.bool_]
    truth_defined: NDArray[np.bool_]
    hed: NDArray[np.float64]
    hed_other: NDArray[np.float64]
    """HED in the form not chosen (to show what the choice of (5.30) moves)."""
    covdiff: NDArray[np.float64]
    nees_real: NDArray[np.float64]
    nees_synthetic: NDArray[np.float64]
    rmse_real: NDArray[np.float64]
    rmse_synthetic: NDArray[np.float64]

    @property
    def common(self) -> NDArray[np.bool_]:
        return self.has_real & self.has_synthetic


@dataclass
class TargetComparison:
    """The per-(target, tuning) line of ``seatwin compare``."""

    target: str
    tuning: str
    ahed: float | None
    hellinger_form: str
    ahed_standard: float | None
    ahed_printed: float | None
    both_missing: str
    n_instants: int
    n_common: int
    n_only_real: int
    n_only_synthetic: int
    n_both_missing: int
    fraction_only_one: float | None
    """(n_only_real + n_only_synthetic) / instants where either dataset has the target."""
    mean_covdiff: float | None
    nees_difference_rms: float | None
    rmse_difference_rms: float | None
    anees_real: float | None
    anees_synthetic: float | None
    score: float | None = None
    """The unpaired fidelity score (S3) of this target; None when refused (``score_reason``)."""
    score_ci_low: float | None = None
    score_ci_high: float | None = None
    score_reason: str | None = None

    def to_dict(self) -> dict:
        return {**asdict(self), "ahed_reason": self.ahed_reason}

    @property
    def ahed_reason(self) -> str | None:
        """Why AHED is undefined, in words (None when it is defined)."""
        if self.ahed is not None:
            return None
        if self.n_common:
            return "no common instant counted under the both-missing convention"
        if self.n_only_real == self.n_only_synthetic == 0:
            return "neither dataset tracked the target"
        side = "real" if self.n_only_real else "synthetic"
        return f"only the {side} dataset tracked the target (no instant where both did)"


@dataclass
class Comparison:
    """A real-versus-synthetic comparison under one tuning."""

    tuning: str
    options: CompareOptions
    real: Evaluation
    synthetic: Evaluation
    series: dict[str, ComparisonSeries] = field(default_factory=dict)
    targets: list[TargetComparison] = field(default_factory=list)
    score: FidelityScore | None = None


def _num(x: float) -> float | None:
    return float(x) if x is not None and np.isfinite(x) else None


def _ahed(hed: NDArray[np.float64], n_only: int, n_both_missing: int, both_missing: str) -> float | None:
    """AHED (5.34) of the common-instant distances ``hed`` under the ``both_missing`` convention."""
    n_common = len(hed)
    total = float(np.sum(hed))
    if both_missing == "zero":
        n = n_common + n_both_missing
        return total / n if n else None
    if n_common:
        return total / n_common
    if both_missing == "never" and n_only == 0 and n_both_missing > 0:
        return 0.0  # neither dataset ever tracked the target: full agreement (thesis scenario 7)
    return None


def _valid_at(valid: NDArray[np.bool_], idx: NDArray[np.int64]) -> NDArray[np.bool_]:
    out = np.zeros(len(idx), dtype=bool)
    ok = idx >= 0
    out[ok] = valid[idx[ok]]
    return out


def _pick(values: NDArray[np.float64], idx: NDArray[np.int64]) -> NDArray[np.float64]:
    out = np.full(idx.shape + values.shape[1:], np.nan)
    ok = idx >= 0
    out[ok] = values[idx[ok]]
    return out


def compare_target(
    real: Evaluation, synthetic: Evaluation, truth: TruthSet, target: str, tuning: str, options: CompareOptions
) -> tuple[ComparisonSeries, TargetComparison]:
    """HED over time and the AHED line of one target."""
    sr, ss = real.series[target], synthetic.series[target]
    ir, is_ = match_times(sr.time, ss.time, options.time_tolerance)
    time = np.empty(len(ir))
    time[ir >= 0] = sr.time[ir[ir >= 0]]
    time[ir < 0] = ss.time[is_[ir < 0]]
    has_r = _valid_at(sr.valid, ir)
    has_s = _valid_at(ss.valid, is_)
    truth_ok = np.isfinite(truth[target].state_at(time)[:, 0]) if len(time) else np.zeros(0, bool)
    common = has_r & has_s
    n = len(time)
    hed = np.full(n, np.nan)
    other = np.full(n, np.nan)
    cdiff = np.full(n, np.nan)
    if common.any():
        mr, pr = sr.state[ir[common]], sr.covariance[ir[common]]
        ms, ps = ss.state[is_[common]], ss.covariance[is_[common]]
        other_form = "printed" if options.form == "standard" else "standard"
        hed[common] = hellinger(ms, ps, mr, pr, options.form)
        other[common] = hellinger(ms, ps, mr, pr, other_form)
        cdiff[common] = covdiff(ps, pr)
    series = ComparisonSeries(
        target,
        time,
        has_r,
        has_s,
        truth_ok,
        hed,
        other,
        cdiff,
        _pick(sr.nees, ir),
        _pick(ss.nees, is_),
        _pick(sr.rmse, ir),
        _pick(ss.rmse, is_),
    )
    n_common = int(np.count_nonzero(common))
    n_only_r = int(np.count_nonzero(has_r & ~has_s))
    n_only_s = int(np.count_nonzero(has_s & ~has_r))
    n_none = int(np.count_nonzero(~has_r & ~has_s & truth_ok))
    either = n_common + n_only_r + n_only_s
    ahed = _ahed(hed[common], n_only_r + n_only_s, n_none, options.both_missing)
    ahed_other = _ahed(other[common], n_only_r + n_only_s, n_none, options.both_missing)
    by_form = {options.form: ahed, ("printed" if options.form == "standard" else "standard"): ahed_other}
    summary_r = next(s for s in real.summaries if s.target == target)
    summary_s = next(s for s in synthetic.summaries if s.target == target)
    line = TargetComparison(
        target=target,
        tuning=tuning,
        ahed=ahed,
        hellinger_form=options.form,
        ahed_standard=by_form["standard"],
        ahed_printed=by_form["printed"],
        both_missing=options.both_missing,
        n_instants=int(np.count_nonzero(truth_ok)),
        n_common=n_common,
        n_only_real=n_only_r,
        n_only_synthetic=n_only_s,
        n_both_missing=n_none,
        fraction_only_one=((n_only_r + n_only_s) / either) if either else None,
        mean_covdiff=_num(float(np.mean(cdiff[common]))) if n_common else None,
        nees_difference_rms=_num(rms(series.nees_synthetic[common] - series.nees_real[common])) if n_common else None,
        rmse_difference_rms=_num(rms(series.rmse_synthetic[common] - series.rmse_real[common])) if n_common else None,
        anees_real=summary_r.anees,
        anees_synthetic=summary_s.anees,
    )
    return series, line


def compare(
    real: Tracks,
    synthetic: Tracks,
    truth: TruthSet,
    tuning: str = "",
    options: CompareOptions | None = None,
    mask: object | None = None,
    dont_care: TruthSet | None = None,
) -> Comparison:
    """Compare a real and a synthetic tracker run against the same ground truth (thesis 5.2.1); false tracks
    on land are counted with the water ``mask`` when given; tracks of a vessel of ``dont_care`` (no reliable ground
    truth: AIS-only vessels, moored boats) are not false tracks (:func:`seatwin.evaluation.evaluate.false_tracks`), and
    the score leaves plots and tracks near one out of its clutter and false-track terms
    (:func:`seatwin.evaluation.sensor_score.score_runs_with_sensor_terms`)."""
    options = options or CompareOptions()
    ev_r = evaluate(real, truth, options.gate, options.confirmed_only, options.confidence, mask, dont_care)
    ev_s = evaluate(synthetic, truth, options.gate, options.confirmed_only, options.confidence, mask, dont_care)
    result = Comparison(tuning, options, ev_r, ev_s)
    if options.score is not None:
        result.score = score_runs_with_sensor_terms(
            [real], [synthetic], truth, [ev_r], [ev_s], options.score, dont_care=dont_care
        )
    for name in truth.names:
        series, line = compare_target(ev_r, ev_s, truth, name, tuning, options)
        if result.score is not None:
            s = result.score.targets[name]
            line.score, line.score_ci_low, line.score_ci_high, line.score_reason = s.value, s.ci_low, s.ci_high, s.reason
        result.series[name] = series
        result.targets.append(line)
    return result


def comparison_table(comparisons: list[Comparison]) -> dict:
    """The JSON of ``seatwin compare``: per (target, tuning) lines, the mean AHED overall and per tuning.

    Means are over the targets whose AHED is defined; ``ahed_n`` / ``ahed_n_by_tuning`` say how many
    (of ``len(targets)``) that is — an undefined AHED is never counted as agreement."""
    lines = [t.to_dict() for c in comparisons for t in c.targets]
    values = [ln["ahed"] for ln in lines if ln["ahed"] is not None]
    by_tuning: dict[str, float | None] = {}
    n_by_tuning: dict[str, int] = {}
    for c in comparisons:
        v = [t.ahed for t in c.targets if t.ahed is not None]
        by_tuning[c.tuning] = float(np.mean(v)) if v else None
        n_by_tuning[c.tuning] = len(v)
    opts = comparisons[0].options if comparisons else CompareOptions()
    return {
        "targets": lines,
        "score_by_tuning": {c.tuning: c.score and c.score.to_dict() for c in comparisons},
        "ahed_mean": float(np.mean(values)) if values else None,
        "ahed_n": len(values),
        "ahed_mean_by_tuning": by_tuning,
        "ahed_n_by_tuning": n_by_tuning,
        "false_tracks": [
            {
                "tuning": c.tuning,
                "real": c.real.false_tracks and c.real.false_tracks.to_dict(),
                "synthetic": c.synthetic.false_tracks and c.synthetic.false_tracks.to_dict(),
            }
            for c in comparisons
        ],
        "conventions": {
            "hellinger_form": opts.form,
            "both_missing": opts.both_missing,
            "time_tolerance_s": opts.time_tolerance,
            "gate_m": opts.gate,
            "confirmed_only": opts.confirmed_only,
        },
    }
