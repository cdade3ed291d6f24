"""The spinning lidar: beam pattern, mount, posing, water, drop, noise, ordering, motion in a sweep."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.errors import InputError
from seatwin.scenario.model import Role, Scenario, Trajectory, Vessel
from seatwin.sensors.lidar import Lidar, lidar_for_scenario, sweep_starts, sweep_to_world
from seatwin.sensors.lidar_config import (
    MILLIAMPERE_LIDAR_MOUNT,
    VLP16,
    VLP16_THESIS,
    IntensityModel,
    LidarMount,
    RangeDissipation,
    lidar_preset,
)
from seatwin.sensors.lidar_physics import cos_incidence, intensity, return_probability, water_limit
from seatwin.sensors.rangemodel import BeamBatch, BeamRanges, get_range_model, register_range_model
from seatwin.world.objects import WorldObject
from seatwin.world.scene import Scene
from seatwin.world.shapes import block
from seatwin.world.vessels import VesselModel

EXACT = VLP16.with_(drop_probability=0.0, range_accuracy=0.0)
T0 = 1.6e9


def line(n0, e0, vn, ve, heading, duration=5.0) -> Trajectory:
    t = T0 + np.arange(0.0, duration + 1e-9, 0.1)
    return Trajectory(t, n0 + vn * (t - T0), e0 + ve * (t - T0), np.full(t.shape, heading))


def box_vessel(length=10.0, beam=4.0, height=3.0) -> VesselModel:
    return VesselModel("box", block(-length / 2, length / 2, -beam / 2, beam / 2, height, -0.5), reflectivity=0.5)


def wall_scene() -> Scene:
    """A wall 20 m north of the origin, 4 m high, and nothing else (open water)."""
    wall = WorldObject("wall", "quay", block(20.0, 21.0, -50.0, 50.0, 4.0, -1.0), 0.3)
    return Scene([wall])


def fixed(scene, config=EXACT, z=-2.0, **kw) -> Lidar:
    return Lidar(scene, config, LidarMount(x=0.0, y=0.0, z=z), platform=None, **kw)


def test_vlp16_presets() -> None:
    assert VLP16.elevations_deg == tuple(range(-15, 16, 2)) and VLP16.rings == 16
    assert VLP16.columns == 1800 and VLP16_THESIS.columns == 1024
    assert VLP16.beams == 28800 and VLP16.max_range == 100.0 and VLP16.rate_hz == 10.0
    assert VLP16.drop_probability == 0.8 and VLP16.range_noise_std == pytest.approx(0.015)
    assert lidar_preset("VLP16-thesis") is VLP16_THESIS
    with pytest.raises(InputError):
        lidar_preset("hdl64")
    d = VLP16.sensor_directions()
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, atol=1e-6)
    # Column 0 looks along +x; the head spins clockwise seen from above (column 1 slightly to the right, −y).
    np.testing.assert_allclose(d[7], [np.cos(np.radians(-1)), 0, np.sin(np.radians(-1))], atol=1e-6)
    assert d[16 + 7, 1] < 0
    np.testing.assert_allclose(VLP16.column_offsets()[[0, 900]], [0.0, 0.05])


@pytest.mark.parametrize(
    ("changes", "param"),
    [
        ({"columns": 0}, "columns"),
        ({"elevations_deg": ()}, "elevations_deg"),
        ({"elevations_deg": (1.0, -1.0)}, "elevations_deg"),
        ({"rate_hz": 0.0}, "rate_hz"),
        ({"min_range": 200.0}, "min_range"),
        ({"drop_probability": 1.5}, "drop_probability"),
        ({"dissipation": {"half_range": -1.0}}, "dissipation"),
        ({"colour": "red"}, "colour"),
    ],
)
def test_lidar_config_names_the_bad_field(changes, param) -> None:
    from seatwin.errors import ParameterError

    with pytest.raises(ParameterError) as exc:
        VLP16.with_(**changes)
    assert exc.value.param == param
    with pytest.raises(ParameterError) as exc:
        lidar_preset("hdl64")
    assert exc.value.param == "preset"
    for model in (VLP16, VLP16.intensity, RangeDissipation(), MILLIAMPERE_LIDAR_MOUNT):  # one settings style
        assert all(f.description for f in type(model).model_fields.values())
    assert MILLIAMPERE_LIDAR_MOUNT.with_(yaw_deg=0.0) == LidarMount(z=MILLIAMPERE_LIDAR_MOUNT.z, roll_deg=180.0)


def test_milliampere_mount_is_upside_down_and_turned_573_deg_to_starboard() -> None:
    r = MILLIAMPERE_LIDAR_MOUNT.rotation()
    a = np.radians(57.3)
    np.testing.assert_allclose(r @ [1, 0, 0], [np.cos(a), np.sin(a), 0], atol=1e-12)  # x: 57.3° clockwise of the bow
    np.testing.assert_allclose(r @ [0, 0, 1], [0, 0, 1], atol=1e-12)  # sensor up = body down (NED)
    np.testing.assert_allclose(np.linalg.det(r), 1.0)
    np.testing.assert_allclose(LidarMount().rotation() @ [0, 1, 0], [0, -1, 0])  # upright: left = port


def test_points_on_a_wall_at_the_right_range_in_the_sensor_frame() -> None:
    lid = fixed(wall_scene())
    s = lid.sweep(T0, 0)
    assert len(s) > 100 and (s.object_id == 0).all()
    # Beams hitting the wall face: x·cos... the face is the plane north = 20 → sensor x = 20.
    np.testing.assert_allclose(s.x, 20.0, atol=1e-3)
    assert s.x.dtype == np.float32 and s.ring.dtype == np.uint16 and s.time.dtype == np.float32
    # Upright at 2 m above the water: nothing below the water in the world.
    assert (s.z >= -2.0 - 1e-4).all()
    # The wall's top is at 4 m: nothing above it.
    assert (s.z <= 2.0 + 1e-3).all()
    assert (s.intensity > 0).all() and (s.intensity <= 255).all()


def test_no_water_returns_in_open_water() -> None:
    s = fixed(Scene([]), VLP16.with_(drop_probability=0.0)).sweep(T0, 0)
    assert len(s) == 0


def test_points_are_azimuth_major_with_ring_and_time() -> None:
    s = fixed(wall_scene()).sweep(T0, 0)
    key = s.time.astype(np.float64) * 1e6 * 100 + s.ring
    assert (np.diff(key) > 0).all()
    assert s.time.min() >= 0 and s.time.max() < 0.1
    assert s.stamp == T0 and s.frame == 0


def test_ray_drop_is_reproducible_and_seeded() -> None:
    scene = wall_scene()
    cfg = VLP16.with_(range_accuracy=0.03)
    a = fixed(scene, cfg, seed=1).sweep(T0, 5)
    b = fixed(scene, cfg, seed=1).sweep(T0, 5)
    c = fixed(scene, cfg, seed=2).sweep(T0, 5)
    d = fixed(scene, cfg, seed=1).sweep(T0, 6)
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.intensity, b.intensity)
    assert len(a) != len(c) or not np.array_equal(a.x, c.x)
    assert len(a) != len(d) or not np.array_equal(a.x, d.x)
    full = fixed(scene).sweep(T0, 5)
    assert 0.15 < len(a) / len(full) < 0.25  # 80 % dropped
    kept = fixed(scene, cfg, seed=1).kept_beams(5)
    assert kept is not None and 0.18 < kept.size / cfg.beams < 0.22


def test_range_noise_has_the_configured_spread() -> None:
    noisy = fixed(wall_scene(), EXACT.with_(range_accuracy=0.1)).sweep(T0, 0)
    clean = fixed(wall_scene()).sweep(T0, 0)
    err = noisy.range - clean.range
    assert abs(err.mean()) < 0.01 and err.std() == pytest.approx(0.05, rel=0.15)


def test_range_dissipation_thins_far_returns() -> None:
    far = WorldObject("far", "quay", block(70.0, 71.0, -100.0, 100.0, 20.0, -1.0), 0.3)
    near = WorldObject("near", "quay", block(-11.0, -10.0, -100.0, 100.0, 20.0, -1.0), 0.3)
    scene = Scene([far, near])
    cfg = EXACT.with_(dissipation=RangeDissipation(half_range=40.0, width=5.0))
    s, base = fixed(scene, cfg).sweep(T0, 0), fixed(scene).sweep(T0, 0)
    far_share = ((s.object_id == 0).sum() + 1) / ((base.object_id == 0).sum() + 1)
    near_share = (s.object_id == 1).sum() / (base.object_id == 1).sum()
    assert far_share < 0.05 and near_share > 0.9


def test_thesis_return_model_functions() -> None:
    m = IntensityModel(scale=255.0, reference_range=10.0, exponent=2.0)
    out = intensity(np.float32([1.0, 1.0, 0.5, 1.0]), np.float32([1.0, 1.0, 1.0, 0.5]), np.float32([5.0, 20.0, 10.0, 10.0]), m)
    np.testing.assert_allclose(out, [255.0, 255.0 / 4, 127.5, 127.5], rtol=1e-6)
    assert return_probability(np.float32([60.0]), RangeDissipation(half_range=60.0, width=8.0))[0] == pytest.approx(0.5)
    np.testing.assert_allclose(water_limit(np.float32([-3.0, -3.0]), np.float32([0.5, -0.5]), 100.0), [6.0, 100.0])
    np.testing.assert_allclose(
        cos_incidence(np.float32([[0, 0, 4], [0, 0, 0]]), np.float32([[0, 0.6, -0.8], [1, 0, 0]])), [0.8, 0.0], atol=1e-6
    )


def moving_scenario(speed: float) -> Scenario:
    own = line(0.0, 0.0, 0.0, 0.0, 0.0)
    tgt = line(0.0, 15.0, 0.0, speed, np.pi / 2)  # heading east, moving away along east
    return Scenario("m", [Vessel("own", Role.OWNSHIP, own, "milliampere"), Vessel("tgt", Role.TARGET, tgt, "generic")])


def test_vessels_move_during_the_sweep() -> None:
    """Each column sees the target where it is at that column's own time."""
    speed = 40.0
    sc = moving_scenario(speed)
    scene = Scene([], {"own": (box_vessel(), sc.vessels[0].trajectory), "tgt": (box_vessel(), sc.vessels[1].trajectory)})
    lid = Lidar(scene, EXACT, LidarMount(x=0.0, y=0.0, z=-2.0), platform="own", self_returns=False)
    start = T0
    s = lid.sweep(start, 0)
    w = sweep_to_world(lid, s)
    on = s.object_id == scene.vessel_ids["tgt"]
    assert on.sum() > 20
    t = start + s.time[on].astype(np.float64)
    # The target's west face (its stern) at east = 15 + v·t − 5 (own box is 10 m long, 4 m wide: from
    # east 2 the sensor sees the target's stern face).
    stern = 15.0 + speed * (t - T0) - 5.0
    face = np.abs(w[on, 1] - stern) < 2e-3
    assert face.mean() > 0.5
    spread = np.ptp(w[on][face, 1])
    assert spread > 0.15  # different columns, different times, different positions
    # Posing the whole sweep at its start instead would put every stern point at one east value.
    np.testing.assert_allclose(np.ptp(stern[face]), spread, rtol=1e-3)


