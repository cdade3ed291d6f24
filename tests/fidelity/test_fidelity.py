"""The fidelity method end to end on a toy joyride file (and on the real one when present)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from seatwin.cli.main import run
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
    code = run(["fidelity", "joyride", str(toy_mat), "--out", str(out), "--fit-on", "first-half", "--seeds", "2",
                "--boot", "50", "--fit-boot", "5", "--no-html"])
    assert code == 0
    j = json.loads((out / "fidelity.json").read_text())
    for key in ("ahed", "ahed_ci", "n_common", "n_only_real", "n_only_synthetic", "fit_on", "seeds"):
        assert key in j
    assert j["fit_on"] == "first-half" and j["seeds"] == 2
    assert set(j["models"]) == {"default", "fitted"}
    assert set(j["models"]["fitted"]["agents"]) == {"jipda", "gnn"}
    if j["ahed"] is not None:
        assert 0.0 <= j["ahed"] <= 1.0
        assert j["ahed_ci"][0] <= j["ahed"] <= j["ahed_ci"][1]
    # The fit saw only the first half.
    assert j["radar_fit"]["n_scans"] == 40
    assert j["window"][0] == pytest.approx(load_joyride(toy_mat).time[40])
    assert "What drives the remaining distance" in (out / "fidelity.md").read_text()


def test_fidelity_bad_input(tmp_path, capsys):
    assert run(["fidelity", "joyride", str(tmp_path / "nope.mat"), "--out", str(tmp_path / "o")]) == 2
    bad = tmp_path / "bad.mat"
    bad.write_text("not a mat file")
    assert run(["fidelity", "joyride", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert run(["fidelity", "joyride", str(bad), "--out", str(tmp_path / "o"), "--fit-on", "sideways"]) == 2
    err = capsys.readouterr().err
    assert "fit-on" in err and err.count("\n") == 3


@pytest.mark.slow
def test_fidelity_real_joyride(shared_data, tmp_path):
    out = tmp_path / "real"
    code = run(["fidelity", "joyride", str(shared_data / "joyride" / "joyride.mat"), "--out", str(out),
                "--seeds", "1", "--agents", "jipda", "--boot", "50", "--fit-on", "first-half", "--fit-boot", "5"])
    assert code == 0
    j = json.loads((out / "fidelity.json").read_text())
    assert 0.0 < j["ahed"] < 1.0
    assert j["n_common"] > 0
    assert (out / "index.html").stat().st_size > 10_000


def test_calibrate_bias_needs_a_fit_and_sets_the_tracker_bias(toy_mat, tmp_path, capsys):
    assert run(["fidelity", "joyride", str(toy_mat), "--out", str(tmp_path / "x"), "--calibrate-bias"]) == 2
    assert "calibrate-bias" in capsys.readouterr().err
    out = tmp_path / "cal"
    assert run(["fidelity", "joyride", str(toy_mat), "--out", str(out), "--fit-on", "all", "--calibrate-bias",
                "--seeds", "1", "--agents", "gnn", "--boot", "20", "--fit-boot", "0", "--no-html"]) == 0
    j = json.loads((out / "fidelity.json").read_text())
    assert j["agent"] == "gnn" and j["fit_on"] == "all"
    assert j["tracker_bearing_bias_deg"] == pytest.approx(j["models"]["fitted"]["radar"]["noise"]["bearing_bias_deg"])


@pytest.mark.slow
def test_fidelity_reruns_are_identical(toy_mat, tmp_path):
    args = ["fidelity", "joyride", str(toy_mat), "--fit-on", "first-half", "--seeds", "1", "--agents", "gnn",
            "--boot", "20", "--fit-boot", "3", "--no-html", "--seed", "4"]
    assert run([*args, "--out", str(tmp_path / "a")]) == 0
    assert run([*args, "--out", str(tmp_path / "b")]) == 0
    assert (tmp_path / "a" / "fidelity.json").read_text() == (tmp_path / "b" / "fidelity.json").read_text()
