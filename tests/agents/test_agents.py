"""The reference agent's guidance and COLREG velocity obstacles (seatwin.agents)."""

from __future__ import annotations

import math

import pytest

from seatwin.agents import (
    AvoidanceParameters,
    Mission,
    Navigation,
    ReferenceAgent,
    TrackEstimate,
    choose_velocity,
    los_guidance,
    make_agent,
)
from seatwin.encounters import Kind
from seatwin.errors import ParameterError

MISSION = Mission(0.0, 0.0, 300.0, 0.0, 2.0, "none")
P = AvoidanceParameters()


def nav(north=0.0, east=0.0, heading=0.0, u=2.0):
    return Navigation(0.0, north, east, heading, u, 0.0, 0.0)


def test_los_follows_the_path_and_steers_back_to_it():
    speed, course = los_guidance(nav(), MISSION, P)
    assert (speed, course) == (2.0, 0.0)
    _, course = los_guidance(nav(east=20.0), MISSION, P)
    assert course == pytest.approx(-math.pi / 4)  # 20 m to starboard of the path, 20 m lookahead: 45° back to port
    speed, course = los_guidance(nav(north=299.0, heading=0.3), MISSION, P)
    assert speed == 0.0 and course == 0.3  # arrived: stop, hold the heading
    speed, course = los_guidance(nav(north=310.0, east=30.0), MISSION, P)
    assert speed > 0 and course == pytest.approx(math.atan2(-30.0, -10.0))  # past the goal abeam: back to it
    speed, _ = los_guidance(nav(north=295.0), MISSION, P)
    assert 0.3 <= speed < 2.0  # slowing down for the goal


def test_a_target_passing_clear_to_starboard_is_not_crossed_ahead_of():
    target = TrackEstimate(8, 150.0, 15.0, -2.0, 0.0)  # head-on, passing 15 m to starboard: inside 20 m, but clear
    speed, course, acting = choose_velocity(nav(), 2.0, 0.0, [target], P)
    assert acting == {8: Kind.HEAD_ON}
    assert course <= 0.0 or speed < 2.0  # widened to port of it (or slowed), never across its bow to starboard


def test_an_agent_stopped_at_its_goal_still_gets_out_of_the_way():
    target = TrackEstimate(6, -12.0, 0.0, 1.0, 0.0)  # coming up from astern onto a stopped ownship, 12 s away
    stopped = nav(u=0.0)
    assert choose_velocity(stopped, 0.0, 0.0, [target], P)[:2] == (0.0, 0.0)  # speeds scaled by 0: nowhere to go
    speed, course, acting = choose_velocity(stopped, 0.0, 0.0, [target], P, speed_scale=2.0)
    assert acting and speed > 0


def test_no_obstacle_keeps_the_desired_velocity():
    assert choose_velocity(nav(), 2.0, 0.1, [], P) == (2.0, 0.1, {})


def test_head_on_turns_to_starboard_and_clears_the_safety_radius():
    target = TrackEstimate(7, 150.0, 0.0, -2.0, 0.0)
    speed, course, acting = choose_velocity(nav(), 2.0, 0.0, [target], P)
    assert acting == {7: Kind.HEAD_ON}
    assert course > 0  # to starboard
    # with the chosen velocity held, the target passes at least the safety radius off
    vn, ve = speed * math.cos(course) - target.v_north, speed * math.sin(course) - target.v_east
    t = (150.0 * vn) / (vn * vn + ve * ve)
    assert math.hypot(150.0 - vn * t, -ve * t) >= P.safety_radius - 1e-6


def test_a_give_way_crossing_passes_astern_not_ahead():
    target = TrackEstimate(3, 100.0, 100.0, 0.0, -2.0)  # from starboard, heading west: collision course
    speed, course, acting = choose_velocity(nav(), 2.0, 0.0, [target], P)
    assert acting == {3: Kind.CROSSING_GIVE_WAY}
    assert course > 0 or speed < 2.0  # turns to starboard (behind it) or slows, never crosses ahead to port


def test_stand_on_and_late_agents_wait():
    from_port = TrackEstimate(4, 100.0, -100.0, 0.0, 2.0)  # from port: the ownship stands on until 15 s before CPA
    assert choose_velocity(nav(), 2.0, 0.0, [from_port], P)[2] == {}
    head_on = TrackEstimate(5, 150.0, 0.0, -2.0, 0.0)  # CPA in 37.5 s
    late = AvoidanceParameters(reaction_time=10.0)
    assert choose_velocity(nav(), 2.0, 0.0, [head_on], late)[2] == {}
    assert choose_velocity(nav(), 2.0, 0.0, [TrackEstimate(5, 30.0, 0.0, -2.0, 0.0)], late)[2] == {5: Kind.HEAD_ON}


def test_an_engaged_obstacle_keeps_its_first_situation_until_passed():
    # after turning to starboard the head-on target is on the port bow; still avoided as head-on
    target = TrackEstimate(9, 80.0, -10.0, -2.0, 0.0)
    _, _, acting = choose_velocity(nav(heading=0.5), 2.0, 0.0, [target], P, engaged={9: Kind.HEAD_ON})
    assert acting == {9: Kind.HEAD_ON}
    passed = TrackEstimate(9, -30.0, -10.0, -2.0, 0.0)
    assert choose_velocity(nav(), 2.0, 0.0, [passed], P, engaged={9: Kind.HEAD_ON})[2] == {}


def test_agent_variants_and_their_errors():
    assert make_agent("perfect").sensors == ("truth",)
    assert make_agent("reference").sensors == ("lidar", "radar")
    assert make_agent("late").params.reaction_time == 10.0
    with pytest.raises(ParameterError, match="unknown agent"):
        make_agent("reckless")
    with pytest.raises(ParameterError) as err:
        ReferenceAgent(sensors=("camera",))
    assert err.value.param == "sensors"
    with pytest.raises(ParameterError, match="not reset"):
        ReferenceAgent(perception="truth").step(0.0, [], nav())
