"""Pure parts of the radar model: config, detection probability, plot extraction, clutter, spokes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.rng import frame_rng
from seatwin.sensors.radar import Cells, RadarConfig, extract_plots, load_radar_config, save_radar_config
from seatwin.sensors.radar.clutter import annulus_area, clutter_points, expected_clutter, map_density
from seatwin.sensors.radar.config import ClutterConfig, ClutterMap, DetectionConfig
from seatwin.sensors.radar.detection import cell_intensity, detection_probability, snr_linear, swerling1_pd
from seatwin.sensors.radar.plots import components
from seatwin.sensors.radar.spokes import render_spokes


def test_config_yaml_round_trip(tmp_path):
    cfg = RadarConfig(n_spokes=1024, noise={"bearing_bias_deg": -1.5})
    p = save_radar_config(cfg, tmp_path / "r.yaml")
    back = load_radar_config(p)
    assert back == cfg
    assert math.isclose(back.noise.bearing_bias, math.radians(-1.5))
    assert cfg.n_samples == math.ceil(2500 / 2.0)


def test_config_bad_field_names_it(tmp_path):
    p = tmp_path / "bad.yaml"
    p.write_text("radar:\n  noise:\n    range_sigma_m: -1\n")
    with pytest.raises(InputError, match=r"noise\.range_sigma_m"):
        load_radar_config(p)
    p.write_text("radar:\n  min_range_m: 900\n  max_range_m: 800\n")
    with pytest.raises(InputError, match="min_range_m"):
        load_radar_config(p)
    p.write_text("radar: [1, 2\n")
    with pytest.raises(InputError, match="line"):
        load_radar_config(p)
    with pytest.raises(InputError, match="no such"):
        load_radar_config(tmp_path / "missing.yaml")


def test_swerling1_hand_values():
    # SNR 0 → Pd = Pfa; SNR 9 → Pfa^(1/10); large SNR → 1.
    assert swerling1_pd(0.0, 1e-6) == pytest.approx(1e-6)
    assert swerling1_pd(9.0, 1e-6) == pytest.approx(10 ** (-0.6))
    assert swerling1_pd(1e9, 1e-6) == pytest.approx(1.0, abs=1e-6)


def test_snr_falls_with_fourth_power_of_range_and_grows_with_area():
    cfg = DetectionConfig(snr_ref_db=20.0, range_ref_m=1000.0, area_ref_m2=10.0)
    assert snr_linear(1000.0, 10.0, cfg) == pytest.approx(100.0)
    assert snr_linear(2000.0, 10.0, cfg) == pytest.approx(100.0 / 16)
    assert snr_linear(1000.0, 20.0, cfg) == pytest.approx(200.0)
    pd = detection_probability([200.0, 1000.0, 3000.0], 10.0, cfg)
    assert pd[0] > pd[1] > pd[2]
    assert pd[0] <= cfg.pd_max


def test_cell_intensity_is_8_bit_and_monotone():
    v = cell_intensity([0.0, 1.0, 100.0, 1e30])
    assert v.dtype == np.uint8
    assert list(v) == sorted(v) and v[-1] == 255 and v[0] == 8


def _cells(spokes, samples, obj=1, snr=1.0):
    n = len(spokes)
    return Cells(np.asarray(spokes), np.asarray(samples), np.full(n, obj), np.full(n, float(snr)))


def test_components_merge_within_gap_and_wrap_in_azimuth():
    lab = components(np.array([0, 1, 3, 10, 2047]), np.array([5, 5, 6, 5, 5]), 2048, 2, 2)
    assert lab[0] == lab[1] == lab[2] == lab[4]  # 2047 and 0 are neighbours
    assert lab[3] != lab[0]


def test_extract_plots_one_plot_per_target_at_its_centroid():
    cfg = RadarConfig(n_spokes=2048, range_increment_m=2.0)
    c = Cells.concat([_cells([100, 101, 102], [250, 250, 251], obj=7), _cells([900], [400], obj=8)])
    b = extract_plots(c, cfg)
    assert len(b) == 2
    i = int(np.argmin(b.range_m))
    assert b.object_id[i] == 7 and b.n_cells[i] == 3
    assert b.range_m[i] == pytest.approx(2.0 * (np.mean([250, 250, 251]) + 0.5))
    assert b.azimuth[i] == pytest.approx((101 + 0.5) * cfg.spoke_step)


def test_extract_plots_splits_large_blobs():
    cfg = RadarConfig(plots={"max_plot_extent_m": 20.0})
    # A land strip 100 m deep in range on one spoke.
    c = _cells([500] * 50, np.arange(300, 350), obj=3)
    b = extract_plots(c, cfg)
    assert len(b) == 5
    assert (b.extent_m <= 20.0 + 1e-9).all()


def test_uniform_clutter_is_poisson_in_the_annulus():
    cfg = ClutterConfig(kind="uniform", density_per_km2=2.0)
    counts = []
    for k in range(200):
        p = clutter_points(frame_rng(1, "t", k), cfg, (100.0, -50.0), 50.0, 1000.0)
        r = np.hypot(p[:, 0] - 100.0, p[:, 1] + 50.0)
        assert ((r >= 50.0) & (r <= 1000.0)).all()
        counts.append(len(p))
    lam = 2e-6 * annulus_area(50.0, 1000.0)
    assert expected_clutter(cfg, (0, 0), 50.0, 1000.0) == pytest.approx(lam)
    assert np.mean(counts) == pytest.approx(lam, rel=0.05)
    assert np.var(counts) == pytest.approx(lam, rel=0.25)


def test_map_clutter_follows_the_map():
    cmap = ClutterMap(north0_m=0.0, east0_m=0.0, cell_m=100.0, density=[[0.0, 1e-4], [0.0, 0.0]])
    cfg = ClutterConfig(kind="map", map=cmap)
    pts = np.vstack([clutter_points(frame_rng(2, "t", k), cfg, (0.0, 0.0), 0.0, 500.0) for k in range(20)])
    assert len(pts) > 0
    assert ((pts[:, 0] >= 0) & (pts[:, 0] < 100) & (pts[:, 1] >= 100) & (pts[:, 1] < 200)).all()
    assert map_density(cmap, np.array([50.0, 150.0]), np.array([150.0, 150.0])).tolist() == [1e-4, 0.0]
    assert np.mean([len(clutter_points(frame_rng(3, "t", k), cfg, (0, 0), 0, 500)) for k in range(300)]) == pytest.approx(
        1.0, rel=0.2
    )
    with pytest.raises(ValueError):
        ClutterConfig(kind="map")


def test_spokes_layout():
    cfg = RadarConfig(n_spokes=64, max_range_m=200.0, min_range_m=5.0, range_increment_m=2.0)
    c = _cells([3], [20], snr=1000.0)
    sp = render_spokes(cfg, c, 100.0, frame_rng(0, "s", 0))
    assert sp.intensities.shape == (64, 100) and sp.intensities.dtype == np.uint8
    assert sp.intensities[3, 20] == cell_intensity([1000.0])[0]
    d = sp.to_request_dict()
    assert d["num_spokes"] == 64 and d["num_samples"] == 100 and len(d["radar_spokes"]) == 6400
    assert d["time_in_seconds"][1] - d["time_in_seconds"][0] == pytest.approx(2.5 / 64)
    assert d["azimuth"][0] == pytest.approx(0.5 * 2 * math.pi / 64)
