"""The radar through the engine: detection of vessels, occlusion, land, determinism, a scene."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from seatwin.engine import MeshData, make_caster
from seatwin.sensors.radar import AntennaPose, RadarConfig, RadarModel, illuminate
from seatwin.sensors.radar.plots import KIND_CLUTTER, KIND_LAND, KIND_VESSEL


def _box(obj: int, north: float, east: float, extents=(8.0, 3.0, 2.0)) -> MeshData:
    b = trimesh.creation.box(extents=list(extents))
    b.apply_translation([0, 0, -extents[2] / 2])  # z down: from the water up to the top
    return MeshData.from_trimesh(b, obj).transformed(np.eye(3), [north, east, 0.0])


SURE = {
    "detection": {"snr_ref_db": 60.0, "pd_max": 1.0},
    "clutter": {"kind": "none"},
    "noise": {"range_sigma_m": 0.0, "bearing_sigma_deg": 0.0},
}
ANT = AntennaPose(0.0, 0.0, 0.0, 3.0)


def test_a_boat_gives_one_plot_at_its_position():
    caster = make_caster([_box(1, 300.0, 100.0)])
    s = RadarModel(RadarConfig(**SURE), seed=1).scan(0, 0.0, ANT, caster)
    assert len(s) == 1 and s.kind[0] == KIND_VESSEL and s.object_id[0] == 1
    # The plot lies on the near face (radar sees the side facing it), within a few metres.
    assert np.hypot(s.north[0] - 300.0, s.east[0] - 100.0) < 6.0


def test_heading_rotates_azimuth_not_position():
    caster = make_caster([_box(1, 300.0, 100.0)])
    m = RadarModel(RadarConfig(**SURE), seed=1)
    a = m.scan(0, 0.0, ANT, caster)
    b = m.scan(0, 0.0, AntennaPose(0.0, 0.0, 1.0, 3.0), caster)
    assert np.hypot(a.north[0] - b.north[0], a.east[0] - b.east[0]) < 1.0
    assert (a.azimuth[0] - b.azimuth[0]) % (2 * np.pi) == pytest.approx(1.0, abs=0.01)


def test_occlusion_hides_the_boat_behind():
    caster = make_caster([_box(1, 200.0, 0.0, (3.0, 30.0, 6.0)), _box(2, 400.0, 0.0)])
    objs = illuminate(RadarConfig(), ANT, caster)
    assert [o.object_id for o in objs] == [1]


def test_detection_probability_drives_detection_rate():
    cfg = RadarConfig(detection={"snr_ref_db": 5.0, "pd_max": 0.9}, clutter={"kind": "none"})
    caster = make_caster([_box(1, 900.0, 0.0)])
    m = RadarModel(cfg, seed=4)
    hits = [len(m.scan(k, 0.0, ANT, caster)) for k in range(200)]
    obj = illuminate(cfg, ANT, caster)[0]
    from seatwin.sensors.radar import detection_probability

    pd = float(detection_probability(obj.range_m, obj.area_m2, cfg.detection))
    assert 0.05 < pd < 0.95
    assert np.mean(hits) == pytest.approx(pd, abs=0.1)


def test_land_splits_into_several_plots_and_clutter_is_labelled():
    land = MeshData.from_trimesh(trimesh.creation.box(extents=[40, 600, 4]), 5).transformed(np.eye(3), [-500.0, 0.0, 0.0])
    cfg = RadarConfig(clutter={"kind": "uniform", "density_per_km2": 2.0})
    s = RadarModel(cfg, seed=2).scan(3, 0.0, ANT, make_caster([land]), kinds={5: "land"})
    assert (s.kind == KIND_LAND).sum() >= 5
    assert (s.kind == KIND_CLUTTER).sum() > 0
    assert (s.object_id[s.kind == KIND_CLUTTER] == -1).all()
    assert (s.north[s.kind == KIND_LAND] < -400).all()


def test_reruns_are_bit_identical_and_seeds_differ():
    caster = make_caster([_box(1, 300.0, 100.0)])
    cfg = RadarConfig(clutter={"kind": "uniform", "density_per_km2": 3.0})
    a = RadarModel(cfg, seed=7).scan(5, 0.0, ANT, caster, with_spokes=True)
    b = RadarModel(cfg, seed=7).scan(5, 0.0, ANT, caster, with_spokes=True)
    c = RadarModel(cfg, seed=8).scan(5, 0.0, ANT, caster)
    assert np.array_equal(a.north, b.north) and np.array_equal(a.east, b.east)
    assert np.array_equal(a.spokes.intensities, b.spokes.intensities)
    assert not (len(a) == len(c) and np.array_equal(a.north, c.north))


def test_radar_in_a_builtin_scene_sees_the_targets():
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sensors.radar.world import scan_scene
    from seatwin.world.scene import Scene

    sc = builtin_scenario("ferry_crossing")
    scene = Scene.from_scenario(sc)
    s = scan_scene(RadarModel(RadarConfig(**SURE), seed=0), scene, sc.ownship.name, 0, sc.start)
    for v in sc.targets:
        st = v.trajectory.state_at(sc.start)
        i = s.kind == KIND_VESSEL
        d = np.hypot(s.north[i] - float(st.north), s.east[i] - float(st.east))
        assert d.min() < 10.0, v.name
    assert (s.kind == KIND_LAND).any()


def test_beam_timing_sees_a_moving_target_where_the_beam_passes_it():
    from seatwin.scenario.model import Dimensions, Role, Scenario, Trajectory, Vessel
    from seatwin.sensors.radar.world import scan_scene
    from seatwin.world.scene import Scene
    from seatwin.world.vessels import vessel_model

    t = np.array([0.0, 10.0])
    own = Trajectory(t, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0])
    # Target due west (azimuth 270° from a north-facing bow: the beam gets there 3/4 of a rotation
    # after the stamp), moving north at 10 m/s.
    tgt = Trajectory(t, [0.0, 100.0], [-300.0, -300.0], [0.0, 0.0])
    sc = Scenario("t", [Vessel("own", Role.OWNSHIP, own), Vessel("tgt", Role.TARGET, tgt, dimensions=Dimensions(8, 3, 2))])
    scene = Scene([], {v.name: (vessel_model("generic", v.dimensions), v.trajectory) for v in sc.vessels})
    out = {}
    for mode in ("scan", "beam"):
        cfg = RadarConfig(pose_at=mode, rotation_period_s=2.0, **SURE)
        s = scan_scene(RadarModel(cfg, seed=0), scene, "own", 0, 0.0)
        assert len(s) == 1
        out[mode] = s.north[0]
    assert abs(out["scan"]) < 3.0
    assert out["beam"] == pytest.approx(10.0 * 2.0 * 0.75, abs=3.0)
