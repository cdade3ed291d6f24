"""Radar plot-level terms (seatwin.evaluation.plot_terms) and the data-chosen block length, against hand-computed values."""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest

from seatwin.evaluation import TruthSet, TruthTrack
from seatwin.evaluation.bootstrap import block_length, runs_block_length
from seatwin.evaluation.plot_terms import (
    RADAR_SENSOR_WEIGHTS,
    RadarPlotSample,
    clutter_in_annuli,
    detectable_difference,
    detection_design,
    gaussian_hellinger_1d,
    radar_plot_sample,
    radar_plot_terms,
    radar_sensor_score,
    sensor_lead,
    signed_term,
    wrap_deg,
)
from seatwin.evaluation.score import ScoreOptions


def _still(name: str, north: float, east: float, n: int = 4) -> TruthTrack:
    t = np.arange(n, dtype=float)
    return TruthTrack(name, t, np.full(n, north), np.full(n, east), np.zeros(n), np.zeros(n), "<test>")


def test_wrap_deg():
    assert wrap_deg([190.0, -180.0, 180.0, 359.0, 0.5]).tolist() == pytest.approx([-170.0, -180.0, -180.0, -1.0, 0.5])


def test_detectable_difference_hand_value():
    x = np.array([-1.0, 0.0, 1.0, np.nan])  # SD (ddof 1) of the finite values: 1
    assert detectable_difference(x) == pytest.approx(1.959964 + 0.841621, abs=1e-5)
    assert detectable_difference(x, level=0.9, power=0.5) == pytest.approx(1.644854, abs=1e-5)
    assert detectable_difference(np.array([1.0, np.nan])) is None


def test_a_difference_as_large_as_the_detectable_one_is_resolved_with_its_power():
    """The resolution a term states is a power statement: errors of that size are resolved about 80 % of the time,
    half that size far less often; and it is the analytic 2.80 σ √(2/n) for independent values."""
    o = ScoreOptions(n_boot=300)
    n, sigma = 300, 1.0
    first = signed_term(
        "bias", "°", [np.random.default_rng(0).normal(0, sigma, n)], [np.random.default_rng(1).normal(0, sigma, n)], np.mean, o
    )
    mdd = first.detectable
    assert mdd == pytest.approx(2.8016 * sigma * np.sqrt(2 / n), rel=0.2)
    assert f"this data resolves ≥ {mdd:.2g} °" in first.sentence()
    resolved = {1.0: 0, 0.5: 0}
    for k in range(40):
        rng = np.random.default_rng(100 + k)
        real = rng.normal(0, sigma, n)
        for f in resolved:
            resolved[f] += signed_term("bias", "°", [real], [rng.normal(f * mdd, sigma, n)], np.mean, o).resolved
    assert 24 <= resolved[1.0] <= 38 and resolved[0.5] <= 20, resolved  # 80 % and ≈ 29 % expected


def test_block_length_from_the_autocorrelation():
    # A square wave of half-period 5 (n = 200): autocorrelation 1 − 2k/5 at lags k ≤ 5 (0.6, 0.2, −0.2 …);
    # the first below 2/√200 = 0.141 is lag 3.
    x = np.tile(np.repeat([1.0, 0.0], 5), 20)
    acf = partial(block_length, rule="acf")
    assert acf(x) == 3
    assert acf(np.tile([1.0, -1.0], 50)) == 1  # anticorrelated at lag 1
    assert acf(np.ones(50)) == 1 and acf([1.0, 2.0]) == 1
    ar = np.zeros(3000)
    e = np.random.default_rng(0).normal(size=3000)
    for k in range(1, 3000):
        ar[k] = 0.95 * ar[k - 1] + e[k]
    # AR(1), φ = 0.95: ρ(k) = 0.95^k < 2/√3000 = 0.037 from k ≈ 65 (sampling noise moves it a little).
    assert 40 <= acf(ar) <= 90
    assert acf(ar, cap=20) == 20
    assert runs_block_length([x, np.tile([1.0, -1.0], 50)], rule="acf") == 3
    assert acf(np.r_[x, np.nan, np.nan]) == 3  # NaN (scans without a value) left out
    with pytest.raises(ValueError, match="unknown block-length rule"):
        block_length(x, rule="guess")


def _ar1(phi: float, n: int, seed: int) -> np.ndarray:
    e = np.random.default_rng(seed).normal(size=n)
    x = np.zeros(n)
    for k in range(1, n):
        x[k] = phi * x[k - 1] + e[k]
    return x