def test_vessel_hidden_behind_a_nearer_one_and_self_returns() -> None:
    t = line(0.0, 0.0, 0.0, 0.0, 0.0)
    scene = Scene(
        [],
        {
            "own": (box_vessel(10.0, 4.0, 3.0), t),
            "near": (box_vessel(), line(0.0, 20.0, 0.0, 0.0, 0.0)),
            "far": (box_vessel(), line(0.0, 40.0, 0.0, 0.0, 0.0)),
        },
    )
    # 1 m above the ownship's 3 m deck: steep beams hit its own deck.
    lid = Lidar(scene, EXACT, LidarMount(x=0.0, y=0.0, z=-4.0), platform="own")
    s = lid.sweep(T0, 0)
    ids = set(np.unique(s.object_id).tolist())
    assert scene.vessel_ids["own"] in ids and scene.vessel_ids["near"] in ids
    own = s.object_id == scene.vessel_ids["own"]
    assert (s.range[own] < 6.0).all()
    w = sweep_to_world(lid, s)
    far = s.object_id == scene.vessel_ids["far"]
    assert not (far & (np.abs(w[:, 0]) < 1.0)).any()  # straight behind "near": hidden
    # Without self-returns the deck is not seen.
    s2 = Lidar(scene, EXACT, LidarMount(x=0.0, y=0.0, z=-4.0), platform="own", self_returns=False).sweep(T0, 0)
    assert scene.vessel_ids["own"] not in s2.object_id


