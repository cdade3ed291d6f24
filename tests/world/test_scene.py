"""Scene: static geometry once, vessels posed at any time."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.scenario.model import Role, Scenario, Trajectory, Vessel
from seatwin.world.scene import Scene


def scenario(model: str = "havfruen") -> Scenario:
    t = 1000.0 + np.arange(0.0, 10.01, 0.5)
    own = Trajectory(t, np.zeros_like(t), np.zeros_like(t), np.zeros_like(t))
    tgt = Trajectory(t, 20.0 + 2.0 * (t - t[0]), np.full_like(t, 5.0), np.full_like(t, np.pi / 2))
    return Scenario("s", [Vessel("own", Role.OWNSHIP, own, "milliampere"), Vessel("tgt", Role.TARGET, tgt, model)])


def test_object_ids_and_poses() -> None:
    sc = scenario()
    scene = Scene.from_scenario(sc)
    assert [o.name for o in scene.objects[-2:]] == ["own", "tgt"]
    assert scene.vessel_ids["tgt"] == len(scene.objects) - 1
    assert all(o.id == i for i, o in enumerate(scene.objects))
    assert scene.reflectivity[-1] == 0.0  # a miss (id −1)
    p = scene.pose("tgt", [1002.25, 1004.0])
    ref = sc.state_at("tgt", [1002.25, 1004.0])
    np.testing.assert_allclose(p.north, ref.north)
    np.testing.assert_allclose(p.east, ref.east)
    np.testing.assert_allclose(np.cos(p.heading), np.cos(ref.heading))
    with pytest.raises(InputError, match="outside"):
        scene.pose("tgt", 2000.0)
    with pytest.raises(InputError, match="no vessel"):
        scene.pose("ghost", 1000.0)


def test_posed_meshes_put_the_vessel_where_the_trajectory_says() -> None:
    scene = Scene.from_scenario(scenario())
    m = scene.vessel_mesh_at("tgt", 1005.0)
    lo, hi = m.vertices.min(0), m.vertices.max(0)
    # Heading east: the 8 m length lies along east, centred on (north 30, east 5).
    assert (lo[0] + hi[0]) / 2 == pytest.approx(30.0, abs=0.05)
    assert hi[1] - lo[1] == pytest.approx(8.0, abs=0.01)
    meshes = scene.posed_meshes(1005.0, exclude=["own"])
    assert len(meshes) == len(scene.static_meshes) + 1


def test_vessel_caster_is_in_the_body_frame() -> None:
    scene = Scene.from_scenario(scenario())
    h = scene.vessel_caster("tgt").cast([[0.0, 0.0, -10.0], [1.0, 0.0, -10.0]], [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]])
    assert h.object_id.tolist() == [scene.vessel_ids["tgt"]] * 2
    # Havfruen's roof rig tops out at 2.6 m, its cabin roof (x = 1) at 2.4 m above the water.
    np.testing.assert_allclose(h.range, [7.4, 7.6], atol=1e-4)


def test_unknown_model_and_water() -> None:
    with pytest.raises(InputError, match="unknown vessel model"):
        Scene.from_scenario(scenario("zeppelin"))
    sc = scenario()
    sc.environment["water"] = "storm"
    with pytest.raises(InputError, match="only 'flat'"):
        Scene.from_scenario(sc)
    sc.environment.update(water="flat", harbour="none")
    assert Scene.from_scenario(sc).static_objects == []


def test_a_bad_harbour_override_names_the_parameter() -> None:
    from seatwin.errors import ParameterError

    sc = scenario()
    with pytest.raises(ParameterError, match="unknown harbour") as exc:
        Scene.from_scenario(sc, harbour="atlantis")
    assert exc.value.param == "harbour"
    sc.environment["harbour"] = "atlantis"  # the scenario's own harbour: the scenario is named
    with pytest.raises(InputError, match="unknown harbour") as exc2:
        Scene.from_scenario(sc)
    assert not isinstance(exc2.value, ParameterError) and exc2.value.where == "environment.harbour"


def test_a_scene_takes_any_scenario_shaped_object() -> None:
    from types import SimpleNamespace

    sc = scenario()
    vessels = [SimpleNamespace(**vars(v)) for v in sc.vessels]
    duck = SimpleNamespace(source="duck", environment={"harbour": "none"}, vessels=vessels)
    scene = Scene.from_scenario(duck)
    assert scene.vessel_names == ["own", "tgt"] and scene.static_objects == []