def test_politis_white_block_length_is_the_default():
    # AR(1), φ = 0.9, n = 3000: G = 2φ/(1−φ)² γ₀ = 180 γ₀, spectral sum (1+φ)/(1−φ) γ₀ = 19 γ₀, D = 4/3 · 19² γ₀²,
    # b = (2 G²/D)^(1/3) n^(1/3) = 5.12 × 14.42 = 73.9.
    assert 55 <= block_length(_ar1(0.9, 3000, 0)) <= 95
    assert block_length(_ar1(0.0, 3000, 1)) <= 3  # independent: (almost) no blocks
    assert block_length(_ar1(0.5, 200, 2)) < block_length(_ar1(0.9, 200, 2))
    assert block_length(_ar1(0.95, 100, 3)) <= 30  # ⌈min(3√n, n/3)⌉ = 30 (and n // 3 = 33)
    assert block_length(np.ones(50)) == 1 and block_length([1.0, 2.0]) == 1


def test_radar_plot_sample_hand_computed():
    truth = TruthSet({"target": _still("target", 1000.0, 0.0)}, "<test>")
    boat = TruthSet({"boat": _still("boat", 0.0, 500.0)}, "<test>")
    b = np.radians(1.0)
    plots = [
        np.array(
            [[1010.0 * np.cos(b), 1010.0 * np.sin(b)], [0.0, 505.0]]
        ),  # target plot 10 m beyond, 1° clockwise; one near the boat
        np.array([[-500.0, 0.0]]),  # clutter only: the target missed
        np.array(
            [[995.0, 0.0], [1000.0 * np.cos(-b), 1000.0 * np.sin(-b)]]
        ),  # two in the gate (neither is clutter): the nearer counts
        np.empty((0, 2)),
    ]
    s = radar_plot_sample(np.arange(4.0), np.zeros((4, 2)), plots, truth, "target", 60.0)
    assert s.target_range.tolist() == pytest.approx([1000.0] * 4)
    np.testing.assert_allclose(s.range_error, [10.0, np.nan, -5.0, np.nan], atol=1e-9)
    np.testing.assert_allclose(s.bearing_error, [1.0, np.nan, 0.0, np.nan], atol=1e-9)
    assert s.clutter.tolist() == [1, 1, 0, 0] and s.detected.tolist() == [1.0, 0.0, 1.0, 0.0]
    with_boat = radar_plot_sample(np.arange(4.0), np.zeros((4, 2)), plots, truth, "target", 60.0, dont_care=boat)
    assert with_boat.clutter.tolist() == [0, 1, 0, 0]  # the plot near the un-truthed boat is not clutter
    moved = radar_plot_sample(np.arange(4.0), np.full((4, 2), [0.0, 100.0]), plots, truth, "target", 60.0)
    assert moved.target_range[0] == pytest.approx(np.hypot(1000.0, 100.0))  # range and bearing from the antenna


def test_signed_term_values_direction_and_interval():
    o = ScoreOptions(n_boot=300, seed=3)
    real = [np.tile([-2.0, -1.0], 30)]  # mean −1.5
    synth = [np.tile([0.0, 1.0], 20), np.tile([0.0, 1.0, np.nan], 10)]  # mean 0.5 (NaN: scans without a plot)
    t = signed_term("bearing bias", "°", real, synth, np.mean, o, ("far clockwise", "far anticlockwise"))
    assert (t.real, t.synthetic, t.difference) == pytest.approx((-1.5, 0.5, 2.0))
    assert (t.counts["n_real"], t.counts["n_synthetic"]) == (60, 60)
    assert t.counts["memory_inflation_real"] >= 1.0 and t.counts["memory_inflation_synthetic"] >= 1.0  # long memory
    assert t.real_ci[0] <= -1.5 <= t.real_ci[1] and t.difference_ci[0] > 0.0 and t.resolved
    assert "model is 2 ° too far clockwise" in t.sentence() and "(resolved)" in t.sentence()
    same = signed_term("bearing bias", "°", real, [np.tile([-1.0, -2.0], 25)], np.mean, o)
    assert same.difference == pytest.approx(0.0) and not same.resolved
    assert same.difference_ci[0] < 0.0 < same.difference_ci[1]
    again = signed_term("bearing bias", "°", real, synth, np.mean, o, ("far clockwise", "far anticlockwise"))
    assert again.to_dict() == t.to_dict()  # reproducible
    few = signed_term("x", "m", [np.ones(5)], synth, np.mean, o)
    assert few.difference is None and few.reason == "fewer than 10 values (5 real, 60 synthetic)" and not few.resolved
    assert "not computed" in few.sentence()