def test_moving_ownship_poses_the_sensor_per_column() -> None:
    own = line(0.0, 0.0, 5.0, 0.0, 0.0)
    scene = Scene([WorldObject("wall", "quay", block(30.0, 31.0, -80.0, 80.0, 6.0, -1.0), 0.3)], {"own": (box_vessel(), own)})
    lid = Lidar(scene, EXACT, LidarMount(x=0.0, y=0.0, z=-4.0), platform="own", self_returns=False)
    s = lid.sweep(T0 + 1.0, 0)
    w = sweep_to_world(lid, s)
    np.testing.assert_allclose(w[:, 0], 30.0, atol=2e-3)  # the wall stays put in the world
    # ... while in the sensor frame its range shrinks as the ownship advances during the sweep.
    ahead = np.abs(s.y) < 1.0
    early, late = s.time[ahead] < 0.01, s.time[ahead] > 0.09
    assert early.any() and late.any()
    assert s.x[ahead][early].mean() - s.x[ahead][late].mean() == pytest.approx(0.5, abs=0.05)


def test_range_models_are_selectable() -> None:
    calls = []

    def ten_metres(scene: Scene, batch: BeamBatch) -> BeamRanges:
        calls.append(len(batch))
        hit = batch.directions[:, 2] < 0.0  # upwards only
        r = np.where(hit, np.float32(10.0), np.float32(np.inf)).astype(np.float32)
        nrm = -batch.directions.copy()
        return BeamRanges(r, np.where(hit, 0, -1).astype(np.int32), nrm)

    register_range_model("ten-metres", ten_metres)
    lid = fixed(wall_scene(), range_model="ten-metres")
    s = lid.sweep(T0, 0)
    assert calls == [EXACT.beams]
    np.testing.assert_allclose(s.range, 10.0, rtol=1e-6)
    assert (s.z > 0).all()
    with pytest.raises(InputError, match="unknown range model"):
        get_range_model("psychic")


