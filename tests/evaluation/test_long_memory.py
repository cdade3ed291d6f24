"""Long memory in a signed term's series (issue 22, item 2): integrated autocorrelation time and the inflation."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.evaluation.bootstrap import (
    circular_block_indices,
    integrated_autocorrelation_time,
    long_memory_inflation,
    runs_autocorrelation_time,
)
from seatwin.evaluation.plot_terms import signed_term
from seatwin.evaluation.score import ScoreOptions


def _ar1(rng: np.random.Generator, n: int, phi: float) -> np.ndarray:
    x = np.empty(n)
    x[0] = rng.normal()
    e = rng.normal(0.0, np.sqrt(1 - phi * phi), n)
    for k in range(1, n):
        x[k] = phi * x[k - 1] + e[k]
    return x


def test_integrated_autocorrelation_time_of_ar1_and_edge_cases():
    rng = np.random.default_rng(0)
    for phi in (0.5, 0.8):  # τ = (1 + φ) / (1 − φ)
        assert integrated_autocorrelation_time(_ar1(rng, 200_000, phi)) == pytest.approx((1 + phi) / (1 - phi), rel=0.05)
    assert integrated_autocorrelation_time(rng.normal(size=50_000)) == pytest.approx(1.0, abs=0.05)
    assert integrated_autocorrelation_time(np.ones(30)) == 1.0
    assert integrated_autocorrelation_time([1.0, 2.0, np.nan]) == 1.0
    assert integrated_autocorrelation_time(np.tile([1.0, -1.0], 100)) == 1.0  # negative correlation: the floor
    # Pooled over runs: weighted by each run's number of finite values.
    a, b = _ar1(rng, 20_000, 0.8), rng.normal(size=60_000)
    pooled = runs_autocorrelation_time([a, b])
    assert pooled == pytest.approx(
        (20_000 * integrated_autocorrelation_time(a) + 60_000 * integrated_autocorrelation_time(b)) / 80_000
    )


def _boot_means(x: np.ndarray, block: int, n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.array([x[circular_block_indices(len(x), block, rng)].mean() for _ in range(n)])


def test_inflation_widens_short_blocks_on_a_remembering_series_only():
    rng = np.random.default_rng(1)
    iid = rng.normal(size=2000)
    assert long_memory_inflation([iid], _boot_means(iid, 1, 400, 2)) < 1.1
    slow = _ar1(rng, 2000, 0.95)  # τ = 39: blocks of 1 see a 39th of the mean's variance
    f = long_memory_inflation([slow], _boot_means(slow, 1, 400, 3))
    assert 3.0 < f < 10.0, f
    assert long_memory_inflation([np.ones(10)], np.ones(5)) == 1.0


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-100, 100), min_size=2, max_size=60), st.integers(1, 5))
def test_inflation_is_at_least_one(values, block):
    x = np.asarray(values)
    f = long_memory_inflation([x], _boot_means(x, block, 50, 0))
    assert np.isfinite(f) and f >= 1.0


@pytest.mark.slow
def test_long_memory_rule_restores_the_coverage_of_a_mean_under_drift():
    """Coverage by simulation: 40 AR(1) series (φ 0.9) plus white noise, 240 scans; the interval of one series' mean
    holds the true mean (0) in ≥ 85 % with the rule, and more often than the block bootstrap alone."""
    rng = np.random.default_rng(22)
    held = {True: 0, False: 0}
    for i in range(40):
        x = 0.3 * _ar1(rng, 240, 0.9) + rng.normal(0.0, 0.6, 240)
        y = 0.3 * _ar1(rng, 240, 0.9) + rng.normal(0.0, 0.6, 240)
        for memory in held:
            t = signed_term("mean", "", [x], [y], np.mean, ScoreOptions(n_boot=200, seed=i, long_memory=memory))
            held[memory] += t.real_ci[0] <= 0.0 <= t.real_ci[1]
            assert (t.counts["memory_inflation_real"] >= 1.0) if memory else ("memory_inflation_real" not in t.counts)
    assert held[True] >= 34 and held[True] > held[False], held


def test_batch_means_inflation_hand_computed():
    from scipy.stats import norm, t

    from seatwin.evaluation.bootstrap import batch_means_inflation

    x = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, np.nan]  # 4 batches of 2: means 0, 0, 1, 1 → V_bm = (1/3) / 4
    boot = np.array([0.0, 0.5]) * np.sqrt(2 / 48) / 0.5  # variance 1/48 (ddof 1) → r = 4
    assert float(np.var(boot, ddof=1)) == pytest.approx(1 / 48)
    assert batch_means_inflation([x], boot) == pytest.approx(2.0 * t.ppf(0.975, 3) / norm.ppf(0.975))
    assert batch_means_inflation([x[:4], x[4:]], boot) == batch_means_inflation([x], boot)  # runs one after another
    assert batch_means_inflation([x], boot * 3.0) == 1.0  # r = 4/9 ≤ 1: the bootstrap stands
    assert batch_means_inflation([x[:7]], boot) == 1.0  # fewer than 2 values a batch
    assert batch_means_inflation([x], np.ones(5)) == 1.0  # no bootstrap spread


def test_batch_floor_widens_drifting_detections_only_and_is_on_by_default():
    from seatwin.evaluation.plot_terms import RadarPlotSample, radar_plot_terms

    rng = np.random.default_rng(4)

    def drifting(n: int = 240) -> object:  # Pd 0.85 ± 0.15 over one slow period; ranges unrelated to time
        pd = 0.85 + 0.15 * np.sin(2 * np.pi * np.arange(n) / n)
        err = np.where(rng.random(n) < pd, 0.5, np.nan)  # a plot 0.5 m / 0.5° off where detected
        return RadarPlotSample(rng.uniform(300.0, 900.0, n), err, err, np.zeros(n, dtype=np.int64))

    real, synth = [drifting()], [drifting(), drifting()]
    off = radar_plot_terms(real, synth, 1.0, ScoreOptions(n_boot=300, seed=0, batch_floor=False))
    on = radar_plot_terms(real, synth, 1.0, ScoreOptions(n_boot=300, seed=0))
    assert ScoreOptions().batch_floor is True  # since evaluation 13 (docs/fidelity-score.md)
    assert on["pd_all"].real == off["pd_all"].real  # the values stay; only the spread may grow
    assert np.std(on["pd_all"].difference_replicates) >= np.std(off["pd_all"].difference_replicates)
    key = "memory_inflation_synthetic"  # two runs: here the autocorrelation time misses the drift
    grew = on["pd_all"].counts[key] / off["pd_all"].counts[key]
    assert grew > 1.5  # the batch means see a drift too weak per lag for the autocorrelation time
    for k in ("bearing_bias", "range_sigma", "clutter_per_scan"):  # not detection terms: unchanged to the bit
        assert np.array_equal(on[k].difference_replicates, off[k].difference_replicates, equal_nan=True)
