"""The lock-step closed loop and its verdicts (seatwin.verification)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from seatwin.agents import ForceCommand, SetPoint, make_agent
from seatwin.encounters import encounter_scenario, space
from seatwin.errors import ParameterError
from seatwin.layout import DEFAULT_LAYOUT
from seatwin.sim.settings import SimulationSettings
from seatwin.verification import hulls_overlap, judge, run_closed_loop


def _scenario(family, u=0.5, harbour="none", seed=1, **kw):
    sp = space(family, **kw)
    return encounter_scenario(sp.encounter([u] * sp.dimension), f"{family}_{u}", harbour, seed)[0]


def test_hull_overlap_hand_cases():
    box = np.array([[[1.0, 0.5], [1.0, -0.5], [-1.0, -0.5], [-1.0, 0.5]]])
    assert hulls_overlap(box, box + [1.5, 0.0])[0]
    assert not hulls_overlap(box, box + [2.1, 0.0])[0]
    diamond = np.array([[[0.0, 1.0], [1.0, 0.0], [0.0, -1.0], [-1.0, 0.0]]]) + [1.9, 1.4]
    assert not hulls_overlap(box, diamond)[0]  # corners near but apart: only the diamond's edges separate them


@pytest.mark.parametrize("family", ["head_on", "crossing_give_way", "crossing_stand_on", "overtaking", "multi"])
def test_perfect_perception_avoids_a_collision_course(family):
    rec = run_closed_loop(_scenario(family), make_agent("perfect"))
    v = judge(rec)
    assert v.passed, v.reasons
    assert not v.collision and v.min_distance >= 10.0
    assert all(f.nominal_cpa < 1.0 for f in v.targets)  # they were on a collision course (cpa at the middle: 0 m)


def test_a_late_agent_fails_and_the_verdict_says_why():
    v = judge(run_closed_loop(_scenario("crossing_give_way"), make_agent("late", sensors=("lidar",))))
    assert not v.passed
    assert any("collision" in r or "safety domain" in r for r in v.reasons), v.reasons
    assert any("COLREG" in r and "late" in r for r in v.reasons), v.reasons


def test_the_loop_is_deterministic_and_a_slow_agent_changes_nothing():
    sc = _scenario("head_on", tcpa=(20.0, 20.0), run_out=5.0)
    a = run_closed_loop(sc, make_agent("reference", sensors=("lidar",)), duration=12.0)
    slow = make_agent("reference", sensors=("lidar",))
    step = slow.step

    def sleepy(*args):
        time.sleep(0.002)
        return step(*args)

    slow.step = sleepy
    b = run_closed_loop(sc, slow, duration=12.0)
    np.testing.assert_array_equal(a.own, b.own)
    np.testing.assert_array_equal(a.command[:-1], b.command[:-1])
    assert a.frames == b.frames == {"lidar": 120}
    assert a.tracked["target_1"].any()  # the lidar tracks the target within 100 m
    c = run_closed_loop(sc, make_agent("reference", sensors=("lidar",)), SimulationSettings(seed=7), duration=12.0)
    assert not np.array_equal(a.own, c.own) or a.tracked["target_1"].sum() != c.tracked["target_1"].sum()


class FullAhead:
    """A minimal agent of the interface: a constant force, no sensors."""

    name = "full_ahead"
    sensors: tuple[str, ...] = ()

    def reset(self, mission):
        self.mission = mission

    def step(self, time, frames, navigation):
        return ForceCommand(1000.0, 0.0, 0.0)

    def tracks(self):
        return []


class EastAtFullSpeed(FullAhead):
    def step(self, time, frames, navigation):
        return SetPoint(2.5, np.pi / 2)


def test_grounding_is_found_with_the_harbours_land():
    sc = _scenario("head_on", harbour="default", tcpa=(20.0, 30.0), run_out=30.0)
    v = judge(run_closed_loop(sc, EastAtFullSpeed()), DEFAULT_LAYOUT)
    assert v.grounding and any(r.startswith("grounding at") for r in v.reasons)  # the 150 m channel's east quay
    assert not v.passed
    rec = run_closed_loop(sc, FullAhead(), duration=10.0)
    assert rec.own[-1, 3] > rec.own[0, 3]  # a force command: it speeds up from its cruise speed
    assert not judge(rec, DEFAULT_LAYOUT).grounding


def test_bad_commands_are_named():
    class Broken(FullAhead):
        def step(self, time, frames, navigation):
            return ForceCommand(float("nan"), 0.0, 0.0)

    with pytest.raises(ParameterError, match="non-finite command"):
        run_closed_loop(_scenario("head_on"), Broken(), duration=1.0)
    with pytest.raises(ParameterError, match="dt"):
        run_closed_loop(_scenario("head_on"), FullAhead(), dt=0.0)