def test_scenario_lidar_and_sweep_schedule() -> None:
    sc = moving_scenario(2.0)
    lid = lidar_for_scenario(sc)
    assert lid.platform == "own" and lid.seed == sc.seed and lid.mount == MILLIAMPERE_LIDAR_MOUNT
    starts = sweep_starts(sc)
    assert len(starts) == 50 and starts[1] - starts[0] == pytest.approx(0.1)
    with pytest.raises(InputError, match="outside"):
        lid.sweep(T0 + 100.0, 0)
    with pytest.raises(InputError, match="above the water"):
        Lidar(lid.scene, VLP16, LidarMount(z=0.5))
    with pytest.raises(InputError, match="not a vessel"):
        Lidar(lid.scene, VLP16, platform="nobody")


def test_batched_sweeps_equal_single_sweeps() -> None:
    sc = moving_scenario(6.0)
    scene = Scene.from_scenario(sc)
    cfg = VLP16.with_(dissipation=RangeDissipation(half_range=30.0, width=5.0))
    lid = Lidar(scene, cfg, LidarMount(x=0.0, y=0.0, z=-3.0, yaw_deg=30.0, roll_deg=180.0), platform="own", seed=3)
    starts = [T0 + 0.5, T0 + 0.6, T0 + 0.7]
    batched = lid.sweeps(starts, [5, 6, 7])
    for s, start, frame in zip(batched, starts, [5, 6, 7]):
        one = lid.sweep(start, frame)
        assert s.stamp == one.stamp and s.frame == one.frame
        for field in ("x", "y", "z", "intensity", "ring", "time", "object_id"):
            np.testing.assert_array_equal(getattr(s, field), getattr(one, field))
    assert scene.vessel_ids["tgt"] in np.concatenate([s.object_id for s in batched])
    lid.config = cfg.with_(drop_probability=0.0)
    both = lid.sweeps(starts[:2])
    np.testing.assert_array_equal(both[1].x, lid.sweep(starts[1], 1).x)
    assert lid.sweeps([]) == []
    with pytest.raises(InputError, match="frame numbers"):
        lid.sweeps(starts, [1])


