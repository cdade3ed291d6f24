"""Lidar sensor-level terms (seatwin.evaluation.lidar_terms) and the per-track false-track term (false_tracks)."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.evaluation import TruthSet, TruthTrack
from seatwin.evaluation.false_tracks import false_track_births, false_track_score
from seatwin.evaluation.lidar_terms import (
    FAMILY_WEIGHTS,
    LidarReturnSample,
    bernoulli_hellinger,
    combined_distance,
    lidar_return_samples,
    lidar_returns_score,
    lidar_term_specs,
    lidar_terms,
    pooled_return,
    return_spreads,
    time_design_residuals,
)
from seatwin.evaluation.score import ScoreOptions, poisson_hellinger
from seatwin.evaluation.tracks_io import PlotLog, Tracks


def _still(name: str, north: float, east: float, t_end: float = 100.0) -> TruthTrack:
    t = np.array([0.0, t_end])
    return TruthTrack(name, t, np.full(2, north), np.full(2, east), np.zeros(2), np.zeros(2), "<test>")


def _moments(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    c = points.mean(axis=0)
    d = points - c
    cov = d.T @ d / len(points)
    return np.array([len(points), cov[0, 0], cov[0, 1], cov[1, 1]]), c


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 5), st.integers(0, 10_000))
def test_pooled_return_equals_the_moments_of_the_union(k, seed):
    rng = np.random.default_rng(seed)
    clouds = [rng.normal(rng.normal(0, 3, 2), rng.uniform(0.05, 1.0), (int(rng.integers(1, 30)), 2)) for _ in range(k)]
    rows, cents = zip(*(_moments(c) for c in clouds))
    n, c, cov = pooled_return(np.array(rows), np.array(cents))
    union = np.concatenate(clouds)
    assert n == len(union)
    np.testing.assert_allclose(c, union.mean(axis=0), atol=1e-9)
    np.testing.assert_allclose(cov, np.cov(union, rowvar=False, ddof=0), atol=1e-9)


def test_return_spreads_along_and_across_the_line_of_sight():
    # Spread 0.3 m along north, 2 m along east; seen from due south (line of sight = north): depth 0.3, width 2.
    cov = np.diag([0.3**2, 2.0**2])
    depth, width, thick = return_spreads(cov, np.array([50.0, 0.0]), np.zeros(2))
    assert (depth, width, thick) == pytest.approx((0.3, 2.0, 0.3))
    # Seen from due west (line of sight = east): depth and width swap, thickness does not change.
    depth, width, thick = return_spreads(cov, np.array([0.0, 50.0]), np.zeros(2))
    assert (depth, width, thick) == pytest.approx((2.0, 0.3, 0.3))
    # At 45°: both are the RMS of the two axes' variances.
    depth, width, _ = return_spreads(cov, np.array([30.0, 30.0]), np.zeros(2))
    assert depth == pytest.approx(np.sqrt((0.09 + 4.0) / 2)) and width == pytest.approx(depth)


def test_lidar_return_samples_hand_built():
    truth = TruthSet({"a": _still("a", 30.0, 0.0, 2.0), "b": _still("b", 0.0, 60.0, 2.0)}, "<test>")
    boat = TruthSet({"boat": _still("boat", 36.0, 0.0, 2.0)}, "<test>")
    r1, c1 = _moments(np.array([[29.0, 0.0], [31.0, 0.0], [30.0, 1.0], [30.0, -1.0]]))  # on a
    r2, c2 = _moments(np.array([[35.0, 0.0], [35.0, 0.5], [35.0, -0.5]]))  # 5 m from a, 1 m from the boat
    r3, c3 = _moments(np.array([[80.0, 80.0], [80.5, 80.0], [81.0, 80.0]]))  # clutter
    times = np.array([0.0, 1.0, 2.0, 3.0])
    plots = PlotLog(
        times,
        (np.array([c1, c2, c3]), np.array([c3]), np.array([c1]), np.array([c1])),
        None,
        np.zeros((4, 2)),
        (np.array([r1, r2, r3]), np.array([r3]), None, np.array([r1])),  # scan 2 is a radar scan: no clusters
    )
    s = lidar_return_samples(plots, truth)
    assert s is not None and set(s) == {"a", "b"}
    a = s["a"]
    # Scans 0, 1, 3 are lidar; at 3 (t = 3) the truth has ended: NaN range, not a missed detection.
    np.testing.assert_allclose(a.target_range, [30.0, 30.0, np.nan])
    np.testing.assert_allclose(a.detected, [1.0, 0.0, np.nan])
    # Without the boat as don't-care, the cluster 5 m away joins a's return.
    assert a.points[0] == 7
    with_boat = lidar_return_samples(plots, truth, dont_care=boat)
    assert with_boat is not None
    a = with_boat["a"]
    assert a.points[0] == 4 and a.points[1] == 0
    assert a.depth[0] == pytest.approx(np.sqrt(0.5)) and a.width[0] == pytest.approx(np.sqrt(0.5))
    assert np.isnan(a.depth[1])
    assert with_boat["b"].detected.tolist()[:2] == [0.0, 0.0]
    assert lidar_return_samples(PlotLog(times, plots.positions), truth) is None  # no cluster moments kept


def _sample(rng: np.random.Generator, n: int, thickness: float, pd: float, points: float = 40.0) -> LidarReturnSample:
    r = rng.uniform(5.0, 95.0, n)
    det = rng.random(n) < pd
    pts = np.where(det, rng.poisson(points, n) + 3.0, 0.0)
    nan = np.where(det, 1.0, np.nan)
    return LidarReturnSample(
        r,
        pts,
        nan * np.abs(rng.normal(0.5, 0.05, n)),
        nan * np.abs(rng.normal(2.0, 0.2, n)),
        nan * thickness * rng.lognormal(0, 0.2, n),
    )


def test_lidar_terms_name_the_parameter_and_its_direction():
    rng = np.random.default_rng(1)
    real = [{"a": _sample(rng, 600, 0.02, 0.8)}]
    same = [{"a": _sample(rng, 600, 0.02, 0.8)}]
    thick = [{"a": _sample(rng, 600, 0.10, 0.8)}]
    lossy = [{"a": _sample(rng, 600, 0.02, 0.4, points=20.0)}]
    o = ScoreOptions(n_boot=100)
    t = lidar_terms(real, thick, o)
    assert t["thickness_25_50m"].resolved and t["thickness_25_50m"].difference > 0
    assert "too thick" in t["thickness_25_50m"].sentence()
    assert not t["pd_25_50m"].resolved
    t = lidar_terms(real, lossy, o)
    assert t["pd_50_100m"].resolved and t["pd_50_100m"].difference < 0
    assert t["points_0_25m"].resolved and "too few" in t["points_0_25m"].sentence()
    resolved_same = sum(v.resolved for v in lidar_terms(real, same, o).values())
    assert resolved_same <= 2  # 15 terms at 95 %: a couple may be by chance
    s_same, s_thick, s_lossy = (lidar_returns_score(real, x, o) for x in (same, thick, lossy))
    assert s_same.value < 0.05 < s_thick.value and s_same.value < s_lossy.value
    assert s_thick.ci_low > s_same.value
    assert s_thick.counts["d_thickness_25_50m"] > 0.5 and s_thick.counts["d_pd_25_50m"] < 0.1
    again = lidar_returns_score(real, thick, o)
    assert (again.value, again.ci_low, again.ci_high) == (s_thick.value, s_thick.ci_low, s_thick.ci_high)


def _pass(rng: np.random.Generator, n: int = 300, noise: float = 0.05, shift: float = 0.0) -> LidarReturnSample:
    """A target passing at 10–20 m: its returns' width follows its aspect along the pass (a shared pattern, 1–3 m),
    plus independent per-scan noise; every scan has a return."""
    t = np.linspace(0.0, 1.0, n)
    width = 2.0 + np.sin(2 * np.pi * t) + shift + rng.normal(0.0, noise, n)
    ones = np.ones(n)
    return LidarReturnSample(15.0 + 5.0 * np.cos(np.pi * t), 40.0 * ones, 0.3 * ones, width, 0.05 * ones)


def test_time_design_residuals_hand_values():
    spec = lidar_term_specs()["width_0_25m"]
    ones = np.ones(4)
    a = LidarReturnSample(np.array([10.0, 10.0, 30.0, 10.0]), 9 * ones, ones, np.array([1.0, 3.0, 7.0, 5.0]), ones)
    b = LidarReturnSample(np.array([10.0, 10.0, 10.0, 10.0]), 9 * ones, ones, np.array([3.0, 5.0, 2.0, 7.0]), ones)
    # pooled finite values of target "t": scan indices 0,1,3 (run a; scan 2 is beyond 25 m) and 0,1,2,3 (run b), N = 7,
    # B = round(√7) = 3 equal-count bins of the index: cuts at the 1/3 and 2/3 quantiles of (0,0,1,1,2,3,3) = 1, 2
    # (a value on a cut goes up) → bins {0,0} (mean of 1, 3: 2), {1,1} (3, 5: 4), {2,3,3} (2, 5, 7: 14/3); dof √(7/4)
    res = time_design_residuals([spec.series(a), spec.series(b)], ["t", "t"])
    dof = np.sqrt(7 / 4)
    np.testing.assert_allclose(res[0], np.array([-1.0, -1.0, np.nan, 1 / 3]) * dof)
    np.testing.assert_allclose(res[1], np.array([1.0, 1.0, -8 / 3, 7 / 3]) * dof)


def test_time_design_gives_intervals_the_size_of_the_sampling_spread():
    """Two sides sharing a pass's aspect pattern: without the design the difference's interval is many times the
    difference's real spread between pairs (blocks draw more or fewer of the pattern's phases); with it, near it —
    and a real width error of 0.05 m is then resolved."""
    o_on, o_off = ScoreOptions(n_boot=200, lidar_design=True), ScoreOptions(n_boot=200)
    diffs, se_on, se_off, held = [], [], [], 0
    for k in range(12):
        rng = np.random.default_rng(100 + k)
        a, b = [{"v": _pass(rng)}], [{"v": _pass(rng)}]
        on, off = lidar_terms(a, b, o_on)["width_0_25m"], lidar_terms(a, b, o_off)["width_0_25m"]
        assert on.difference == off.difference  # the value is the design's to leave alone
        diffs.append(on.difference)
        se_on.append(np.diff(on.difference_ci)[0] / 3.92)
        se_off.append(np.diff(off.difference_ci)[0] / 3.92)
        held += on.difference_ci[0] <= 0.0 <= on.difference_ci[1]
    sd = 0.05 * np.sqrt(2 / 300)  # the difference of two means of 300 independent N(0, 0.05²)
    assert np.mean(se_off) > 5 * sd and 0.7 * sd < np.mean(se_on) < 2.0 * sd, (np.mean(se_off), np.mean(se_on), sd)
    assert np.std(diffs, ddof=1) < 2.0 * sd and held >= 10
    rng = np.random.default_rng(7)
    wider = lidar_terms([{"v": _pass(rng)}], [{"v": _pass(rng, shift=0.05)}], o_on)["width_0_25m"]
    assert wider.resolved and "too wide" in wider.sentence()
    assert not lidar_terms([{"v": _pass(rng)}], [{"v": _pass(rng, shift=0.05)}], o_off)["width_0_25m"].resolved


def test_combined_distance_is_the_family_weighted_mean():
    assert sum(FAMILY_WEIGHTS.values()) == pytest.approx(1.0)
    x = {"pd_0_1m": [np.r_[np.ones(20), np.zeros(20)]], "pd_1_2m": [np.ones(40)], "thickness_0_1m": [np.full(40, 0.1)]}
    y = {"pd_0_1m": [np.ones(40)], "pd_1_2m": [np.ones(40)], "thickness_0_1m": [np.full(40, 0.1)]}
    value, d = combined_distance(x, y, 10)
    # Pd family: mean of the two bins' distances; thickness family: 0; equal weights over the two families.
    assert d["pd_0_1m"] == pytest.approx(bernoulli_hellinger(0.5, 1.0)) and d["pd_1_2m"] == 0.0
    assert value == pytest.approx(0.5 * (d["pd_0_1m"] / 2) + 0.5 * 0.0)
    assert len(lidar_term_specs()) == 15


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 50), st.integers(2, 50), st.integers(0, 10_000))
def test_the_1d_closed_form_is_the_score_s_gaussian_hellinger(n, m, seed):
    from seatwin.evaluation.lidar_terms import gaussian_hellinger_1d
    from seatwin.evaluation.score import error_hellinger

    rng = np.random.default_rng(seed)
    x, y = rng.normal(0.0, rng.uniform(0.001, 2.0), n), rng.normal(rng.normal(0, 2), rng.uniform(0.001, 2.0), m)
    assert gaussian_hellinger_1d(x, y, 0.01) == pytest.approx(error_hellinger(x[:, None], y[:, None], 0.01), abs=1e-9)


def test_bernoulli_hellinger_hand_values():
    assert bernoulli_hellinger(0.5, 0.5) == 0.0
    assert bernoulli_hellinger(0.0, 1.0) == pytest.approx(1.0)
    assert bernoulli_hellinger(0.5, 1.0) == pytest.approx(np.sqrt(1 - np.sqrt(0.5)))


def _tracks(rows: list[tuple[float, int, float, float]], scan_times: np.ndarray) -> Tracks:
    t, ids, n, e = (np.array(x, float) for x in zip(*rows))
    state = np.column_stack([n, np.zeros(len(t)), e, np.zeros(len(t))])
    return Tracks(
        t, ids.astype(int), np.full(len(t), 0.9), state, np.tile(np.eye(4), (len(t), 1, 1)), np.ones(len(t), bool), scan_times
    )


def test_false_tracks_count_once_per_track_whatever_its_length():
    truth = TruthSet({"a": _still("a", 0.0, 0.0, 200.0)}, "<test>")
    scans = np.arange(0.0, 120.0, 1.0)  # 2 minutes of 1 s scans
    rows = [(t, 1, 0.5, 0.0) for t in scans]  # the target's track: never false
    rows += [(t, 2, 300.0, 0.0) for t in scans[10:110]]  # one long ghost (100 scans)
    rows += [(t, 3, 0.0, 300.0) for t in scans[50:53]]  # a short one
    rows += [(t, 4, 0.0 if t < 61 else 100.0, 0.0) for t in scans[60:63]]  # 2 of 3 rows far: false
    rows += [(t, 5, 0.0 if t < 72 else 100.0, 0.0) for t in scans[70:74]]  # 2 of 4 far: not more than half
    births, times = false_track_births(_tracks(rows, scans), truth, 25.0)
    assert times.tolist() == scans.tolist()
    assert births.sum() == 3 and births[10] == 1 and births[50] == 1 and births[60] == 1
    short = [r for r in rows if r[1] != 2] + [(t, 2, 300.0, 0.0) for t in scans[10:12]]
    real, synth = _tracks(rows, scans), _tracks(short, scans)
    none = _tracks([r for r in rows if r[1] == 1], scans)
    o = ScoreOptions(n_boot=50)
    # The ghost's length does not matter: the same 3 false tracks in 2 minutes on both sides.
    assert false_track_score([real], [synth], truth, o).value == 0.0
    s = false_track_score([real], [none], truth, o)
    assert s.counts["rate_real_per_min"] == pytest.approx(1.5) and s.counts["rate_synthetic_per_min"] == 0.0
    assert s.value == pytest.approx(poisson_hellinger(1.5, 0.0))
    assert s.ci_low <= s.value <= s.ci_high
    again = false_track_score([real], [none], truth, o)
    assert (again.ci_low, again.ci_high) == (s.ci_low, s.ci_high)


def test_score_runs_carries_the_new_terms_and_the_former_false_track_value():
    from seatwin.evaluation import evaluate
    from seatwin.evaluation.sensor_score import score_runs_with_sensor_terms

    truth = TruthSet({"a": _still("a", 0.0, 0.0, 200.0)}, "<test>")
    scans = np.arange(0.0, 60.0, 1.0)
    rows = [(t, 1, 0.5, 0.0) for t in scans] + [(t, 2, 300.0, 0.0) for t in scans[5:55]]
    tr = _tracks(rows, scans)
    ev = evaluate(tr, truth, 10.0)
    f = score_runs_with_sensor_terms([tr], [tr], truth, [ev], [ev], ScoreOptions(n_boot=20))
    assert f.plots["false_tracks"].value == 0.0 and f.plots["false_tracks"].counts["alive_hellinger"] == 0.0
    assert f.plots["lidar_returns"].value is None and "no lidar cluster moments" in f.plots["lidar_returns"].reason
    assert "lidar_returns" in f.overall.reason


def test_lidar_scan_keeps_cluster_moments_and_the_plot_log_travels():
    """The perception hands each cluster's count and covariance on (``cluster_moment_rows``), ``track_scans`` keeps
    them with the sensor position, and a campaign job's JSON carries them (None for a scan that is no lidar sweep)."""
    import json

    from seatwin.campaign.job import tracks_from_json, tracks_to_json
    from seatwin.perception.frames import SensorPose
    from seatwin.perception.lidar import cluster_moment_rows, lidar_scan
    from seatwin.perception.measurements import MeasurementKind, Scan
    from seatwin.pipeline.track import track_scans

    rng = np.random.default_rng(3)
    eye = np.eye(3)
    pose = SensorPose(np.array([5.0, -2.0, 0.0]), eye, eye, np.array([5.0, -2.0, 0.0]))
    boat = np.column_stack([rng.normal(30.0, 0.05, 40), rng.normal(0.0, 1.5, 40), rng.uniform(-1.0, 0.5, 40)])
    scans = [lidar_scan(boat, float(t), pose) for t in range(12)]
    rows = cluster_moment_rows(scans[0])
    assert rows is not None and rows.shape == (1, 4) and rows[0, 0] == 40
    np.testing.assert_allclose(rows[0, 1:], np.cov(boat[:, :2], rowvar=False, ddof=0).ravel()[[0, 1, 3]], atol=1e-9)
    radar = Scan(12.0, "radar", MeasurementKind.RANGE_BEARING, np.array([[100.0, 0.0]]))
    assert cluster_moment_rows(radar) is None
    tracks = track_scans([*scans, radar], "synthetic")
    log = tracks.plots
    assert log is not None and log.clusters is not None and log.sensor is not None
    assert log.clusters[-1] is None and log.clusters[0].shape == (1, 4)
    np.testing.assert_allclose(log.sensor[0], [5.0, -2.0])
    back = tracks_from_json(json.loads(json.dumps(tracks_to_json(tracks)))).plots
    assert back is not None and back.clusters is not None and back.clusters[-1] is None
    np.testing.assert_array_equal(back.clusters[0], log.clusters[0])
    np.testing.assert_array_equal(back.sensor, log.sensor)
    truth = TruthSet({"a": _still("a", 30.0, 0.0, 20.0)}, "<test>")
    s = lidar_return_samples(back, truth)
    assert s is not None and s["a"].points.tolist() == [40.0] * 12
    u = boat[:, :2].mean(axis=0)  # the points are in the sensor frame: the world centroid minus the sensor
    u /= np.linalg.norm(u)
    cov = np.cov(boat[:, :2], rowvar=False, ddof=0)
    assert s["a"].depth[0] == pytest.approx(np.sqrt(u @ cov @ u), rel=1e-9)  # along the line of sight from the sensor


