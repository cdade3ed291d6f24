"""The fit recovers the parameters of a recording the model made itself; the real joyride fit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.sensors.radar import RadarConfig
from seatwin.sensors.radar.fit import RadarObservations, fit_radar, poisson_ci, wilson


def test_wilson_and_poisson_intervals_hand_values():
    lo, hi = wilson(8, 10)
    assert lo == pytest.approx(0.4902, abs=1e-3) and hi == pytest.approx(0.9433, abs=1e-3)
    assert poisson_ci(0)[0] == 0.0 and poisson_ci(0)[1] == pytest.approx(3.689, abs=1e-3)
    lo, hi = poisson_ci(10)
    assert lo == pytest.approx(4.795, abs=1e-3) and hi == pytest.approx(18.39, abs=1e-2)


def _synthetic_obs(n=300, sr=5.0, sb_deg=1.0, bb_deg=-2.0, pd=0.8, clutter_per_scan=1.0, seed=0):
    g = np.random.default_rng(seed)
    antenna = np.zeros((n, 2))
    truth = np.column_stack([np.linspace(200, 900, n), np.full(n, 100.0)])
    plots = []
    for k in range(n):
        p = []
        if g.random() < pd:
            r = np.hypot(*truth[k]) + sr * g.standard_normal()
            b = math.atan2(truth[k, 1], truth[k, 0]) + math.radians(bb_deg + sb_deg * g.standard_normal())
            p.append([r * math.cos(b), r * math.sin(b)])
        m = g.poisson(clutter_per_scan)
        rr = np.sqrt(g.uniform(20**2, 2000**2, m))
        bb = g.uniform(0, 2 * np.pi, m)
        p += np.column_stack([rr * np.cos(bb), rr * np.sin(bb)]).tolist()
        plots.append(np.array(p).reshape(-1, 2))
    return RadarObservations(np.arange(n) * 2.5, plots, antenna, truth, 10.0)


@pytest.mark.slow
def test_fit_recovers_noise_detection_and_clutter():
    obs = _synthetic_obs()
    base = RadarConfig(min_range_m=20.0, max_range_m=2000.0)
    res = fit_radar(obs, base, n_boot=30, fit_max_range=False)
    e = res.report["estimates"]
    assert e["range_sigma_m"]["estimate"] == pytest.approx(5.0, rel=0.2)
    assert e["bearing_bias_deg"]["estimate"] == pytest.approx(-2.0, abs=0.25)
    assert e["bearing_sigma_deg"]["estimate"] == pytest.approx(1.0, rel=0.2)
    assert e["detection_rate"]["estimate"] == pytest.approx(0.8, abs=0.07)
    # ~1 false plot per scan over the annulus (a few clutter plots fall inside the gate).
    assert e["clutter_per_scan"]["estimate"] == pytest.approx(1.0, rel=0.2)
    for v in e.values():
        assert v["se"] >= 0
    assert res.config.noise.bearing_bias_deg == pytest.approx(e["bearing_bias_deg"]["estimate"])
    assert res.config.clutter.density_per_km2 == pytest.approx(e["clutter_density_per_km2"]["estimate"])
    assert res.config.fit["n_scans"] == 300
    ci = e["bearing_bias_deg"]["ci95"]
    assert ci[0] <= -2.0 <= ci[1]


def test_fit_map_clutter_and_bad_input():
    obs = _synthetic_obs(n=40)
    res = fit_radar(obs, RadarConfig(), n_boot=0, clutter="map", map_cell_m=500.0)
    assert res.config.clutter.kind == "map" and res.config.clutter.map is not None
    with pytest.raises(InputError):
        fit_radar(obs.subset([0, 1]), RadarConfig())
    with pytest.raises(InputError, match="truth"):
        RadarObservations(np.arange(3.0), [np.empty((0, 2))] * 3, np.zeros((3, 2)), np.zeros((4, 1, 2)))


def test_fit_on_the_models_own_recording():
    """The replica simulated with known parameters: the fit finds them (plots lie on the hull's near
    side, so the range bias absorbs a metre or two of geometry)."""
    from seatwin.fidelity.joyride import observations
    from seatwin.fidelity.synthetic import TOY_RADAR as TRUE_RADAR
    from seatwin.fidelity.synthetic import toy_dataset

    res = fit_radar(observations(toy_dataset()), RadarConfig(), n_boot=20)
    e = res.report["estimates"]
    assert e["bearing_bias_deg"]["estimate"] == pytest.approx(TRUE_RADAR["noise"]["bearing_bias_deg"], abs=0.4)
    assert e["bearing_sigma_deg"]["estimate"] == pytest.approx(TRUE_RADAR["noise"]["bearing_sigma_deg"], rel=0.35)
    assert e["range_sigma_m"]["estimate"] == pytest.approx(TRUE_RADAR["noise"]["range_sigma_m"], rel=0.35)
    assert abs(e["range_bias_m"]["estimate"]) < 4.0


@pytest.mark.slow
def test_fit_real_joyride(shared_data):
    from seatwin.fidelity.joyride import load_joyride, observations

    res = fit_radar(observations(load_joyride(shared_data / "joyride" / "joyride.mat")), RadarConfig(), n_boot=10)
    e = res.report["estimates"]
    # Measured on the real data (docs/validation.md, radar): a −1.8° bearing bias, σ_θ ≈ 1.8°, Pd ≈ 0.76.
    assert e["bearing_bias_deg"]["estimate"] == pytest.approx(-1.8, abs=0.3)
    assert e["bearing_sigma_deg"]["estimate"] == pytest.approx(1.8, abs=0.4)
    assert e["detection_rate"]["estimate"] == pytest.approx(0.76, abs=0.05)
