"""Built-in scenarios: on water, plausible speeds, smooth, and the situations they are meant to make."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.layout import DEFAULT_LAYOUT, Box
from seatwin.scenario import builtin_names, builtin_scenario, load_scenario
from seatwin.scenario.model import Role, Scenario, VesselState
from seatwin.scenario.summary import closest_approach

REQUIRED = {
    "ferry_crossing",
    "evasive_halted_ferry",
    "stop_and_evade",
    "targets_in_line",
    "surprise_separation",
    "constant_bearing",
    "emerging_target",
}


@pytest.fixture(scope="module")
def scenarios() -> dict[str, Scenario]:
    return {name: builtin_scenario(name) for name in builtin_names()}


def _states(sc: Scenario) -> tuple[np.ndarray, dict[str, VesselState]]:
    t = sc.ownship.trajectory.time
    return t, {v.name: v.trajectory.state_at(t) for v in sc.vessels}


def _bearing(frm: VesselState, to: VesselState) -> np.ndarray:
    return np.arctan2(to.east - frm.east, to.north - frm.north)


def _angle_diff_deg(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.degrees(np.abs(np.angle(np.exp(1j * (a - b)))))


def _segment_hits_box(p0: tuple[float, float], p1: tuple[float, float], box: Box) -> bool:
    """Does the 2-D segment p0→p1 (north, east) pass through the box? (Liang–Barsky clipping.)"""
    lo, hi = 0.0, 1.0
    for x0, dx, bmin, bmax in (
        (p0[0], p1[0] - p0[0], box.north_min, box.north_max),
        (p0[1], p1[1] - p0[1], box.east_min, box.east_max),
    ):
        if dx == 0.0:
            if not bmin <= x0 <= bmax:
                return False
            continue
        a, b = sorted(((bmin - x0) / dx, (bmax - x0) / dx))
        lo, hi = max(lo, a), min(hi, b)
        if lo > hi:
            return False
    return True


def test_the_required_builtins_exist_and_are_usable_by_name(scenarios):
    assert set(scenarios) >= REQUIRED
    for name, sc in scenarios.items():
        assert load_scenario(name).ownship.trajectory.north == pytest.approx(sc.ownship.trajectory.north)


def test_shape_rate_duration_and_fixed_start(scenarios):
    starts = set()
    for sc in scenarios.values():
        assert [(v.name, v.role, v.model) for v in sc.vessels] == [
            ("Havfruen", Role.TARGET, "havfruen"),
            ("Finn", Role.TARGET, "finn"),
            ("milliAmpere", Role.OWNSHIP, "milliampere"),
        ]
        assert 40.0 <= sc.duration <= 90.0
        for v in sc.vessels:
            assert v.trajectory.rate_hz == pytest.approx(10.0, rel=1e-4)
            assert v.trajectory.start == sc.start and v.dimensions is not None
        assert sc.start == float(int(sc.start))  # a whole POSIX second, the same every run
        assert sc.environment == {"harbour": "default", "water": "flat"}
        starts.add(sc.start)
    assert len(starts) == len(scenarios)


def test_deterministic():
    a, b = builtin_scenario("evasive_halted_ferry"), builtin_scenario("evasive_halted_ferry")
    for va, vb in zip(a.vessels, b.vessels):
        assert np.array_equal(va.trajectory.north, vb.trajectory.north)
        assert np.array_equal(va.trajectory.heading, vb.trajectory.heading)


@pytest.mark.slow
def test_every_hull_stays_on_water_clear_of_moored_boats(scenarios):
    for name, sc in scenarios.items():
        _, states = _states(sc)
        for v in sc.vessels:
            s, d = states[v.name], v.dimensions
            fwd = np.stack([np.cos(s.heading), np.sin(s.heading)])
            stb = np.stack([-np.sin(s.heading), np.cos(s.heading)])
            for a in (-0.5, 0.0, 0.5):
                for b in (-0.5, 0.0, 0.5):
                    n = s.north + a * d.length * fwd[0] + b * d.beam * stb[0]
                    e = s.east + a * d.length * fwd[1] + b * d.beam * stb[1]
                    dry = [i for i in range(len(n)) if not DEFAULT_LAYOUT.is_water(n[i], e[i])]
                    assert not dry, f"{name}: {v.name} on land at sample {dry[0]} ({n[dry[0]]:.1f}, {e[dry[0]]:.1f})"
            for boat in DEFAULT_LAYOUT.moored_boats:
                gap = np.hypot(s.north - boat.north, s.east - boat.east).min() - (boat.length + d.length) / 2
                assert gap > 5.0, f"{name}: {v.name} within {gap:.1f} m of {boat.name}"


def test_speeds_are_plausible(scenarios):
    for name, sc in scenarios.items():
        _, states = _states(sc)
        own = states["milliAmpere"].speed
        assert own.max() <= 2.0 + 1e-6 and own.max() >= 0.8, name
        for target in ("Havfruen", "Finn"):
            sp = states[target].speed
            underway = sp[sp > 0.5]  # Finn stops for the ferry in stop_and_evade
            assert 2.0 <= sp.max() <= 5.0 and 2.0 <= np.mean(underway) <= 5.0, (name, target)


def test_motion_is_smooth_and_headings_follow_it(scenarios):
    for name, sc in scenarios.items():
        t, states = _states(sc)
        for v in sc.vessels:
            s = states[v.name]
            moving = s.speed > 0.3
            course = np.arctan2(s.v_east, s.v_north)
            assert _angle_diff_deg(course[moving], s.heading[moving]).max() < 3.0, (name, v.name)
            assert np.degrees(np.abs(s.yaw_rate)).max() < 12.0, (name, v.name)
            accel = np.hypot(np.gradient(s.v_north, t), np.gradient(s.v_east, t))
            assert accel.max() < 1.0, (name, v.name)
            # No jumps: steps between samples within what the top speed allows.
            assert np.hypot(np.diff(s.north), np.diff(s.east)).max() < 0.1 * 5.0 + 1e-9


def test_no_collisions(scenarios):
    for name, sc in scenarios.items():
        for i, a in enumerate(sc.vessels):
            for b in sc.vessels[i + 1 :]:
                d, _ = closest_approach(a.trajectory, b.trajectory)
                assert d > 12.0, f"{name}: {a.name} and {b.name} come within {d:.1f} m"


@pytest.mark.parametrize("name", ["targets_in_line", "constant_bearing"])
def test_one_target_hides_the_other_from_the_ownship(scenarios, name):
    _, s = _states(scenarios[name])
    own, h, f = s["milliAmpere"], s["Havfruen"], s["Finn"]
    diff = _angle_diff_deg(_bearing(own, h), _bearing(own, f))
    rng_h = np.hypot(h.north - own.north, h.east - own.east)
    rng_f = np.hypot(f.north - own.north, f.east - own.east)
    in_line = (diff < 2.0) & (np.abs(rng_h - rng_f) > 10.0)
    assert in_line.sum() >= 10 * 20, f"{name}: in line for only {in_line.sum() / 10:.1f} s"


def test_surprise_separation_hides_then_splits(scenarios):
    t, s = _states(scenarios["surprise_separation"])
    own = s["milliAmpere"]
    diff = _angle_diff_deg(_bearing(own, s["Havfruen"]), _bearing(own, s["Finn"]))
    rel = t - t[0]
    assert diff[rel <= 15.0].max() < 2.0
    assert diff[rel >= 55.0].min() > 45.0


def test_finn_stops_for_the_ferry(scenarios):
    t, s = _states(scenarios["stop_and_evade"])
    stopped = s["Finn"].speed < 0.05
    assert stopped.sum() >= 10 * 20
    own_n = s["milliAmpere"].north[stopped]
    assert np.all(s["Finn"].north[stopped] < own_n - 20.0)  # waiting short of the ferry's line
    assert s["Finn"].north[-1] > s["milliAmpere"].north[-1]  # and crossing it after the ferry


def test_constant_bearing_holds_while_the_range_closes(scenarios):
    t, s = _states(scenarios["constant_bearing"])
    own = s["milliAmpere"]
    first = t - t[0] <= 30.0
    for target in ("Havfruen", "Finn"):
        b = _bearing(own, s[target])[first]
        r = np.hypot(s[target].north - own.north, s[target].east - own.east)[first]
        assert _angle_diff_deg(b, b[0]).max() < 0.5
        assert r[-1] < r[0] - 50.0


def test_emerging_target_starts_hidden_behind_the_west_pier(scenarios):
    t, s = _states(scenarios["emerging_target"])
    pier = next(p for p in DEFAULT_LAYOUT.piers if p.name == "west_pier")
    own = s["milliAmpere"]

    def hidden(name: str, k: int) -> bool:
        return _segment_hits_box((own.north[k], own.east[k]), (s[name].north[k], s[name].east[k]), pier)

    assert hidden("Finn", 0), "Finn must be hidden behind the west pier at the start"
    assert pier.north_max < s["Finn"].north[0] and pier.east_min <= s["Finn"].east[0] <= pier.east_max
    visible_from = next(k for k in range(len(t)) if not hidden("Finn", k))
    assert 3.0 <= t[visible_from] - t[0] <= 30.0
    assert not any(hidden("Finn", k) for k in range(visible_from, len(t)))
    assert not any(hidden("Havfruen", k) for k in range(len(t)))
    # Havfruen holds its course throughout.
    assert np.ptp(s["Havfruen"].heading) < 1e-9
