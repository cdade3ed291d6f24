"""``seatwin radar fit`` and ``seatwin radar simulate``."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.sensors.radar import load_radar_config


@pytest.fixture(scope="module")
def toy_mat(tmp_path_factory):
    from seatwin.fidelity.synthetic import toy_dataset, write_joyride_mat

    return write_joyride_mat(toy_dataset(n=60), tmp_path_factory.mktemp("joy") / "toy.mat")


def test_radar_fit_cli_writes_a_loadable_config(toy_mat, tmp_path, capsys):
    out = tmp_path / "radar.yaml"
    assert run(["radar", "fit", str(toy_mat), "--out", str(out), "--boot", "10"]) == 0
    cfg = load_radar_config(out)
    assert cfg.fit is not None and cfg.fit["n_scans"] == 60
    assert cfg.noise.bearing_bias_deg == pytest.approx(-0.5, abs=0.4)
    text = capsys.readouterr().out
    assert "bearing_bias_deg" in text and "±" in text
    assert run(["radar", "fit", str(toy_mat), "--out", str(tmp_path / "h.yaml"), "--boot", "0", "--first-half"]) == 0
    assert load_radar_config(tmp_path / "h.yaml").fit["n_scans"] == 30


def test_radar_fit_cli_bad_input(tmp_path, capsys):
    assert run(["radar", "fit", str(tmp_path / "none.mat"), "--out", str(tmp_path / "r.yaml")]) == 2
    bad = tmp_path / "r.yaml"
    bad.write_text("radar:\n  n_spokes: many\n")
    assert run(["radar", "simulate", "ferry_crossing", "--out", str(tmp_path / "p.csv"), "--radar", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "n_spokes" in err


def test_radar_simulate_csv_and_bag(tmp_path):
    csv_path, bag = tmp_path / "plots.csv", tmp_path / "run"
    args = [
        "radar",
        "simulate",
        "ferry_crossing",
        "--duration",
        "5",
        "--seed",
        "3",
        "--out",
        str(csv_path),
        "--out-bag",
        str(bag),
    ]
    assert run(args) == 0
    rows = list(csv.DictReader(csv_path.open()))
    assert {r["kind"] for r in rows} >= {"vessel", "land"}
    # Bit-identical rerun.
    assert (
        run(["radar", "simulate", "ferry_crossing", "--duration", "5", "--seed", "3", "--out", str(tmp_path / "again.csv")]) == 0
    )
    assert (tmp_path / "again.csv").read_text() == csv_path.read_text()
    from seatwin.recording import open_bag

    with open_bag(bag) as rec:
        assert "/radar/detections" in rec.radar_topics()
        scans = list(rec.radar_scans())
        truth = rec.ground_truth()
    assert len(scans) == 2  # rotations at 0 and 2.5 s of [0, 5) s
    n_csv = sum(1 for r in rows if float(r["time"]) == float(rows[0]["time"]))
    assert len(scans[0].points) == n_csv
    assert np.isfinite(scans[0].points["range"]).all()
    assert len(truth) == 3


def test_radar_fit_from_an_imported_recording(toy_mat, tmp_path):
    run_dir = tmp_path / "joy"
    assert run(["import", "joyride", str(toy_mat), "--out", str(run_dir)]) == 0
    out = tmp_path / "bag.yaml"
    assert run(["radar", "fit", str(run_dir), "--out", str(out), "--boot", "5"]) == 0
    from_bag = load_radar_config(out)
    assert run(["radar", "fit", str(toy_mat), "--out", str(tmp_path / "mat.yaml"), "--boot", "5"]) == 0
    from_mat = load_radar_config(tmp_path / "mat.yaml")
    # Same plots, same truth: same noise estimates (the visible area differs: nominal vs replica geometry).
    assert from_bag.noise.bearing_bias_deg == pytest.approx(from_mat.noise.bearing_bias_deg, abs=1e-6)
    assert from_bag.noise.range_sigma_m == pytest.approx(from_mat.noise.range_sigma_m, rel=1e-6)
    assert from_bag.fit["n_scans"] == from_mat.fit["n_scans"]


def test_radar_simulate_spokes(tmp_path):
    d = tmp_path / "spokes"
    assert run(["radar", "simulate", "ferry_crossing", "--duration", "1", "--spokes-dir", str(d)]) == 0
    z = np.load(d / "scan_000000.npz")
    assert z["radar_spokes"].shape == (int(z["num_spokes"]), int(z["num_samples"]))
    assert z["radar_spokes"].dtype == np.uint8 and z["radar_spokes"].max() > 100
    assert len(z["azimuth"]) == int(z["num_spokes"]) and float(z["range_increment"]) > 0
