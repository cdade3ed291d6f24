"""The 3-DOF model, thrusters, RK4, autopilot and waypoint targets (seatwin.dynamics)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.dynamics import (
    MILLIAMPERE,
    MILLIAMPERE_THRUSTERS,
    Autopilot,
    Model,
    ThrusterState,
    VesselState,
    actuate,
    allocate,
    follow_waypoints,
    generalised_force,
    rk4,
    step_force,
    step_thrusters,
)
from seatwin.dynamics.sanity import manoeuvres
from seatwin.errors import ParameterError

REST = VesselState(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, ThrusterState.idle())
speeds = st.floats(-3.0, 3.0)
rates = st.floats(-1.0, 1.0)
forces = st.floats(-800.0, 800.0)


@settings(max_examples=60, deadline=None)
@given(speeds, speeds, rates, forces, forces, st.floats(-1500.0, 1500.0))
def test_accelerations_solve_the_matrix_equation(u, v, r, X, Y, N):
    p, nu, tau = MILLIAMPERE, np.array([u, v, r]), np.array([X, Y, N])
    expected = np.linalg.solve(p.mass_matrix(), tau - p.coriolis(nu) @ nu - p.damping(nu) @ nu)
    np.testing.assert_allclose(Model(p).accelerations((u, v, r), (X, Y, N)), expected, rtol=1e-9, atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(speeds, speeds, rates)
def test_coriolis_does_no_work(u, v, r):
    nu = np.array([u, v, r])
    C = MILLIAMPERE.coriolis(nu)
    np.testing.assert_allclose(C, -C.T)
    assert abs(nu @ C @ nu) < 1e-9


def test_top_speed_is_where_full_thrust_meets_the_surge_resistance():
    p = MILLIAMPERE
    full = sum(MILLIAMPERE_THRUSTERS.max_thrust)
    roots = np.roots([-p.X_uuu, -p.X_uu, -p.X_u, -full])  # 13.965 u³ + 110.064 u² + 27.632 u = 1000
    u_star = max(float(x.real) for x in roots if abs(x.imag) < 1e-12)
    m = manoeuvres()
    assert m.top_speed == pytest.approx(u_star, rel=1e-4)
    assert 2.0 < m.top_speed < 3.0  # milliAmpere: about 5 knots
    assert m.crash_stop_distance < m.coast_distance
    assert m.crash_stop_time < m.coast_time
    assert 1.0 < m.turn_radius < 50.0 and m.turn_speed < m.top_speed  # weak identified yaw damping: a tight circle


def test_rk4_is_fourth_order():
    model, tau = Model(MILLIAMPERE), (600.0, 100.0, 400.0)
    start = replace(REST, u=1.0, r=0.05)

    def at(t_end, dt):
        s = start
        for _ in range(round(t_end / dt)):
            s = rk4(model, s, tau, dt)
        return np.array([s.north, s.east, s.heading, s.u, s.v, s.r])

    ref = at(8.0, 0.0125)
    e1 = np.abs(at(8.0, 0.4) - ref).max()
    e2 = np.abs(at(8.0, 0.2) - ref).max()
    assert 10.0 < e1 / e2 < 22.0  # 2⁴ = 16


def test_a_step_is_deterministic():
    model = Model(MILLIAMPERE)
    a = step_force(model, MILLIAMPERE_THRUSTERS, replace(REST, u=1.3, r=0.01), (300.0, 20.0, 100.0), 0.1)
    b = step_force(model, MILLIAMPERE_THRUSTERS, replace(REST, u=1.3, r=0.01), (300.0, 20.0, 100.0), 0.1)
    assert a == b


@settings(max_examples=60, deadline=None)
@given(st.floats(-400.0, 400.0), st.floats(-200.0, 200.0), st.floats(-300.0, 300.0))
def test_allocation_gives_the_asked_force_when_within_limits(X, Y, N):
    angles, thrusts = allocate(MILLIAMPERE_THRUSTERS, (X, Y, N), ThrusterState.idle())
    got = generalised_force(MILLIAMPERE_THRUSTERS, ThrusterState(angles, thrusts))
    tol = 2 * MILLIAMPERE_THRUSTERS.min_force * 1.8  # a thruster asked for under 1 N is left off
    np.testing.assert_allclose(got, (X, Y, N), atol=tol)


def test_allocation_scales_an_impossible_force_keeping_its_direction():
    angles, thrusts = allocate(MILLIAMPERE_THRUSTERS, (3000.0, 0.0, 900.0), ThrusterState.idle())
    assert max(thrusts) == pytest.approx(500.0)
    X, Y, N = generalised_force(MILLIAMPERE_THRUSTERS, ThrusterState(angles, thrusts))
    assert abs(Y) < 1e-9
    ratio = N / X
    assert ratio == pytest.approx(0.3)


def test_actuators_respect_their_rate_limits_and_turn_the_short_way():
    th = MILLIAMPERE_THRUSTERS
    s = ThrusterState((math.radians(170.0), 0.0), (0.0, 0.0))
    n = actuate(th, s, (math.radians(-170.0), math.radians(90.0)), (500.0, 500.0), 0.1)
    assert math.degrees(n.angle[0]) == pytest.approx(173.446, abs=1e-3)  # towards ±180°, not back through 0
    assert math.degrees(n.angle[1]) == pytest.approx(3.753, abs=1e-6)
    assert n.thrust == (25.0, 25.0)


def test_the_thrust_acts_along_the_actual_azimuth_while_it_turns():
    model, th = Model(MILLIAMPERE), MILLIAMPERE_THRUSTERS
    s = step_thrusters(model, th, REST, ((math.pi / 2, math.pi / 2), (500.0, 500.0)), 0.1)
    assert s.thrusters.angle[0] == pytest.approx(th.max_angle_rate[0] * 0.1)
    assert s.v > 0 and s.u > 0  # mostly still ahead after one step


def test_autopilot_reaches_its_set_points():
    model, th, ap = Model(MILLIAMPERE), MILLIAMPERE_THRUSTERS, Autopilot()
    s = REST
    for _ in range(900):
        s = step_force(model, th, s, ap.force(MILLIAMPERE, s, 2.0, math.radians(90.0)), 0.1)
    assert s.u == pytest.approx(2.0, abs=0.05)
    assert math.degrees(s.heading) == pytest.approx(90.0, abs=1.0)


def test_a_straight_waypoint_leg_is_exactly_straight():
    p = follow_waypoints([(0.0, 0.0), (100.0, 100.0)], 2.0, 1000.0, 60.0, dt=0.1)
    assert p.time[0] == 1000.0 and p.time[-1] == pytest.approx(1060.0)
    np.testing.assert_allclose(p.north, p.east, atol=1e-9)
    np.testing.assert_allclose(np.hypot(np.diff(p.north), np.diff(p.east)), 0.2, rtol=1e-12)
    np.testing.assert_allclose(p.heading, math.pi / 4)


def test_waypoints_with_a_turn_end_on_the_second_leg():
    p = follow_waypoints([(0.0, 0.0), (100.0, 0.0), (100.0, 200.0)], 2.0, 0.0, 150.0, dt=0.1, max_turn_rate=math.radians(10.0))
    assert abs(p.north[-1] - 100.0) < 1.0 and 60.0 < p.east[-1] < 200.0
    assert math.degrees(p.heading[-1]) == pytest.approx(90.0, abs=1.0)
    assert np.all(np.abs(np.diff(np.unwrap(p.heading))) <= math.radians(10.0) * 0.1 + 1e-12)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [({"waypoints": [(0.0, 0.0)]}, "waypoints"), ({"speed": -1.0}, "speed"), ({"duration": 0.0}, "dt")],
)
def test_bad_waypoint_input_names_the_parameter(kwargs, name):
    args = {"waypoints": [(0.0, 0.0), (1.0, 1.0)], "speed": 1.0, "start_time": 0.0, "duration": 10.0, **kwargs}
    with pytest.raises(ParameterError) as err:
        follow_waypoints(**args)
    assert err.value.param == name
