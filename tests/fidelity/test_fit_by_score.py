"""``seatwin radar fit --by-score`` (seatwin.fidelity.radar_fit.fit_by_score): the fit minimises the radar sensor
score's own distances, on a recording made by a known radar model (the toy dataset)."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.fidelity.radar_fit import SCORE_FIT_TERMS, fit_by_score
from seatwin.fidelity.synthetic import TOY_RADAR, toy_dataset
from seatwin.sensors.radar import load_radar_config
from seatwin.sensors.radar.config import RadarConfig


def test_fit_by_score_recovers_the_known_model():
    data = toy_dataset()
    fit = fit_by_score(data, RadarConfig(max_range_m=1500.0, detection={"snr_ref_db": 15.0}), n_boot=100)
    p = fit.parameters
    assert set(p) == set(SCORE_FIT_TERMS)
    true = TOY_RADAR["noise"]
    assert p["bearing_bias_deg"]["estimate"] == pytest.approx(true["bearing_bias_deg"], abs=0.2)
    assert p["bearing_sigma_deg"]["estimate"] == pytest.approx(true["bearing_sigma_deg"], rel=0.3)
    assert p["range_sigma_m"]["estimate"] == pytest.approx(true["range_sigma_m"], rel=0.3)
    assert p["clutter_density_per_km2"]["estimate"] == pytest.approx(TOY_RADAR["clutter"]["density_per_km2"], rel=0.3)
    assert p["pd_max"]["estimate"] == pytest.approx(TOY_RADAR["detection"]["pd_max"], abs=0.15)
    for name, v in p.items():
        assert v["ci95"][0] <= v["estimate"] <= v["ci95"][1], name
    assert fit.config.noise.bearing_bias_deg == p["bearing_bias_deg"]["estimate"]
    assert len(fit.steps) == 3 and all(0.0 <= s["sensor_score"] <= 1.0 for s in fit.steps)
    # Far from where it started (the built-in model: bias 0, σ_θ 0.5°, σ_r 3 m): the fit moved towards the data.
    assert fit.sensor_score["score"]["value"] < 0.5
    again = fit_by_score(data, RadarConfig(max_range_m=1500.0, detection={"snr_ref_db": 15.0}), n_boot=100)
    assert again.to_dict() == fit.to_dict()  # reproducible


def test_radar_fit_by_score_cli(tmp_path, capsys):
    from seatwin.fidelity.synthetic import write_joyride_mat

    mat = write_joyride_mat(toy_dataset(n=80), tmp_path / "toy.mat")
    out = tmp_path / "radar.yaml"
    assert run(["radar", "fit", str(mat), "--out", str(out), "--boot", "20", "--by-score"]) == 0
    cfg = load_radar_config(out)
    sf = cfg.fit["score_fit"]
    assert cfg.noise.bearing_sigma_deg == pytest.approx(sf["parameters"]["bearing_sigma_deg"]["estimate"])
    assert np.isfinite(sf["sensor_score"]["score"]["value"])
    text = capsys.readouterr().out
    assert "fitted by the radar sensor score" in text and "bearing_bias_deg" in text
    bag = tmp_path / "run.mcap"
    bag.write_bytes(b"not a bag")
    assert run(["radar", "fit", str(bag), "--out", str(tmp_path / "b.yaml"), "--by-score"]) == 2
    assert "--by-score" in capsys.readouterr().err
