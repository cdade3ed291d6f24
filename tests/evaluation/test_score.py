"""The unpaired fidelity score (S1–S5): hand-computed values, refusals, and that it ranks the true model first."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.evaluation.bootstrap import circular_block_indices, percentile_interval
from seatwin.evaluation.score import (
    ERROR_FLOOR_M,
    ScoreOptions,
    TargetErrors,
    clutter_counts,
    combine,
    error_hellinger,
    gaussian_fit,
    overall_score,
    poisson_hellinger,
    rate_score,
    target_score,
)
from seatwin.evaluation.truth import TruthSet, TruthTrack


def test_poisson_hellinger_hand_computed():
    # (√4 − √9)² / 2 = 0.5  →  H = sqrt(1 − e^−0.5)
    assert poisson_hellinger(4.0, 9.0) == pytest.approx(math.sqrt(1 - math.exp(-0.5)), rel=1e-12)
    assert poisson_hellinger(3.0, 3.0) == 0.0
    assert poisson_hellinger(0.0, 50.0) == pytest.approx(math.sqrt(1 - math.exp(-25.0)))


def test_combine_hand_computed():
    assert combine(0.2, 0.5) == pytest.approx(0.6)
    assert combine(0.0, 0.0, 0.0) == 0.0
    assert combine(0.3, 1.0) == 1.0


def test_gaussian_fit_and_error_hellinger_hand_computed():
    e = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])
    mean, cov = gaussian_fit(e)
    var = 2.0 / 3.0 + ERROR_FLOOR_M**2
    np.testing.assert_allclose(mean, [0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(cov, var * np.eye(2), rtol=1e-12)
    assert error_hellinger(e, e) == pytest.approx(0.0, abs=1e-7)
    # Same covariance, means 1 m apart in north: NEES = 1/var, HED = sqrt(1 − exp(−NEES/8)).
    expected = math.sqrt(1 - math.exp(-1.0 / var / 8.0))
    assert error_hellinger(e, e + [1.0, 0.0]) == pytest.approx(expected, rel=1e-9)


def test_clutter_counts_against_truth():
    truth = TruthSet({"a": TruthTrack("a", np.array([0.0, 10.0]), np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2))})
    plots = [np.array([[0.0, 5.0], [100.0, 0.0]]), np.empty((0, 2)), np.array([[30.0, 0.0]])]
    np.testing.assert_array_equal(clutter_counts([0.0, 1.0, 20.0], plots, truth, gate=25.0), [1, 0, 1])


def _errors(rng: np.random.Generator, n: int, sigma: float, coverage: float = 1.0, bias: float = 0.0) -> TargetErrors:
    e = rng.normal(0.0, sigma, (n, 2)) + [bias, 0.0]
    e[rng.random(n) >= coverage] = np.nan
    return TargetErrors(e)


def test_target_score_refusals():
    rng = np.random.default_rng(0)
    few = TargetErrors(np.vstack([rng.normal(size=(5, 2)), np.full((50, 2), np.nan)]))
    many = _errors(rng, 60, 1.0)
    s = target_score([few], [few])
    assert s.value is None and "fewer than 10" in s.reason
    lost = target_score([few], [many])  # 5 instants with a track against 60: as good as never tracked there
    assert lost.value == 1.0 and lost.counts["one_sided"]
    none = TargetErrors(np.full((60, 2), np.nan))
    assert target_score([none], [none]).reason == "neither dataset tracked the target"
    one_sided = target_score([none], [many])  # never tracked on one side, always on the other: total disagreement
    assert one_sided.value == 1.0
    assert target_score([TargetErrors(np.empty((0, 2)))], [many]).reason == "no ground-truth instants in the window"


def test_target_score_ci_and_reproducible():
    rng = np.random.default_rng(1)
    real, synth = [_errors(rng, 200, 1.0)], [_errors(rng, 200, 1.5) for _ in range(3)]
    a = target_score(real, synth, ScoreOptions(seed=3))
    b = target_score(real, synth, ScoreOptions(seed=3))
    assert a.value == b.value and (a.ci_low, a.ci_high) == (b.ci_low, b.ci_high)
    assert a.ci_low <= a.value <= a.ci_high
    assert a.counts["n_real"] == 200 and a.counts["n_synthetic"] == 600


def test_score_ranks_the_true_model_first():
    """The controlled property AHED lacks: independent noise, and the true model still wins against
    too clean, too noisy, biased and lossy ones."""
    rng = np.random.default_rng(7)
    real = [_errors(rng, 300, 1.0, coverage=0.8)]
    models = {
        "true": dict(sigma=1.0, coverage=0.8),
        "too_clean": dict(sigma=0.2, coverage=0.99),
        "wide": dict(sigma=3.0, coverage=0.8),
        "biased": dict(sigma=1.0, coverage=0.8, bias=1.5),
        "lossy": dict(sigma=1.0, coverage=0.3),
    }
    scores = {name: target_score(real, [_errors(rng, 300, **kw) for _ in range(3)]).value for name, kw in models.items()}
    assert min(scores, key=scores.get) == "true", scores
    assert all(v > scores["true"] + 0.1 for k, v in scores.items() if k != "true"), scores


def test_rate_and_count_scores():
    rng = np.random.default_rng(2)
    same = rate_score([rng.poisson(3.0, 100)], [rng.poisson(3.0, 100)], stream="c")
    heavy = rate_score([rng.poisson(3.0, 100)], [rng.poisson(30.0, 100)], stream="c")
    assert same.value < 0.15 < 0.9 < heavy.value
    assert heavy.counts["rate_synthetic_per_scan"] == pytest.approx(30.0, rel=0.1)
    assert rate_score([np.ones(3)], [np.ones(3)]).value is None
    c = rate_score([np.full(20, 4.0)], [np.full(20, 9.0), np.full(30, 9.0)])
    assert c.value == pytest.approx(poisson_hellinger(4, 9))
    assert c.ci_low <= c.value <= c.ci_high


def test_overall_combines_parts_and_names_what_is_left_out():
    rng = np.random.default_rng(4)
    t = target_score([_errors(rng, 100, 1.0)], [_errors(rng, 100, 1.2)])
    clutter = rate_score([rng.poisson(2.0, 50)], [rng.poisson(4.0, 50)])
    false = rate_score([rng.poisson(0.5, 50)], [rng.poisson(1.0, 50)])
    o = overall_score({"a": t}, {"clutter": clutter, "false_tracks": false})
    assert o.value == pytest.approx(combine(t.value, clutter.value, false.value))
    assert o.ci_low <= o.value <= o.ci_high
    without = overall_score({"a": t}, {"clutter": rate_score([], []), "false_tracks": false})
    assert without.value == pytest.approx(combine(t.value, false.value)) and "clutter" in without.reason
    refused = overall_score(
        {"a": target_score([TargetErrors(np.full((20, 2), np.nan))], [TargetErrors(np.full((20, 2), np.nan))])},
        {"clutter": clutter, "false_tracks": false},
    )
    assert refused.value is None and "neither dataset" in refused.reason


def test_with_sensor_score_replaces_the_terms_it_measures_again():
    from seatwin.evaluation.score import FidelityScore, with_sensor_score

    rng = np.random.default_rng(5)
    t = target_score([_errors(rng, 100, 1.0)], [_errors(rng, 100, 1.2)])
    clutter = rate_score([rng.poisson(2.0, 50)], [rng.poisson(4.0, 50)])
    false = rate_score([rng.poisson(0.5, 50)], [rng.poisson(1.0, 50)])
    sensor = rate_score([rng.poisson(1.0, 50)], [rng.poisson(3.0, 50)])  # any ScoreValue with replicates
    plots = {"clutter": clutter, "false_tracks": false}
    base = FidelityScore(overall_score({"a": t}, plots), {"a": t}, plots)
    got = with_sensor_score(base, "radar_sensor", sensor, ("clutter",))
    assert got.overall.value == pytest.approx(combine(t.value, false.value, sensor.value))  # clutter not counted twice
    assert got.overall.ci_low <= got.overall.value <= got.overall.ci_high
    d = got.to_dict()
    assert d["radar_sensor"]["value"] == sensor.value and d["clutter"]["value"] == clutter.value
    assert d["not_combined"] == {"clutter": "measured inside radar_sensor"}
    assert "not_combined" not in base.to_dict()


def test_bootstrap_helpers():
    rng = np.random.default_rng(0)
    idx = circular_block_indices(30, 10, rng)
    assert len(idx) == 30 and idx.min() >= 0 and idx.max() < 30
    assert circular_block_indices(0, 5, rng).size == 0
    assert percentile_interval(np.array([np.nan])) is None
    lo, hi = percentile_interval(np.arange(101.0))
    assert (lo, hi) == pytest.approx((2.5, 97.5))


def test_error_floor_matches_sampling():
    """(S1') against Monte Carlo: two samples from one Gaussian, mean H² ≈ 5/8 · (1/n + 1/m)."""
    from seatwin.evaluation.score import error_hellinger_floor

    rng = np.random.default_rng(5)
    h2 = [error_hellinger(rng.normal(size=(400, 2)), rng.normal(size=(800, 2))) ** 2 for _ in range(300)]
    assert np.mean(h2) == pytest.approx(error_hellinger_floor(400, 800) ** 2, rel=0.15)


def test_shape_score_sees_a_thicker_cluster_distribution():
    from seatwin.evaluation.score import shape_score

    rng = np.random.default_rng(8)

    def runs(thickness: float) -> list[list[np.ndarray]]:
        return [[np.column_stack([rng.normal(2.0, 0.5, 5), rng.normal(np.log(thickness), 0.3, 5)]) for _ in range(60)]]

    ref, same, thick = runs(0.1), runs(0.1), runs(0.4)
    s_same, s_thick = shape_score(ref, same), shape_score(ref, thick)
    assert s_same.value < 0.1 < 0.9 < s_thick.value
    assert s_thick.ci_low <= s_thick.value <= s_thick.ci_high
    assert shape_score([[np.zeros((0, 2))]], same).value is None


def test_far_tracks_count_only_tracks_beyond_the_gate():
    from seatwin.evaluation.score import run_far_tracks
    from seatwin.evaluation.tracks_io import Tracks

    truth = TruthSet({"a": TruthTrack("a", np.array([0.0, 10.0]), np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2))})
    state = np.zeros((3, 4))
    state[1, 0] = 15.0  # a poor track of the target: within the 25 m gate, not false
    state[2, 0] = 100.0  # far from every target: false
    tracks = Tracks(
        [1.0, 1.0, 1.0], [0, 1, 2], [0.9] * 3, state, np.tile(np.eye(4), (3, 1, 1)), [True] * 3, scan_times=[0.0, 1.0]
    )
    np.testing.assert_array_equal(run_far_tracks([tracks], truth, 25.0)[0], [0, 1])
    np.testing.assert_array_equal(run_far_tracks([tracks], truth, 25.0, window=(0.5, 2.0))[0], [1])


