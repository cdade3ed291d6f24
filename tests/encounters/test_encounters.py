"""Encounter geometry, spaces and samplers, placement on water, scenario files (seatwin.encounters)."""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.cli.main import run
from seatwin.encounters import (
    SPACES,
    Kind,
    TargetGeometry,
    adaptive_search,
    closest_approach,
    encounter_scenario,
    latin_hypercube,
    place,
    random_points,
    save_encounter,
    space,
    target_start,
)
from seatwin.errors import InputError, ParameterError
from seatwin.layout import DEFAULT_LAYOUT
from seatwin.scenario import load_scenario
from seatwin.scenario.on_water import is_water_in


@settings(max_examples=150, deadline=None)
@given(
    st.floats(0.5, 3.0),
    st.floats(-40.0, 40.0),
    st.floats(5.0, 200.0),
    st.floats(-math.pi, math.pi),
    st.floats(0.0, 4.0),
)
def test_the_start_gives_the_asked_cpa_and_tcpa(own_speed, cpa, tcpa, course, speed):
    t = TargetGeometry(cpa, tcpa, course, speed)
    if math.hypot(speed * math.cos(course) - own_speed, speed * math.sin(course)) < 0.05:
        return  # hardly any relative motion
    s = target_start(own_speed, t)
    d, tc = closest_approach((0.0, 0.0, own_speed, 0.0), (s.north, s.east, speed * math.cos(course), speed * math.sin(course)))
    assert d == pytest.approx(abs(cpa), abs=1e-6)
    assert tc == pytest.approx(tcpa, rel=1e-9, abs=1e-6)
    east_at_cpa = s.east + speed * math.sin(course) * tcpa
    if abs(east_at_cpa) > 1e-6:
        assert (east_at_cpa > 0) == (cpa > 0)  # positive CPA: the target passes on the starboard side


@pytest.mark.parametrize("family", list(SPACES))
@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_every_point_of_a_family_is_the_kind_it_is_drawn_as(family, data):
    sp = space(family)
    u = data.draw(st.lists(st.floats(0.0, 1.0), min_size=sp.dimension, max_size=sp.dimension))
    e = sp.encounter(u)
    assert e.situations == e.kinds


@pytest.mark.parametrize("family", list(SPACES))
def test_the_corners_of_a_family_are_its_kind(family):
    sp = space(family)
    for corner in itertools.product([0.0, 1.0], repeat=sp.dimension):
        e = sp.encounter(corner)
        assert e.situations == e.kinds, (corner, e)


def test_hand_situations():
    assert target_start(2.0, TargetGeometry(0.0, 50.0, math.pi, 2.0)).bearing == pytest.approx(0.0)
    assert space("head_on").encounter([0.5] * 5).situations == (Kind.HEAD_ON,)
    # a target from port crossing to starboard: the ownship stands on
    s = target_start(2.0, TargetGeometry(0.0, 50.0, math.radians(90.0), 2.0))
    assert (s.north, s.east) == pytest.approx((100.0, -100.0))
    assert Kind.CROSSING_GIVE_WAY.give_way and not Kind.CROSSING_STAND_ON.give_way


def test_latin_hypercube_hits_each_stratum_once_and_samplers_repeat_for_a_seed():
    pts = latin_hypercube(5, 40, seed=3)
    for axis in range(5):
        assert sorted(np.floor(pts[:, axis] * 40).astype(int)) == list(range(40))
    np.testing.assert_array_equal(pts, latin_hypercube(5, 40, seed=3))
    np.testing.assert_array_equal(random_points(5, 10, 7), random_points(5, 10, 7))
    assert not np.array_equal(latin_hypercube(5, 40, seed=4), pts)


def test_adaptive_search_finds_a_small_failure_region_sooner_than_random():
    centre = np.array([0.8, 0.2, 0.7])

    def score(u):
        return float(np.linalg.norm(np.asarray(u) - centre)) - 0.1  # fails within 0.1 of the centre (0.4 % of the cube)

    adaptive, rand = [], []
    for seed in range(5):
        trials = adaptive_search(score, 3, budget=300, seed=seed)
        assert trials[-1].score < 0
        adaptive.append(len(trials))
        scores = [score(u) for u in random_points(3, 2000, seed)]
        rand.append(next(i + 1 for i, s in enumerate(scores) if s < 0))
    assert sum(adaptive) < sum(rand)
    assert adaptive_search(score, 3, budget=300, seed=1) == adaptive_search(score, 3, budget=300, seed=1)


def test_bad_space_input_is_named():
    with pytest.raises(ParameterError, match="family"):
        space("collision")
    with pytest.raises(ParameterError, match="expected 5 values"):
        space("head_on").encounter([0.5, 0.5])
    with pytest.raises(ParameterError, match="tcpa"):
        TargetGeometry(1.0, -5.0, 0.0, 1.0)
    with pytest.raises(ParameterError, match="no relative motion"):
        target_start(2.0, TargetGeometry(1.0, 5.0, 0.0, 2.0))


@pytest.mark.parametrize("family", ["head_on", "crossing_give_way", "multi"])
def test_placement_in_the_default_harbour_keeps_every_path_on_water(family):
    e = space(family, run_out=10.0, tcpa=(20.0, 30.0)).encounter([0.5] * space(family).dimension)
    for seed in range(3):
        _, p = place(e, "default", seed, 0.0)
        for q in (p.ownship, *p.targets):
            assert is_water_in(DEFAULT_LAYOUT, q.north, q.east).all()
    pl, _ = place(e, "none", 0, 0.0)
    assert (pl.north, pl.east) == (0.0, 0.0)


def test_a_harbour_too_small_is_a_clear_error(tmp_path):
    (tmp_path / "pond.yaml").write_text(
        "map_width: 20\nmap_height: 20\ngrid_resolution: 1.0\norigin_x_coordinate: 0\norigin_y_coordinate: 0\n"
    )
    (tmp_path / "pond.bin").write_bytes(np.ones(400, np.uint8).tobytes())
    with pytest.raises(InputError, match="no place on water"):
        place(space("head_on").encounter([0.5] * 5), str(tmp_path / "pond.yaml"), 0, 0.0, tries=50)


def test_a_saved_encounter_loads_back_and_seatwin_simulate_replays_it(tmp_path):
    e = space("multi", run_out=10.0, tcpa=(20.0, 30.0)).encounter([0.3] * 9)
    scenario, path = save_encounter(e, tmp_path / "enc.yaml", harbour="default", seed=5)
    back = load_scenario(path)
    assert [v.name for v in back.vessels] == [v.name for v in scenario.vessels]
    for a, b in zip(back.vessels, scenario.vessels):
        np.testing.assert_allclose(a.trajectory.north, b.trajectory.north, atol=1e-6)
        np.testing.assert_allclose(a.trajectory.east, b.trajectory.east, atol=1e-6)
    assert back.environment["harbour"] == "default" and back.seed == 5
    record = json.loads((tmp_path / "enc.encounter.json").read_text())
    assert record["situations"] == ["head_on", "crossing_give_way"] and record["parameters"]["cpa_1"] == e.targets[0].cpa
    # the same encounter and seed give the same scenario
    again, _ = encounter_scenario(e, "enc", "default", 5)
    np.testing.assert_array_equal(again.vessels[0].trajectory.north, scenario.vessels[0].trajectory.north)
    out = tmp_path / "run"
    assert run(["simulate", str(path), "--out", str(out), "--sensors", "lidar", "--duration", "1", "--no-progress"]) == 0
    assert (out / "scenario.yaml").is_file() or any(out.iterdir())
