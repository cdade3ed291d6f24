"""Deliberately wrong radar models (ablations) and the controlled test: a model must rank itself first."""

from __future__ import annotations

import json

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.errors import ParameterError
from seatwin.fidelity.ablations import (
    ABLATIONS,
    TOO_CLEAN_SCALE,
    ablated_models,
    heavy_clutter,
    low_pd,
    no_bias,
    scale_clutter,
    too_clean,
    wide_noise,
)
from seatwin.sensors.radar.config import ClutterConfig, ClutterMap, RadarConfig
from seatwin.sensors.radar.detection import detection_probability

FITTED = RadarConfig(
    name="fit",
    noise={"range_sigma_m": 6.0, "range_bias_m": -1.0, "bearing_sigma_deg": 0.6, "bearing_bias_deg": -1.0},
    clutter={"kind": "uniform", "density_per_km2": 0.8},
    detection={"snr_ref_db": 15.0, "pd_max": 0.85},
)
KNOWN = {
    "noise": {"range_sigma_m": 6.0, "range_bias_m": 0.0, "bearing_sigma_deg": 0.6, "bearing_bias_deg": -1.0},
    "clutter": {"kind": "uniform", "density_per_km2": 1.0},
    "detection": {"snr_ref_db": 15.0, "pd_max": 0.85},
    "max_range_m": 1000.0,
}
"""The radar that makes the controlled test's "real" recording (distinct from the built-in default model)."""


def _same_except(a: RadarConfig, b: RadarConfig, *sections: str) -> None:
    da, db = a.model_dump(), b.model_dump()
    for key in ("name", *sections):
        da.pop(key), db.pop(key)
    assert da == db


def test_no_bias_and_wide_noise():
    nb = no_bias(FITTED)
    assert nb.noise.bearing_bias_deg == 0.0 and nb.noise.range_bias_m == -1.0 and nb.noise.bearing_sigma_deg == 0.6
    _same_except(nb, FITTED, "noise")
    wn = wide_noise(FITTED)
    assert (wn.noise.range_sigma_m, wn.noise.bearing_sigma_deg) == pytest.approx((18.0, 1.8))
    assert wn.noise.bearing_bias_deg == -1.0 and wn.noise.range_bias_m == -1.0
    _same_except(wn, FITTED, "noise")
    assert FITTED.noise.range_sigma_m == 6.0 and FITTED.name == "fit"  # the input is untouched
    assert nb.name == "fit (no_bias)" and wn.name == "fit (wide_noise)"


def test_low_pd_is_flat_over_range():
    lp = low_pd(FITTED)
    _same_except(lp, FITTED, "detection")
    pd = detection_probability(np.array([50.0, 500.0, 2500.0]), np.array([1.0, 16.0, 1.0]), lp.detection)
    np.testing.assert_allclose(pd, 0.3, atol=1e-4)
    # The fitted model itself falls off with range: the ablation is not the fitted one with a lower cap.
    assert detection_probability(np.array([2500.0]), np.array([1.0]), FITTED.detection)[0] < 0.5


def test_heavy_clutter_scales_uniform_and_map_densities():
    hc = heavy_clutter(FITTED)
    assert hc.clutter.density_per_km2 == pytest.approx(8.0) and hc.clutter.kind == "uniform"
    _same_except(hc, FITTED, "clutter")
    grid = ClutterMap(north0_m=0, east0_m=0, cell_m=10, density=[[1e-6, 0.0], [2e-6, 3e-6]], outside_density=1e-7)
    m = ClutterConfig(kind="map", map=grid)
    s = scale_clutter(m, 10.0)
    np.testing.assert_allclose(s.map.density, [[1e-5, 0.0], [2e-5, 3e-5]])
    assert s.map.outside_density == pytest.approx(1e-6) and m.map.density[0][0] == 1e-6


def test_too_clean():
    tc = too_clean(FITTED)
    assert tc.noise.range_sigma_m == pytest.approx(6.0 * TOO_CLEAN_SCALE)
    assert tc.noise.bearing_sigma_deg == pytest.approx(0.6 * TOO_CLEAN_SCALE)
    assert tc.noise.bearing_bias_deg == -1.0  # only the noise goes, not the calibration error
    assert tc.clutter.kind == "none" and tc.clutter.density_per_km2 == 0.0
    pd = detection_probability(np.array([100.0, 2500.0]), np.array([1.0, 1.0]), tc.detection)
    np.testing.assert_allclose(pd, 0.99, atol=1e-4)
    _same_except(tc, FITTED, "noise", "clutter", "detection")


def test_ablated_models_in_report_order():
    models = ablated_models(FITTED)
    assert list(models) == ["no_bias", "wide_noise", "low_pd", "heavy_clutter", "too_clean"] == list(ABLATIONS)
    assert all(RadarConfig.model_validate(m.model_dump()) == m for m in models.values())  # each is a valid config


def test_ablations_need_a_fitted_model(tmp_path, capsys):
    from seatwin.fidelity import FidelityOptions

    with pytest.raises(ParameterError) as exc:
        FidelityOptions(ablations=True)  # fit_on defaults to none
    assert exc.value.param == "ablations" and "fit_on" in str(exc.value)
    assert FidelityOptions().with_(fit_on="first-half", ablations=True).ablations
    assert run(["fidelity", "joyride", str(tmp_path / "x.mat"), "--out", str(tmp_path / "o"), "--ablations"]) == 2
    err = capsys.readouterr().err
    assert "ablations" in err and "Traceback" not in err


@pytest.mark.slow
def test_controlled_recording_ranks_its_own_model_first(tmp_path):
    """A "real" recording made by a known radar model: fitted on its first half (recovering the model),
    that model must score best on the held-out half against the default and every ablation."""
    from seatwin.fidelity import run_fidelity, write_fidelity
    from seatwin.fidelity.synthetic import orbit_dataset, write_joyride_mat

    path = write_joyride_mat(orbit_dataset(KNOWN, n=200, seed=11), tmp_path / "orbit.mat")
    result = run_fidelity(str(path), fit_on="first-half", ablations=True, seeds=2, agents=("gnn",), n_boot=100, fit_boot=0)
    est = {k: v["estimate"] for k, v in result.radar_fit["estimates"].items()}
    assert est["bearing_bias_deg"] == pytest.approx(-1.0, abs=0.3)
    assert est["range_sigma_m"] == pytest.approx(6.0, rel=0.3)
    ranking = result.ranking()
    assert [r["model"] for r in ranking][0] == "fitted"
    assert {r["model"] for r in ranking} == {"default", "fitted", *ABLATIONS}
    scores = {r["model"]: r["score"] for r in ranking}
    assert all(v is not None for v in scores.values()), ranking
    best = ranking[0]
    assert best["ci_low"] <= best["score"] <= best["ci_high"]
    assert min(v for k, v in scores.items() if k != "fitted") - scores["fitted"] > 0.1  # not a near-tie
    write_fidelity(tmp_path / "out", result, html=False)
    j = json.loads((tmp_path / "out" / "fidelity.json").read_text())
    assert j["ranking"][0]["model"] == "fitted" and j["score"] == scores["fitted"]
    assert set(j["ranking"][0]) >= {"model", "score", "ci_low", "ci_high", "ahed", "n_common", "n_only_real", "n_only_synthetic"}
    assert "Models ranked by fidelity score" in (tmp_path / "out" / "fidelity.md").read_text()