def test_dont_care_vessels_are_neither_clutter_nor_false_tracks():
    """A vessel without ground truth (``dont_care``): its plots are not clutter and a track on it is not false,
    so a replica that lacks it, or detects it less often, is not charged for it in the plot terms."""
    from seatwin.evaluation import evaluate
    from seatwin.evaluation.score import score_runs
    from seatwin.evaluation.tracks_io import PlotLog, Tracks

    times = np.arange(40, dtype=float)
    still = np.zeros(2)
    truth = TruthSet({"a": TruthTrack("a", np.array([0.0, 40.0]), still, still, still, still)})
    boat = TruthSet({"boat": TruthTrack("boat", np.array([0.0, 40.0]), [500.0, 500.0], still, still, still)})

    def run(with_boat: bool) -> Tracks:
        plots = [np.array([[1.0, 0.0], [500.0, 2.0]] if with_boat else [[1.0, 0.0]]) for _ in times]
        n = 2 if with_boat else 1
        state = np.zeros((len(times) * n, 4))
        if with_boat:
            state[1::2, 0] = 500.0
        return Tracks(
            np.repeat(times, n),
            np.tile(np.arange(n), len(times)),
            np.full(len(times) * n, 0.9),
            state,
            np.tile(np.eye(4), (len(times) * n, 1, 1)),
            np.ones(len(times) * n, bool),
            scan_times=times,
            plots=PlotLog(times, tuple(plots)),
        )

    real, synth = run(True), run(False)
    evals = [evaluate(real, truth, 10.0)], [evaluate(synth, truth, 10.0)]
    o = ScoreOptions(n_boot=20)
    charged = score_runs([real], [synth], truth, *evals, o)
    assert charged.plots["clutter"].value > 0.5 and charged.plots["false_tracks"].value > 0.5
    spared = score_runs([real], [synth], truth, *evals, o, dont_care=boat)
    assert spared.plots["clutter"].value == 0.0 and spared.plots["false_tracks"].value == 0.0
    assert spared.targets["a"].value == charged.targets["a"].value