def test_score_runs_with_sensor_terms_reports_the_lidar_terms_one_by_one():
    """Two lidar runs that differ only in their returns' thickness: S7 > 0, the thickness term says "too thick",
    and the JSON carries each term's sentence (what ``seatwin compare`` prints for the resolved ones)."""
    from seatwin.evaluation import evaluate
    from seatwin.evaluation.sensor_score import score_runs_with_sensor_terms

    truth = TruthSet({"a": _still("a", 40.0, 0.0, 100.0)}, "<test>")
    times = np.arange(0.0, 60.0, 0.5)

    def run(thick: float, seed: int) -> Tracks:
        rng = np.random.default_rng(seed)
        rows, cents = [], []
        for _ in times:
            pts = np.column_stack([rng.normal(40.0, thick, 30), rng.normal(0.0, 2.0, 30)])
            r, c = _moments(pts)
            rows.append(r[None])
            cents.append(c[None])
        tr = _tracks([(t, 1, 40.0, 0.0) for t in times], times)
        tr.plots = PlotLog(times, tuple(cents), None, np.zeros((len(times), 2)), tuple(rows))
        return tr

    real, synth = run(0.05, 1), run(0.3, 2)
    ev_r, ev_s = evaluate(real, truth, 10.0), evaluate(synth, truth, 10.0)
    f = score_runs_with_sensor_terms([real], [synth], truth, [ev_r], [ev_s], ScoreOptions(n_boot=40))
    assert f.plots["lidar_returns"].value > 0.1 and f.plots["lidar_returns"].counts["d_thickness_25_50m"] > 0.5
    t = f.lidar_terms["thickness_25_50m"]
    assert t.resolved and t.difference > 0 and "too thick" in t.sentence()
    d = f.to_dict()
    assert "too thick" in d["lidar_terms"]["thickness_25_50m"]["sentence"] and d["lidar_returns"]["value"] > 0.1
    same = score_runs_with_sensor_terms([real], [run(0.05, 3)], truth, [ev_r], [ev_r], ScoreOptions(n_boot=40))
    assert same.plots["lidar_returns"].value < f.plots["lidar_returns"].value


def test_combined_distance_does_not_depend_on_the_hash_seed():
    """The families are summed in a fixed order: a Ray worker (another PYTHONHASHSEED) gives the driver's bits."""
    code = (
        "import numpy as np; from seatwin.evaluation.lidar_terms import combined_distance\n"
        "rng = np.random.default_rng(3)\n"
        "keys = ['pd_0', 'points_0', 'depth_0', 'width_0', 'thickness_0', 'depth_1', 'width_1']\n"
        "r = {k: [rng.uniform(0.2, 0.9, 40) if k.startswith('pd') else rng.uniform(0.5, 3, 40)] for k in keys}\n"
        "s = {k: [v[0] * rng.uniform(0.7, 1.3, 40)] for k, v in r.items()}\n"
        "print(repr(combined_distance(r, s, 5)[0]))\n"
    )
    outs = {
        subprocess.run(
            [sys.executable, "-c", code],
            env=os.environ | {"PYTHONHASHSEED": str(seed)},
            capture_output=True,
            text=True,
            check=True,
        ).stdout
        for seed in range(12)
    }
    assert len(outs) == 1, outs
