"""``seatwin lidar fit`` (seatwin.fidelity.lidar_fit): the lidar model fitted by the lidar sensor-level distance (S7)
on a recording made by a known lidar model drawn at random within realistic ranges."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.errors import InputError, ParameterError
from seatwin.fidelity.lidar_fit import PARAMETERS, candidate_config, config_parameters, fit_lidar_to_recording
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sensors.lidar_config import VLP16, RangeDissipation, load_lidar_config, save_lidar_config
from seatwin.sim.run import scenario_sensors, simulate_scenario
from seatwin.sim.sensors import LidarSensor
from seatwin.sim.settings import SimulationSettings

TRUTH_RANGES = {"range_noise_m": (0.01, 0.1), "drop_probability": (0.5, 0.9), "dissipation_half_range_m": (35.0, 90.0)}
"""Where the test draws the "real" model (σ and half range log-uniform); the draw's seed is the test's."""


def _draw(seed: int) -> dict[str, float]:
    rng = np.random.default_rng(seed)
    out = {}
    for k, (lo, hi) in TRUTH_RANGES.items():
        out[k] = float(rng.uniform(lo, hi)) if k == "drop_probability" else float(np.exp(rng.uniform(np.log(lo), np.log(hi))))
    return out


def test_candidate_config_sets_exactly_the_fitted_parameters():
    params = {"range_noise_m": 0.04, "drop_probability": 0.6, "dissipation_half_range_m": 55.0}
    cfg = candidate_config(VLP16.with_(dissipation=RangeDissipation(width=5.0)), params)
    assert config_parameters(cfg) == pytest.approx(params)
    assert cfg.dissipation.width == 5.0 and cfg.columns == VLP16.columns  # the rest is the base's
    assert config_parameters(VLP16)["dissipation_half_range_m"] == float("inf")


def test_the_simulator_reads_a_lidar_yaml(tmp_path):
    cfg = candidate_config(VLP16, {"range_noise_m": 0.05, "drop_probability": 0.55, "dissipation_half_range_m": 40.0})
    path = save_lidar_config(cfg, tmp_path / "lidar.yaml", {"note": "fit report"})
    sc = builtin_scenario("ferry_crossing")
    settings = SimulationSettings(sensors=("lidar",), lidar_config=str(path))
    (lidar,) = [s for s in scenario_sensors(sc, settings) if isinstance(s, LidarSensor)]
    assert lidar.lidar.config == cfg
    # The degradation flags still apply on top of the file.
    settings = SimulationSettings(sensors=("lidar",), lidar_config=str(path), ray_drop=0.3)
    (lidar,) = [s for s in scenario_sensors(sc, settings) if isinstance(s, LidarSensor)]
    assert lidar.lidar.config.drop_probability == 0.3 and lidar.lidar.config.dissipation == cfg.dissipation


@pytest.mark.slow
def test_fit_recovers_a_random_known_model_inside_its_intervals(tmp_path, capsys):
    # A "real" recording by a model drawn at random (seed fixed here so that a failure can be reproduced; the
    # recovery over other draws is in docs/validation.md), at another seed than the candidates'.
    truth = _draw(2211)
    real_cfg = candidate_config(VLP16, truth)
    sc = builtin_scenario("ferry_crossing")
    cfg_file = save_lidar_config(real_cfg, tmp_path / "real_lidar.yaml")
    run_dir = tmp_path / "real"
    window = {"start": sc.start + 15.0, "duration": 45.0}
    simulate_scenario(sc, run_dir, **window, seed=4242, progress=False, sensors=("lidar",), lidar_config=str(cfg_file))
    out = tmp_path / "fit.yaml"
    args = ["lidar", "fit", str(run_dir), "--scenario", "ferry_crossing", "--out", str(out), "--duration", "45", "--every", "3"]
    assert run([*args, "--seeds", "1", "--boot", "100"]) == 0
    text = capsys.readouterr().out
    assert all(p in text for p in PARAMETERS)
    fitted = load_lidar_config(out)  # what the simulator reads back
    import yaml

    report = yaml.safe_load(out.read_text(encoding="utf-8"))["fit"]
    for name in PARAMETERS:
        p = report["parameters"][name]
        lo, hi = p["ci95"]
        assert lo <= truth[name] <= hi, (name, truth[name], p)
        assert lo <= p["estimate"] <= hi
    assert config_parameters(fitted) == pytest.approx({k: v["estimate"] for k, v in report["parameters"].items()})


@pytest.mark.slow
def test_a_short_fit_is_deterministic_and_reads_back(tmp_path):
    sc = builtin_scenario("ferry_crossing")
    run_dir = tmp_path / "real"
    simulate_scenario(sc, run_dir, start=sc.start + 35.0, duration=2.0, seed=7, progress=False, sensors=("lidar",), ray_drop=0.6)
    kw = {"seeds": 1, "rounds": 0, "n_boot": 20}
    fit = fit_lidar_to_recording(run_dir, "ferry_crossing", **kw)
    assert fit.n_sweeps == 20 and len(fit.candidates) == 27 and np.isfinite(fit.distance)
    assert fit.distance == min(c["distance"] for c in fit.candidates)  # the nearest candidate in S7
    for p in fit.parameters.values():
        assert p["ci95"][0] <= p["estimate"] <= p["ci95"][1]
    # Deterministic, and the scenario beside the run (its scenario.yaml) is the default.
    assert fit_lidar_to_recording(run_dir, None, **kw).report() == fit.report()
    path = save_lidar_config(fit.config, tmp_path / "fit.yaml", fit.report())
    assert load_lidar_config(path) == fit.config


@pytest.mark.slow
def test_bad_input_is_one_clear_error(tmp_path, capsys):
    with pytest.raises(InputError, match="no such recording"):
        fit_lidar_to_recording(tmp_path / "nothing", "ferry_crossing")
    with pytest.raises(ParameterError, match="every"):
        fit_lidar_to_recording(tmp_path, "ferry_crossing", every=0)
    with pytest.raises(ParameterError, match="unknown range model") as err:
        fit_lidar_to_recording(tmp_path, "ferry_crossing", lidar_mode="lasers")
    assert err.value.param == "lidar_mode"
    # A recording with a radar but no lidar topic.
    sc = builtin_scenario("ferry_crossing")
    simulate_scenario(sc, tmp_path / "radar", duration=3.0, progress=False, sensors=("radar",))
    with pytest.raises(InputError, match="lidar"):
        fit_lidar_to_recording(tmp_path / "radar", "ferry_crossing")
    # The CLI: one line on stderr, exit 2, naming the recording.
    assert run(["lidar", "fit", str(tmp_path / "radar"), "--scenario", "ferry_crossing", "--out", str(tmp_path / "f.yaml")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "radar" in err[0] and "lidar" in err[0]
    assert not (tmp_path / "f.yaml").exists()
    # A lidar recording whose window holds no sweep; one whose targets are all beyond the lidar's range.
    simulate_scenario(sc, tmp_path / "lidar", duration=0.5, progress=False, sensors=("lidar",))
    with pytest.raises(ParameterError, match="no sweep"):
        fit_lidar_to_recording(tmp_path / "lidar", "ferry_crossing", start_offset=30.0)
    with pytest.raises(InputError, match="no lidar return near any target"):
        fit_lidar_to_recording(tmp_path / "lidar", "ferry_crossing")
    # A lidar YAML with a bad field, given to the simulator: one line naming the file and the field.
    (tmp_path / "bad.yaml").write_text("lidar:\n  range_accuracy: -1\n", encoding="utf-8")
    assert run(["simulate", "ferry_crossing", "--out", str(tmp_path / "s"), "--lidar", str(tmp_path / "bad.yaml")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bad.yaml" in err[0] and "range_accuracy" in err[0]
