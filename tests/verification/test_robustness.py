"""The continuous robustness of a closed-loop run: time to breach, its sign against the verdict, its order."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.agents import AvoidanceParameters, ReferenceAgent
from seatwin.agents.interface import SetPoint
from seatwin.encounters import encounter_scenario, space
from seatwin.verification import judge, run_closed_loop
from seatwin.verification.robustness import closest_approach_distance, robustness, time_to_breach

coord = st.floats(-200.0, 200.0, allow_nan=False)
speed = st.floats(-6.0, 6.0, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(pn=coord, pe=coord, wn=speed, we=speed, radius=st.floats(1.0, 30.0))
def test_time_to_breach_is_the_first_entry_into_the_circle(pn, pe, wn, we, radius):
    a = [np.array([x]) for x in (pn, pe, wn, we)]
    tau = float(time_to_breach(*a, radius)[0])
    cpa = float(closest_approach_distance(*a)[0])
    if math.hypot(pn, pe) <= radius:
        assert tau == 0.0
    elif math.isinf(tau):
        assert cpa >= radius - 1e-6  # never enters: the closest approach stays outside
    else:
        assert tau > 0
        assert math.isclose(math.hypot(pn + wn * tau, pe + we * tau), radius, rel_tol=1e-6, abs_tol=1e-6)  # on the circle
        for s in np.linspace(0.0, tau, 7)[:-1]:
            assert math.hypot(pn + wn * s, pe + we * s) > radius - 1e-6  # outside until then
        assert cpa <= radius + 1e-6


class HoldCourse:
    """An agent that ignores every target: sails its start heading at its cruise speed."""

    name, sensors = "hold", ("truth",)

    def reset(self, mission):
        self.speed = mission.cruise_speed
        self.course = math.atan2(mission.goal_east - mission.start_east, mission.goal_north - mission.start_north)

    def step(self, time, frames, navigation):
        return SetPoint(self.speed, self.course)

    def tracks(self):
        return []


def _late(reaction):
    return ReferenceAgent("late", "truth", avoidance=replace(AvoidanceParameters(), reaction_time=reaction))


def test_robustness_is_negative_on_failure_and_smaller_the_later_the_agent_reacts():
    sp = space("crossing_give_way")
    scenario, _ = encounter_scenario(sp.encounter([0.75, 0.55, 0.33, 0.43, 0.76]), "rob", "none", 0)  # CPA +2 m
    scores = {}
    for name, agent in (("hold", HoldCourse()), ("perfect", ReferenceAgent("perfect", "truth")), ("late", _late(20.0))):
        rec = run_closed_loop(scenario, agent)
        v = judge(rec)
        scores[name] = robustness(rec, v, 10.0)
        assert (scores[name] < 0) == (not v.passed)
    assert scores["hold"] < 0  # no avoidance: inside the safety distance (the breach's depth, in metres)
    assert 0 <= scores["late"] < scores["perfect"]  # both pass; the late one came closer to breaching