@settings(max_examples=8, deadline=None)
@given(
    drop=st.floats(0.0, 0.95),
    sigma=st.floats(0.0, 0.2),
    half=st.one_of(st.none(), st.floats(5.0, 80.0)),
    seed=st.integers(0, 50),
)
def test_redrawn_ranged_beams_equal_a_direct_simulation(drop, sigma, half, seed) -> None:
    # The lidar fit ranges every beam once and redraws drop, dissipation and noise per candidate: the points must be
    # those of simulating that candidate directly, bit for bit (raycast), the carrier's own returns included.
    sc = moving_scenario(3.0)
    scene = Scene.from_scenario(sc)
    mount = LidarMount(x=0.0, y=0.0, z=-3.0, yaw_deg=30.0, roll_deg=180.0)
    ranged = Lidar(scene, VLP16, mount, platform="own", seed=seed).ranged([T0 + 0.5, T0 + 0.6], [5, 6])
    diss = None if half is None else RangeDissipation(half_range=half, width=5.0)
    lid = Lidar(scene, VLP16.with_(drop_probability=drop, range_accuracy=2 * sigma, dissipation=diss), mount, "own", seed=seed)
    direct, redrawn = lid.sweeps([T0 + 0.5, T0 + 0.6], [5, 6]), lid.redraw(ranged)
    for a, b in zip(direct, redrawn, strict=True):
        assert (a.stamp, a.frame) == (b.stamp, b.frame)
        for field in ("x", "y", "z", "intensity", "ring", "time", "object_id"):
            np.testing.assert_array_equal(getattr(a, field), getattr(b, field))
    assert sum(len(s) for s in direct) > 0 or drop > 0.9


def test_redraw_refuses_beams_of_another_lidar() -> None:
    sc = moving_scenario(2.0)
    scene = Scene.from_scenario(sc)
    ranged = Lidar(scene, VLP16, platform="own").ranged([T0 + 0.5], [5])
    with pytest.raises(InputError, match="beam pattern or mount"):
        Lidar(scene, VLP16_THESIS, platform="own").redraw(ranged)
    with pytest.raises(InputError, match="frame numbers"):
        Lidar(scene, VLP16, platform="own").ranged([T0 + 0.5], [5, 6])


def test_lidar_yaml_round_trip_and_bad_field(tmp_path) -> None:
    from seatwin.sensors.lidar_config import load_lidar_config, save_lidar_config

    cfg = VLP16.with_(drop_probability=0.63, range_accuracy=0.07, dissipation=RangeDissipation(half_range=47.0))
    path = save_lidar_config(cfg, tmp_path / "l.yaml", {"note": "a report"})
    assert load_lidar_config(path) == cfg
    (tmp_path / "bad.yaml").write_text("lidar:\n  drop_probability: 1.5\n", encoding="utf-8")
    with pytest.raises(InputError, match="drop_probability") as err:
        load_lidar_config(tmp_path / "bad.yaml")
    assert "bad.yaml" in str(err.value)
    (tmp_path / "list.yaml").write_text("- 1\n", encoding="utf-8")
    with pytest.raises(InputError, match="mapping"):
        load_lidar_config(tmp_path / "list.yaml")
    with pytest.raises(InputError, match="no such"):
        load_lidar_config(tmp_path / "none.yaml")
