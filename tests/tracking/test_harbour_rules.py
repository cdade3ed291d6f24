"""Tracks that cannot be boats are deleted (issue 21): on land for more than ``land_scans`` scans (and never
confirmed there), faster than v_max + margin for more than ``speed_gate_scans`` scans; ``real-thesis`` keeps
the thesis's tracker, which does neither."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.layout.raster import LandRaster
from seatwin.perception import MeasurementKind
from seatwin.perception.map_mask import RasterMask
from seatwin.perception.measurements import Scan
from seatwin.tracking import JIPDATracker, TrackerConfig, load_tuning
from seatwin.tracking.gnn import GNNTracker


def _config(**changes: object) -> TrackerConfig:
    base = dict(
        q_north=0.5,
        q_east=0.5,
        gate_g=None,
        gate_probability=0.999,
        v_max=10.0,
        init_margin=3.0,
        sensors={"radar": {"r_range": 4.0, "r_bearing": 1e-4, "r_cartesian": 1.0, "p_detect": 0.9, "clutter_density": 1e-5}},
    )
    return TrackerConfig.model_validate({**base, **changes})


def _harbour() -> RasterMask:
    """Water south of north = 50 m (rows 0–49 of a 1 m raster from −100 m), land north of it."""
    water = np.zeros((200, 200), bool)
    water[:150] = True
    return RasterMask(LandRaster(water, -100.0, -100.0, 1.0))


def _scans(points: np.ndarray, dt: float = 1.0) -> list[Scan]:
    return [Scan(100.0 + k * dt, "radar", MeasurementKind.CARTESIAN, p.reshape(-1, 2)) for k, p in enumerate(points)]


def _jitter(n: int, seed: int, sigma: float = 0.3) -> np.ndarray:
    return np.random.default_rng(seed).normal(0.0, sigma, (n, 2))


@pytest.mark.parametrize("tracker", [JIPDATracker, GNNTracker])
def test_a_return_on_land_is_never_a_confirmed_track(tracker) -> None:  # noqa: ANN001
    quay = np.array([60.0, 0.0]) + _jitter(30, 1)  # 10 m inside the land
    with_map = tracker(_config(), _harbour())
    tab = with_map.run(_scans(quay))
    assert not tab.confirmed.any() and with_map.deleted_on_land >= 1
    without = tracker(_config())  # no map: the tracker cannot know
    assert without.run(_scans(quay)).confirmed.any()
    thesis = tracker(load_tuning("real-thesis").model_copy(update={"sensors": _config().sensors}), _harbour())
    assert thesis.run(_scans(quay)).confirmed.any()  # the thesis's tracker ignores the map


def test_a_boat_that_sails_onto_land_is_deleted_after_land_scans() -> None:
    n = 40
    path = np.column_stack([np.linspace(0.0, 78.0, n), np.zeros(n)]) + _jitter(n, 2, 0.2)  # 2 m/s north, crosses 50 m
    tracker = JIPDATracker(_config(land_scans=2), _harbour())
    tab = tracker.run(_scans(path))
    conf = tab.confirmed
    assert tracker.deleted_on_land >= 1  # the boat's track, then tracks restarted on land (never confirmed)
    assert len(np.unique(tab.track_id[conf])) == 1
    assert (tab.x[conf, 0] >= 50.0).sum() == 0  # no confirmed row on land: reported unconfirmed there
    on_land = tab.track_id == np.unique(tab.track_id[conf])[0]
    assert 1 <= (tab.x[on_land, 0] >= 50.0).sum() <= 2  # the track itself lives at most land_scans scans on land
    assert tab.time[conf].max() < 100.0 + (n - 1)


def test_a_boat_moored_beside_the_quay_keeps_its_track() -> None:
    moored = np.array([48.0, 0.0]) + _jitter(60, 3, 0.5)  # 2 m off the quay, estimate noise 0.5 m
    tracker = JIPDATracker(_config(), _harbour())
    tab = tracker.run(_scans(moored))
    assert tracker.deleted_on_land == 0
    assert len(np.unique(tab.track_id[tab.confirmed])) == 1 and tab.confirmed[tab.time == tab.time.max()].all()


def test_a_sustained_impossible_speed_deletes_the_track_the_sigma_gate_keeps() -> None:
    boat = np.column_stack([13.0 * np.arange(30), np.zeros(30)])  # 13 m/s > v_max + 1 m/s, constant
    sigma_only = JIPDATracker(_config(speed_gate_scans=None, speed_gate_sigma=None))
    tab = sigma_only.run(_scans(boat))
    assert np.hypot(tab.x[tab.confirmed, 1], tab.x[tab.confirmed, 3]).max() > 12.0  # kept at 13 m/s
    sustained = JIPDATracker(_config(speed_gate_sigma=None))
    tab = sustained.run(_scans(boat))
    assert sustained.deleted_too_fast >= 1
    for k in np.unique(tab.track_id):  # no track, confirmed or not, over 11 m/s for more than 3 scans running
        m = tab.track_id == k
        over = np.hypot(tab.x[m, 1], tab.x[m, 3]) > 11.0
        runs = np.diff(np.flatnonzero(np.diff(np.concatenate([[0], over.astype(int), [0]]))))[::2]
        assert runs.size == 0 or runs.max() <= 3


def test_a_brief_overshoot_is_kept() -> None:
    v = np.concatenate([np.full(10, 8.0), np.full(2, 14.0), np.full(20, 8.0)])  # a 2 s sprint
    north = np.concatenate([[0.0], np.cumsum(v[1:])])
    tracker = JIPDATracker(_config(speed_gate_sigma=None))
    tab = tracker.run(_scans(np.column_stack([north, np.zeros(v.size)])))
    assert tracker.deleted_too_fast == 0 and len(np.unique(tab.track_id[tab.confirmed])) == 1


def test_speed_rule_and_land_rule_are_tuning_properties(tmp_path) -> None:
    for name in ("synthetic", "real", "joyride", "ravnkloa"):
        cfg = load_tuning(name)
        assert (cfg.speed_gate_scans, cfg.land_scans) == (3, 1)
    thesis = load_tuning("real-thesis")
    assert (thesis.speed_gate_sigma, thesis.speed_gate_scans, thesis.land_scans) == (None, None, None)
    assert thesis.sensors == load_tuning("real").sensors and thesis.q_north == load_tuning("real").q_north
    f = tmp_path / "t.yaml"
    f.write_text("base: real\nland_scans: null\nspeed_gate_scans: 5\n")
    cfg = load_tuning(str(f))
    assert (cfg.land_scans, cfg.speed_gate_scans) == (None, 5)
    f.write_text("base: real\nland_scans: -1\n")
    with pytest.raises(Exception, match="land_scans"):
        load_tuning(str(f))
