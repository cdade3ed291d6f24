"""Run-to-run spread of the target terms (issue 22, item 2): estimates, draws, and coverage by simulation."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats

from seatwin.evaluation.run_spread import gaussian_from_params, gaussian_params, run_effects, run_spread, t_scales
from seatwin.evaluation.score import ScoreOptions, ScoreValue, TargetErrors, combine, overall_score, target_score


@settings(max_examples=60, deadline=None)
@given(
    st.floats(-50, 50),
    st.floats(-50, 50),
    st.floats(0.01, 30),
    st.floats(0.01, 30),
    st.floats(-0.95, 0.95),
)
def test_gaussian_params_round_trip(mn, me, sn, se, rho):
    cov = np.array([[sn * sn, rho * sn * se], [rho * sn * se, se * se]])
    m, c = gaussian_from_params(gaussian_params([mn, me], cov))
    assert np.allclose(m, [mn, me]) and np.allclose(c, cov, rtol=1e-9, atol=1e-12)


def test_run_spread_estimates_a_known_covariance():
    rng = np.random.default_rng(0)
    sigma = np.array([[0.04, 0.01], [0.01, 0.09]])
    s = run_spread(rng.multivariate_normal([1.0, -2.0], sigma, 4000))
    assert s is not None and s.dof == 3999 and s.runs == 4000
    assert np.allclose(s.cov, sigma, atol=0.006)
    # Less a within-run part: the difference, projected onto the PSD matrices (never negative).
    less = run_spread(rng.multivariate_normal([0, 0], sigma, 4000), np.tile(np.diag([0.01, 0.2]), (4000, 1, 1)))
    assert less.cov[0, 0] == pytest.approx(0.03, abs=0.006)
    assert np.linalg.eigvalsh(less.cov).min() >= -1e-12
    assert run_spread(np.ones((1, 2))) is None
    with pytest.raises(ValueError, match="finite"):
        run_spread(np.array([[1.0], [np.nan]]))


def test_t_scales_make_student_t_draws():
    rng = np.random.default_rng(1)
    s = run_spread(np.array([[-1.0], [1.0]]))  # sample variance 2, one degree of freedom
    assert s.cov[0, 0] == pytest.approx(2.0)
    u = t_scales(2, 200_000, rng)
    draws = run_effects(run_spread(np.array([[0.0], [np.sqrt(2.0)], [-np.sqrt(2.0)]])), 1.0, u, rng)[:, 0]
    # Variance of the three values: 2; draws are √2 · t₂.
    for q in (0.9, 0.975):
        assert np.quantile(draws, q) == pytest.approx(np.sqrt(2.0) * stats.t.ppf(q, 2), rel=0.04)
    assert np.allclose(run_effects(s, 0.5, np.zeros(3), rng), 0.0)


def _run(rng: np.random.Generator, n: int, offset: np.ndarray, sigma: float, coverage: float) -> TargetErrors:
    """One run: AR(1) errors (φ 0.9) around a run-level offset, with a track for the first ``coverage`` of the run
    (a run-level event: the track is lost once and for all)."""
    e = np.empty((n, 2))
    e[0] = rng.normal(0, sigma, 2)
    for k in range(1, n):
        e[k] = 0.9 * e[k - 1] + rng.normal(0, sigma * np.sqrt(1 - 0.81), 2)
    e += offset
    e[int(round(coverage * n)) :] = np.nan
    return TargetErrors(e)


def _model_run(rng: np.random.Generator, n: int = 120, shift: float = 0.0) -> TargetErrors:
    """A run of a model whose run-level effects dominate: offset N(0, 0.5²) m per run, coverage U(0.6, 1)."""
    return _run(rng, n, rng.normal(0, 0.5, 2) + shift, 0.3, rng.uniform(0.6, 1.0))


@pytest.mark.slow
def test_run_spread_interval_holds_zero_between_runs_of_one_model():
    """Coverage by simulation: one "real" run and K = 4 runs of the *same* model, whose runs differ mostly by
    run-level effects. With the run-to-run spread the interval holds 0 (the true distance) in ≥ 90 % of 40 pairs;
    the within-run bootstrap alone holds it far less often. A real run of a model shifted by 3 m is resolved."""
    rng = np.random.default_rng(22)
    held, held_within, resolved = 0, 0, 0
    pairs = 40
    for i in range(pairs):
        real, synth = [_model_run(rng)], [_model_run(rng) for _ in range(4)]
        s = target_score(real, synth, ScoreOptions(n_boot=200, seed=i))
        assert s.counts["between_runs"] == 4 and s.null_replicates is not None
        held += s.ci_low == 0.0
        if i < 15:
            w = target_score(real, synth, ScoreOptions(n_boot=100, seed=i, run_spread=False))
            assert w.counts["between_runs"] == 0
            held_within += w.ci_low == 0.0
        far = target_score([_model_run(rng, shift=3.0)], synth, ScoreOptions(n_boot=200, seed=i))
        resolved += far.ci_low > 0.0
    assert held >= 0.9 * pairs, held
    assert held_within <= 0.6 * 15, held_within
    assert resolved >= 0.9 * pairs, resolved


def test_run_spread_is_used_only_with_two_tracked_runs_and_is_reproducible():
    rng = np.random.default_rng(5)
    real, synth = [_model_run(rng)], [_model_run(rng) for _ in range(3)]
    a, b = target_score(real, synth, ScoreOptions(seed=2)), target_score(real, synth, ScoreOptions(seed=2))
    assert (a.value, a.ci_low, a.ci_high) == (b.value, b.ci_low, b.ci_high)
    assert np.array_equal(a.null_replicates, b.null_replicates)
    assert a.counts["between_runs"] == 3 and a.counts["null_quantile"] >= 0.0
    assert a.ci_low == max(0.0, a.value - float(np.quantile(a.null_replicates, 0.95)))
    one = target_score(real, synth[:1], ScoreOptions(seed=2))  # one synthetic run: within-run blocks only
    assert one.counts["between_runs"] == 0 and one.null_replicates is None
    lost = TargetErrors(np.full((120, 2), np.nan))
    assert target_score(real, [synth[0], lost], ScoreOptions(seed=2)).counts["between_runs"] == 0
    assert "null_replicates" not in a.to_dict()


def test_overall_lower_bound_from_the_parts_null_replicates():
    """S5 with a target that has null replicates: lower bound = value − the 95 % quantile of the combined nulls,
    a plot part entering with its replicates' excess over its value."""
    reps_t, nulls_t = np.linspace(0.1, 0.5, 200), np.linspace(0.0, 0.4, 200)
    t = ScoreValue(0.3, 0.0, 0.5, None, {}, reps_t, nulls_t)
    reps_p = np.linspace(0.05, 0.25, 200)
    p = ScoreValue(0.1, 0.0, 0.2, None, {}, reps_p)
    o = overall_score({"a": t}, {"clutter": p}, ScoreOptions(n_boot=200))
    assert o.value == pytest.approx(combine(0.3, 0.1))
    nulls = np.array([combine(a, b) for a, b in zip(nulls_t, np.clip(reps_p - 0.1, 0, 1))])
    assert o.ci_low == pytest.approx(max(0.0, o.value - np.quantile(nulls, 0.95)))
    assert o.null_replicates is not None
    plain = overall_score({"a": ScoreValue(0.3, 0.0, 0.5, None, {}, reps_t)}, {"clutter": p}, ScoreOptions(n_boot=200))
    assert plain.null_replicates is None