def test_radar_plot_terms_hand_computed():
    n = 40
    rng_t = np.r_[np.full(20, 100.0), np.full(20, 700.0)]
    real = RadarPlotSample(
        rng_t,
        np.where(np.arange(n) % 2 == 0, 4.0, np.nan),  # detected at every other scan
        np.where(np.arange(n) % 2 == 0, -2.0, np.nan),
        np.full(n, 2, dtype=np.int64),
    )
    synth = RadarPlotSample(rng_t, np.r_[np.full(20, 2.0), np.full(20, 6.0)], np.zeros(n), np.ones(n, dtype=np.int64))
    terms = radar_plot_terms([real], [synth], area_km2=4.0, options=ScoreOptions(n_boot=100))
    assert terms["bearing_bias"].difference == pytest.approx(2.0) and terms["bearing_bias"].resolved
    assert terms["range_bias"].real == pytest.approx(4.0) and terms["range_bias"].synthetic == pytest.approx(4.0)
    assert terms["range_sigma"].real == pytest.approx(0.0) and terms["range_sigma"].synthetic == pytest.approx(
        np.sqrt(40 * 4.0 / 39) / 0.98658  # errors 2 and 6 (all within 3 robust σ = 3 × 1.4826 × 2 of 4): clipped std
    )
    assert (terms["pd_0_250m"].real, terms["pd_0_250m"].synthetic) == pytest.approx((0.5, 1.0))
    assert terms["pd_500_1000m"].difference == pytest.approx(0.5)
    assert terms["pd_1000_1500m"].reason.startswith("fewer than 10 values (0 real")
    assert (terms["clutter_per_scan"].real, terms["clutter_per_scan"].synthetic) == pytest.approx((2.0, 1.0))
    assert terms["clutter_per_km2"].difference == pytest.approx(-0.25)
    assert "too sparse" in terms["clutter_per_km2"].sentence()


def test_score_block_none_chooses_it_from_the_data():
    """ScoreOptions(block=None): the score's bootstraps take the block length from the series' autocorrelation —
    on counts that persist for 10 scans, the interval is wider than an i.i.d. bootstrap's."""
    from seatwin.evaluation.score import rate_score

    rng = np.random.default_rng(1)
    real = [np.repeat(rng.poisson(3.0, 30), 10)]
    synth = [np.repeat(rng.poisson(3.0, 30), 10)]
    auto = rate_score(real, synth, ScoreOptions(block=None, n_boot=300))
    iid = rate_score(real, synth, ScoreOptions(block=1, n_boot=300))
    assert auto.value == iid.value
    assert auto.ci_high - auto.ci_low > 1.5 * (iid.ci_high - iid.ci_low)


def test_lead_of_the_closer_model():
    from seatwin.evaluation.plot_terms import clipped_mean, lead, radar_term_specs

    n = 60
    rng = np.random.default_rng(2)

    def sample(bias: float) -> RadarPlotSample:
        return RadarPlotSample(np.full(n, 300.0), rng.normal(0.0, 5.0, n), rng.normal(bias, 0.5, n), np.zeros(n, dtype=np.int64))

    real, near, far = [sample(-1.8)], [sample(-1.6)], [sample(0.0)]
    spec = radar_term_specs(1.0)["bearing_bias"]
    mean = [clipped_mean(s[0].bearing_error) for s in (real, near, far)]
    got = lead(spec, real, near, far, ScoreOptions(n_boot=300))
    assert got.value == pytest.approx(abs(mean[2] - mean[0]) - abs(mean[1] - mean[0]))
    assert got.value > 1.0 and got.resolved and got.ci[0] <= got.value <= got.ci[1]
    back = lead(spec, real, far, near, ScoreOptions(n_boot=300))
    assert back.value == pytest.approx(-got.value) and not back.resolved
    assert (
        lead(spec, real, near, [sample(-1.8)], ScoreOptions(n_boot=300)).resolved is False
    )  # B (the true bias) is the closer one: no lead


