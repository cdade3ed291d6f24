"""The fidelity method end to end on a toy joyride file (and on the real one when present)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.errors import ParameterError
from seatwin.fidelity.joyride import heading_from_velocity, load_joyride
from seatwin.fidelity.method import block_bootstrap_ci


@pytest.fixture(scope="module")
def toy_mat(tmp_path_factory):
    from seatwin.fidelity.synthetic import toy_dataset, write_joyride_mat

    return write_joyride_mat(toy_dataset(n=80), tmp_path_factory.mktemp("joy") / "toy.mat", invalid_rows=1)


def test_heading_from_velocity_holds_when_slow():
    h = heading_from_velocity(np.array([0.0, 1.0, 0.1, 0.0]), np.array([0.0, 1.0, 0.0, -2.0]))
    assert h[0] == pytest.approx(np.pi / 4) and h[1] == pytest.approx(np.pi / 4)
    assert h[2] == pytest.approx(np.pi / 4) and h[3] == pytest.approx(-np.pi / 2)


def test_load_counts_invalid_rows(toy_mat):
    d = load_joyride(toy_mat)
    assert len(d) == 80 and d.n_invalid == 1
    assert all(np.isfinite(p).all() for p in d.plots)


def test_block_bootstrap_interval_contains_the_mean():
    v = [np.linspace(0.2, 0.8, 50), np.full(30, 0.5)]
    lo, hi = block_bootstrap_ci(v, 300, 5)
    m = np.concatenate(v).mean()
    assert lo <= m <= hi and hi - lo < 0.2
    assert block_bootstrap_ci(v, 300, 5) == (lo, hi)  # seeded


def test_fidelity_cli_on_toy_data(toy_mat, tmp_path):
    out = tmp_path / "fid"
    code = run(
        [
            "fidelity",
            "joyride",
            str(toy_mat),
            "--out",
            str(out),
            "--fit-on",
            "first-half",
            "--seeds",
            "2",
            "--boot",
            "50",
            "--fit-boot",
            "5",
            "--no-html",
        ]
    )
    assert code == 0
    j = json.loads((out / "fidelity.json").read_text())
    for key in ("ahed", "ahed_ci", "n_common", "n_only_real", "n_only_synthetic", "fit_on", "seeds"):
        assert key in j
    assert j["fit_on"] == "first-half" and j["seeds"] == 2
    assert set(j["models"]) == {"default", "fitted"}
    assert set(j["models"]["fitted"]["agents"]) == {"jipda", "gnn"}
    # The unpaired score beside AHED: per model and agent, and the ranking (primary agent, best first).
    assert [r["model"] for r in j["ranking"]] and {r["model"] for r in j["ranking"]} == {"default", "fitted"}
    defined = [r["score"] for r in j["ranking"] if r["score"] is not None]
    assert defined == sorted(defined) and all(r["reason"] for r in j["ranking"] if r["score"] is None)
    assert j["score"] == j["models"]["fitted"]["agents"]["jipda"]["score"]
    assert "targets" in j["models"]["fitted"]["agents"]["gnn"]["score_parts"]
    if j["ahed"] is not None:
        assert 0.0 <= j["ahed"] <= 1.0
        assert j["ahed_ci"][0] <= j["ahed"] <= j["ahed_ci"][1]
    # The fit saw only the first half.
    assert j["radar_fit"]["n_scans"] == 40
    assert j["window"][0] == pytest.approx(load_joyride(toy_mat).time[40])
    assert "What drives the remaining distance" in (out / "fidelity.md").read_text()
    assert "Models ranked by fidelity score" in (out / "fidelity.md").read_text()


def test_fidelity_bad_input(tmp_path, capsys):
    assert run(["fidelity", "joyride", str(tmp_path / "nope.mat"), "--out", str(tmp_path / "o")]) == 2
    bad = tmp_path / "bad.mat"
    bad.write_text("not a mat file")
    assert run(["fidelity", "joyride", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert run(["fidelity", "joyride", str(bad), "--out", str(tmp_path / "o"), "--fit-on", "sideways"]) == 2
    err = capsys.readouterr().err
    assert "fit-on" in err and err.count("\n") == 3


@pytest.mark.slow
def test_fidelity_real_joyride_ranks_the_fitted_model_first(shared_data, tmp_path):
    """Issue 13's acceptance check on the real data, as the method guarantees it (issue 22): fitted on the first half,
    scored on the held-out half against the six wrong models, 5 seeds each, no model's score is below the fitted
    model's interval (not one fixed-seed order); the plot-level bearing-bias term resolves what the tracker-level
    score cannot: no_bias is too far clockwise. (The fitted model is closer to the real bias, by 0.82°, but that
    lead is not resolved on the held-out half — [−0.03, 1.66]°: the real bias moves from −1.98° in the first half
    to −1.58° in the second, and the fitted model, −2.16°, is itself resolved as 0.58° too far anticlockwise.)"""
    out = tmp_path / "real"
    args = ["fidelity", "joyride", str(shared_data / "joyride" / "joyride.mat"), "--out", str(out), "--seeds", "5"]
    args += ["--agents", "jipda", "--boot", "100", "--fit-on", "first-half", "--fit-boot", "5", "--ablations"]
    assert run(args) == 0
    j = json.loads((out / "fidelity.json").read_text())
    assert 0.0 < j["ahed"] < 1.0
    assert j["n_common"] > 0
    ranking = j["ranking"]
    assert {r["model"] for r in ranking} == {"fitted", "default", "no_bias", "wide_noise", "low_pd", "heavy_clutter", "too_clean"}
    by_model = {r["model"]: r for r in ranking}
    fitted = by_model["fitted"]
    assert fitted["ci_low"] <= fitted["score"] <= fitted["ci_high"]
    for r in ranking:
        assert r["score"] >= fitted["ci_low"], (r["model"], ranking)  # the fitted model is never beaten outside its interval
    for clearly_worse in ("default", "heavy_clutter", "too_clean"):
        assert by_model[clearly_worse]["score"] > fitted["ci_high"], (clearly_worse, ranking)
    real_bias = j["models"]["fitted"]["plot_terms"]["bearing_bias"]["real"]
    assert -2.5 < real_bias < -1.0  # the real radar's bearing bias, from its plots against GNSS
    no_bias = j["models"]["no_bias"]["plot_terms"]["bearing_bias"]
    assert no_bias["resolved"] and no_bias["difference_ci"][0] > 0.0 and "too far clockwise" in no_bias["sentence"]
    assert j["plot_term_leads"]["no_bias"]["bearing_bias"]["value"] > 0.0  # closer, though not resolved (docstring)
    # The radar sensor score (in S5 in place of the clutter term): the fitted model's lead over the grossly wrong
    # models is resolved; over no_bias it is not (0.047 [−0.011, 0.092] with the rule off, docs/validation.md).
    assert "radar_sensor" in j["models"]["fitted"]["agents"]["jipda"]["score_parts"]
    for worse in ("default", "too_clean", "wide_noise"):
        assert j["plot_term_leads"][worse]["radar_sensor_score"]["resolved"], (worse, j["plot_term_leads"][worse])
    assert "untruthed1" in j["assumptions"]["untruthed_vessels"]  # the boat without GNSS: in the replica, don't-care in the score
    md = (out / "fidelity.md").read_text()
    assert "## Radar plot-level terms" in md and "bearing bias" in md
    page = (out / "index.html").read_text()
    assert len(page) > 10_000
    assert "Models ranked by fidelity score" in page and 'alt="fidelity score by model"' in page
    assert "held-out second half" in page and "agent JIPDA" in page  # which half was fitted; the agent on each row
    assert "(untruthed1 (113 scans)) are in the replica and are don&#x27;t-care regions" in page


def test_calibrate_bias_needs_a_fit_and_sets_the_tracker_bias(toy_mat, tmp_path, capsys):
    assert run(["fidelity", "joyride", str(toy_mat), "--out", str(tmp_path / "x"), "--calibrate-bias"]) == 2
    assert "calibrate-bias" in capsys.readouterr().err
    out = tmp_path / "cal"
    assert (
        run(
            [
                "fidelity",
                "joyride",
                str(toy_mat),
                "--out",
                str(out),
                "--fit-on",
                "all",
                "--calibrate-bias",
                "--seeds",
                "1",
                "--agents",
                "gnn",
                "--boot",
                "20",
                "--fit-boot",
                "0",
                "--no-html",
            ]
        )
        == 0
    )
    j = json.loads((out / "fidelity.json").read_text())
    assert j["agent"] == "gnn" and j["fit_on"] == "all"
    assert j["tracker_bearing_bias_deg"] == pytest.approx(j["models"]["fitted"]["radar"]["noise"]["bearing_bias_deg"])


@pytest.mark.slow
def test_fidelity_reruns_are_identical(toy_mat, tmp_path, capsys):
    args = [
        "fidelity",
        "joyride",
        str(toy_mat),
        "--fit-on",
        "first-half",
        "--seeds",
        "1",
        "--agents",
        "gnn",
        "--boot",
        "20",
        "--fit-boot",
        "3",
        "--no-html",
        "--seed",
        "4",
    ]
    assert run([*args, "--out", str(tmp_path / "a")]) == 0
    assert run([*args, "--out", str(tmp_path / "b")]) == 0
    assert (tmp_path / "a" / "fidelity.json").read_text() == (tmp_path / "b" / "fidelity.json").read_text()
    # the same command into the same folder resumes; other settings there are refused, the results kept
    before = (tmp_path / "a" / "fidelity.json").read_text()
    assert run([*args, "--out", str(tmp_path / "a")]) == 0
    assert (tmp_path / "a" / "fidelity.json").read_text() == before
    capsys.readouterr()
    assert run([*args[:-1], "5", "--out", str(tmp_path / "a")]) == 2
    assert "holds the results of another fidelity (other settings)" in capsys.readouterr().err
    assert (tmp_path / "a" / "fidelity.json").read_text() == before


def test_replica_subset_draws_as_in_the_whole_recording():
    """The replica runs through the simulation loop; a subset of scans keeps the scan index as frame index."""
    from seatwin.fidelity.joyride import replica_scene, simulate_replica
    from seatwin.fidelity.synthetic import TOY_RADAR, toy_dataset
    from seatwin.sensors.radar import RadarConfig, RadarModel

    data = toy_dataset(n=12)
    model = RadarModel(RadarConfig(**TOY_RADAR), seed=3)
    scene = replica_scene(data)
    whole = simulate_replica(data, model, scene)
    part = simulate_replica(data, model, scene, indices=[2, 5, 11])
    assert [s.time for s in part] == [float(data.time[k]) for k in (2, 5, 11)]
    for k, s in zip((2, 5, 11), part):
        np.testing.assert_array_equal(s.positions, whole[k].positions)
    with pytest.raises(ParameterError) as exc:
        simulate_replica(data, model, scene, indices=[5, 2])
    assert exc.value.param == "indices"


@pytest.mark.parametrize(
    ("changes", "param"),
    [
        ({"fit_on": "sideways"}, "fit_on"),
        ({"calibrate_bias": True}, "calibrate_bias"),
        ({"seeds": 0}, "seeds"),
        ({"agents": ()}, "agents"),
        ({"agents": ("jipda", "kalman")}, "agents"),
        ({"agents": ("gnn", "gnn")}, "agents"),
        ({"clutter": "rain"}, "clutter"),
        ({"n_boot": 0}, "n_boot"),
    ],
)
def test_fidelity_options_name_the_bad_parameter(changes, param):
    from seatwin.fidelity import FidelityOptions

    with pytest.raises(ParameterError) as exc:
        FidelityOptions().with_(**changes)
    assert exc.value.param == param and "--" not in str(exc.value)
    assert FidelityOptions().with_(fit_on="all", calibrate_bias=True).calibrate_bias


def test_typed_result_writes_the_json(toy_mat, tmp_path):
    from seatwin.fidelity import FidelityResult, run_fidelity, write_fidelity

    result = run_fidelity(str(toy_mat), seeds=2, agents=("gnn",), n_boot=20, fit_boot=0, fit_on="all")
    assert isinstance(result, FidelityResult) and result.primary_model == "fitted" and result.primary_agent == "gnn"
    prim = result.primary
    assert [s.seed for s in prim.per_seed] == [0, 1] and prim.floor_pairs <= 1
    write_fidelity(tmp_path, result, html=False)
    j = json.loads((tmp_path / "fidelity.json").read_text())
    assert j["ahed"] == prim.ahed and j["models"]["fitted"]["agents"]["gnn"]["per_seed"][1]["seed"] == 1
    assert list(j)[:5] == ["ahed", "ahed_ci", "n_common", "n_only_real", "n_only_synthetic"] and list(j)[-1] == "dataset"


def test_seeds_run_as_engine_jobs_and_resume(toy_mat, tmp_path, monkeypatch):
    """Every (model, seed) is a campaign-engine job kept in jobs_in/jobs: a second run finds them all
    finished, runs none, and gives the same result."""
    from seatwin.fidelity import jobs as fjobs
    from seatwin.fidelity import run_fidelity

    kw = dict(seeds=2, agents=("gnn",), n_boot=20, fit_boot=0, fit_on="all")
    first = run_fidelity(str(toy_mat), jobs_in=tmp_path, **kw)
    assert len(list((tmp_path / "jobs").glob("*.json"))) == 2 * 2  # default and fitted, two seeds each
    calls = []
    monkeypatch.setattr(fjobs, "seed_run", lambda p, i: calls.append(p) or {})
    again = run_fidelity(str(toy_mat), jobs_in=tmp_path, **kw)
    assert calls == [] and again.primary.ahed == first.primary.ahed and again.primary.score == first.primary.score


def test_untruthed_vessels_are_long_off_target_tracks_and_become_dont_care_truth():
    from seatwin.evaluation.tracks_io import Tracks
    from seatwin.fidelity.joyride import JoyrideData, untruthed_vessels, vessels_truth

    n = 40
    t = 100.0 + np.arange(n)
    target = np.column_stack([np.zeros(n), np.zeros(n), 10.0 * np.arange(n), np.full(n, 10.0)])
    data = JoyrideData(t, [np.empty((0, 2))] * n, target, np.zeros((n, 4)))
    # (time, id, north, east): 1 follows the target; 2 a boat 500 m north for 30 scans, travelling 290 m;
    # 3 a blip of 5 scans; 4 persistent clutter that stays put (within 20 m) for all 40 scans
    rows = []
    for k in range(n):
        rows.append((t[k], 1, 2.0, target[k, 2]))
        if 5 <= k < 35:
            rows.append((t[k], 2, 500.0 + 10.0 * k, 0.0))
        if k < 5:
            rows.append((t[k], 3, -300.0, 0.0))
        rows.append((t[k], 4, -400.0 + 0.5 * k, 100.0))
    time, ids, north, east = (np.array(c) for c in zip(*rows))
    state = np.column_stack([north, np.zeros(len(rows)), east, np.zeros(len(rows))])
    tracks = Tracks(time, ids, np.full(len(rows), 0.9), state, np.tile(np.eye(4), (len(rows), 1, 1)), np.ones(len(rows), bool))
    vessels = untruthed_vessels(tracks, data, gate_m=60.0)
    assert list(vessels) == ["untruthed1"]
    np.testing.assert_allclose(vessels["untruthed1"][[0, -1], 0], [t[5], t[34]])
    boat = vessels_truth(vessels)["untruthed1"]
    np.testing.assert_allclose(boat.state_at(t[10])[[0, 2]], [600.0, 0.0])
    assert np.isnan(boat.state_at(t[0])).all() and np.isnan(boat.state_at(t[-1])).all()


def test_fidelity_console_and_report_say_what_they_show(toy_mat, tmp_path, capsys):
    """Issue 25, items 2 and 12: counts as integers, 'floor' explained (none with one seed), the HTML's AHED rows name
    their tracking agent (JIPDA and GNN rows looked alike)."""
    import re

    out = tmp_path / "fid"
    argv = ["fidelity", "joyride", str(toy_mat), "--out", str(out), "--fit-on", "first-half", "--seeds", "1"]
    assert run([*argv, "--boot", "30", "--fit-boot", "5", "--no-progress"]) == 0
    printed = capsys.readouterr().out
    assert "floor: AHED between the model's own replicas" in printed and "needs --seeds 2 or more" in printed
    assert re.search(r"common \d+(\.\d)?,", printed) and not re.search(r"common \d+\.0\b", printed)
    page = (out / "index.html").read_text()
    rows = re.findall(r"<tr>(.*?)</tr>", page, re.S)
    ahed_rows = [re.sub(r"<[^>]+>", "|", r) for r in rows if "radar model (seed" in r]
    assert ahed_rows and all("agent JIPDA" in r or "agent GNN" in r for r in ahed_rows), ahed_rows[:2]


def test_no_dont_care_and_plot_terms_on_the_toy_dataset(toy_mat, tmp_path):
    """--no-dont-care switches the rule off (and says so); every model gets the radar plot-level terms, with the
    real and the model's value and the signed difference."""
    out = tmp_path / "off"
    args = ["fidelity", "joyride", str(toy_mat), "--out", str(out), "--fit-on", "all", "--seeds", "2", "--agents", "gnn"]
    assert run([*args, "--boot", "20", "--fit-boot", "0", "--no-html", "--no-dont-care"]) == 0
    j = json.loads((out / "fidelity.json").read_text())
    assert j["assumptions"]["score_dont_care"].startswith("off: ")
    terms = j["models"]["fitted"]["plot_terms"]
    assert {"bearing_bias", "range_bias", "bearing_sigma", "range_sigma", "clutter_per_scan", "clutter_per_km2"} <= set(terms)
    bias = terms["bearing_bias"]
    assert bias["difference"] == pytest.approx(bias["synthetic"] - bias["real"])
    assert bias["difference_ci"][0] <= bias["difference"] <= bias["difference_ci"][1]
    assert -1.0 < bias["real"] < 0.0  # the toy radar's bearing bias is −0.5°
    assert set(j["plot_term_leads"]) == {"default"}
    assert "## Radar plot-level terms" in (out / "fidelity.md").read_text()


def test_fit_by_score_replaces_the_moment_fit(toy_mat):
    """``fit_by="score"``: the fitted model is fit_by_score's (started from the moment fit), with its report."""
    from seatwin.fidelity import run_fidelity

    kw = dict(seeds=1, agents=("gnn",), n_boot=20, fit_boot=0, fit_on="first-half")
    moments, score = run_fidelity(str(toy_mat), **kw), run_fidelity(str(toy_mat), fit_by="score", **kw)
    assert "score_fit" in score.radar_fit and "score_fit" not in moments.radar_fit
    fitted = score.models["fitted"].radar["noise"]
    assert score.radar_fit["score_fit"]["parameters"]["bearing_bias_deg"]["estimate"] == fitted["bearing_bias_deg"]
    assert fitted != moments.models["fitted"].radar["noise"]