def test_aspect_and_clutter_ranges_hand_computed():
    # Target 1 km north of the antenna heading north (stern towards the radar), then south (bow-on), then east (beam).
    t = np.arange(3, dtype=float)
    tr = TruthTrack(
        "target", t, np.full(3, 1000.0), np.full(3, 0.0), np.array([5.0, -5.0, 0.0]), np.array([0.0, 0.0, 5.0]), "<t>"
    )
    truth = TruthSet({"target": tr}, "<test>")
    plots = [np.array([[0.0, 300.0], [0.0, -700.0]]), np.array([[1000.0, 0.0]]), np.empty((0, 2))]
    s = radar_plot_sample(t, np.zeros((3, 2)), plots, truth, "target", 60.0)
    np.testing.assert_allclose(s.aspect, [180.0, 0.0, 90.0], atol=1e-6)
    assert [r.tolist() for r in s.clutter_range] == [pytest.approx([300.0, 700.0]), [], []]
    np.testing.assert_array_equal(clutter_in_annuli(s), [[0, 1, 1, 0, 0], [0] * 5, [0] * 5])  # 250–500, 500–1000 m
    slow = TruthSet({"target": _still("target", 1000.0, 0.0, 3)}, "<test>")
    assert np.isnan(radar_plot_sample(t, np.zeros((3, 2)), plots, slow, "target", 60.0).aspect).all()  # no heading


def test_gaussian_hellinger_1d_against_the_formula():
    assert gaussian_hellinger_1d(0.0, 1.0, 0.0, 1.0) == pytest.approx(0.0)
    # Equal σ: H² = 1 − exp(−Δ²/(8σ²)).
    assert gaussian_hellinger_1d(1.0, 1.0, -1.0, 1.0) ** 2 == pytest.approx(1.0 - np.exp(-0.5))
    # Equal means, σ 1 and 2: H² = 1 − √(4/5).
    assert gaussian_hellinger_1d(0.0, 1.0, 0.0, 2.0) ** 2 == pytest.approx(1.0 - np.sqrt(0.8))


def _sample(n: int, rng: np.random.Generator, bias: float = 0.0, sigma: float = 1.0, pd: float = 0.8, clutter: float = 2.0):
    det = rng.random(n) < pd
    b = np.where(det, rng.normal(bias, sigma, n), np.nan)
    r = np.where(det, rng.normal(0.0, 5.0, n), np.nan)
    c = rng.poisson(clutter, n)
    ranges = tuple(rng.uniform(0.0, 1000.0, k) for k in c)
    return RadarPlotSample(np.full(n, 300.0), r, b, c.astype(np.int64), np.full(n, 90.0), ranges)


def test_radar_sensor_score_parts_hand_computed():
    n = 40
    half = np.arange(n) < 20
    real = RadarPlotSample(
        np.full(n, 300.0),
        np.where(half, 0.0, np.nan),
        np.where(half, np.tile([-1.0, 1.0], 20), np.nan),  # mean 0, clipped σ √(20/19)
        np.full(n, 4, dtype=np.int64),
        np.full(n, 90.0),
        tuple(np.array([100.0, 100.0, 600.0, 600.0]) for _ in range(n)),
    )
    synth = RadarPlotSample(
        np.full(n, 300.0),
        np.zeros(n),
        np.tile([-1.0, 1.0], 20) + 1.0,
        np.full(n, 1, dtype=np.int64),
        np.full(n, 90.0),
        tuple(np.array([600.0]) for _ in range(n)),
    )
    sc = radar_sensor_score([real], [synth], ScoreOptions(n_boot=50))
    s = np.sqrt(20.0 / 19.0) / 0.98658
    s_syn = np.sqrt(40.0 / 39.0) / 0.98658
    assert sc.parts["bearing"].value == pytest.approx(gaussian_hellinger_1d(0.0, s, 1.0, s_syn))
    assert sc.parts["range"].value == pytest.approx(0.0, abs=1e-9)  # both exactly 0 (σ floors equal)
    # Detection: one cell (250–500 m, beam), Pd 0.5 vs 1: H² = 1 − √0.5.
    assert sc.parts["detection"].value == pytest.approx(np.sqrt(1.0 - np.sqrt(0.5)))
    # Clutter per scan per annulus: real 2 (0–250 m), 2 (500–1000 m); synthetic 0 and 1.
    assert sc.parts["clutter"].value == pytest.approx(np.sqrt(1.0 - np.exp(-0.5 * (2.0 + (np.sqrt(2.0) - 1.0) ** 2))))
    expected = 1.0 - np.prod([1.0 - v.value for v in sc.parts.values()])
    assert sc.overall.value == pytest.approx(expected) and sc.weights == RADAR_SENSOR_WEIGHTS
    assert sc.to_dict()["parts"]["clutter"]["counts"] == {"weight": 1.0}
    few = radar_sensor_score([real], [synth], ScoreOptions(n_boot=20, n_min=30))
    assert few.parts["bearing"].value is None and "bearing: fewer than 30 target plots" in few.overall.reason


def test_radar_sensor_score_ranks_and_leads():
    rng = np.random.default_rng(5)
    o = ScoreOptions(n_boot=100, seed=1)
    real = [_sample(300, rng, bias=-1.0)]
    same = [_sample(300, rng, bias=-1.0)]
    wrong = {
        "bias": [_sample(300, rng, bias=0.0)],
        "sigma": [_sample(300, rng, bias=-1.0, sigma=2.0)],
        "pd": [_sample(300, rng, bias=-1.0, pd=0.5)],
        "clutter": [_sample(300, rng, bias=-1.0, clutter=6.0)],
    }
    s_true = radar_sensor_score(real, same, o)
    for k, w in wrong.items():
        s_w = radar_sensor_score(real, w, o)
        assert s_w.overall.value > s_true.overall.value, k
        got = sensor_lead(real, same, w, o)
        assert got.resolved and got.ci[0] <= got.value <= got.ci[1], k
    assert not sensor_lead(real, wrong["bias"], same, o).resolved
    assert radar_sensor_score(real, same, o).to_dict() == s_true.to_dict()  # reproducible


def _detections(ranges: np.ndarray, detected: np.ndarray) -> RadarPlotSample:
    err = np.where(detected > 0, 0.5, np.nan)
    return RadarPlotSample(ranges, err, err, np.zeros(len(ranges), dtype=np.int64))


def test_detection_design_hand_computed():
    a = _detections(np.array([100.0, 100.0, 300.0, 3000.0]), np.array([1.0, 0.0, 1.0, 0.0]))
    b = _detections(np.array([200.0, 400.0]), np.array([1.0, 0.0]))
    series = [np.array([1.0, 0.0, 1.0, np.nan]), np.array([1.0, np.nan])]
    got = detection_design([a, b]).residuals(series)
    # N = 6 scans, round(√6) = 2 equal-count bins cut at the median range 250 m: {100, 100, 200} detected 2 of 3,
    # {300, 400, 3000} 1 of 3; residuals times √(6 / (6 − 2))
    f = np.sqrt(6 / 4)
    assert got[0][:3] == pytest.approx([f / 3, -2 * f / 3, 2 * f / 3])
    assert np.isnan(got[0][3]) and np.isnan(got[1][1])
    assert got[1][0] == pytest.approx(f / 3)


def _orbit_like(seed: int, n: int = 600) -> RadarPlotSample:
    """A target that spends long spells beyond the radar's range (Pd 0 there by design), Pd 0.8 within it."""
    rng = np.random.default_rng(seed)
    ranges = np.where((np.arange(n) // 100) % 2 == 0, 600.0, 1200.0)
    detected = np.where(ranges < 1000.0, rng.random(n) < 0.8, False).astype(float)
    return _detections(ranges, detected)


def test_design_adjusted_detection_terms_spread_as_the_detections_do():
    real, synth = [_orbit_like(1)], [_orbit_like(2), _orbit_like(3)]
    on = radar_plot_terms(real, synth, 1.0, ScoreOptions(n_boot=300, seed=0))
    off = radar_plot_terms(real, synth, 1.0, ScoreOptions(n_boot=300, seed=0, design_memory=False))
    sd_on = float(np.std(on["pd_all"].difference_replicates))
    sd_off = float(np.std(off["pd_all"].difference_replicates))
    # given where the target was, the shares' difference has the binomial SD of the 300 + 600 in-range scans
    ideal = float(np.sqrt(0.8 * 0.2 * (1 / 300 + 1 / 600)) * 300 / 600)  # the share is over all 600 / 1200 scans
    assert sd_on == pytest.approx(ideal, rel=0.35)
    assert sd_off > 3 * sd_on
    assert on["pd_all"].real == off["pd_all"].real and on["pd_all"].synthetic == off["pd_all"].synthetic
    for k in ("bearing_bias", "range_sigma", "clutter_per_scan"):  # not detection terms: unchanged to the bit
        assert np.array_equal(on[k].difference_replicates, off[k].difference_replicates, equal_nan=True)
