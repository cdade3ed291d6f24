"""Scenario summary and closest approach."""

from __future__ import annotations

import json

import numpy as np
import pytest

from seatwin.scenario import builtin_scenario, closest_approach, scenario_summary
from seatwin.scenario.model import Role, Scenario, Trajectory, Vessel


def test_closest_approach_between_samples_is_exact():
    a = Trajectory([0.0, 1.0], [-10.0, 10.0], [0.0, 0.0], [0.0, 0.0])
    b = Trajectory([0.0, 0.3, 1.0], [0.5, 0.5, 0.5], [3.0, 3.0, 3.0], [0.0, 0.0, 0.0])
    d, t = closest_approach(a, b)
    assert d == pytest.approx(3.0) and t == pytest.approx(0.525)
    # Limited to a window that ends before the pass: the closest is at the window's end.
    d, t = closest_approach(a, b, 0.0, 0.3)
    assert t == pytest.approx(0.3) and d == pytest.approx(np.hypot(-4.0 - 0.5, 3.0))


def test_summary_of_a_simple_scenario():
    t = np.arange(0.0, 10.01, 0.5)
    own = Trajectory(t, np.zeros_like(t), 1.5 * t, np.full_like(t, np.pi / 2))
    tgt = Trajectory(t, 30.0 - 3.0 * t, np.full_like(t, 7.5), np.full_like(t, np.pi))
    sc = Scenario("simple", [Vessel("own", Role.OWNSHIP, own, "milliampere"), Vessel("tgt", Role.TARGET, tgt)])
    s = scenario_summary(sc)
    json.dumps(s)  # JSON-ready
    assert s["duration_s"] == 10.0 and s["rate_hz"] == 2.0
    own_s, tgt_s = s["vessels"]
    assert own_s["speed_mps"] == pytest.approx({"min": 1.5, "mean": 1.5, "max": 1.5})
    assert tgt_s["speed_mps"]["mean"] == pytest.approx(3.0) and tgt_s["distance_m"] == pytest.approx(30.0)
    (pair,) = s["closest_approach"]
    # Relative position r(t) = (30 − 3t, 7.5 − 1.5t); r·ṙ = 0 at t = (90 + 11.25)/(9 + 2.25) = 9 s, r(9) = (3, −6).
    assert pair["a"] == "own" and pair["b"] == "tgt"
    assert pair["time_from_start_s"] == pytest.approx(9.0)
    assert pair["distance_m"] == pytest.approx(np.hypot(3.0, -6.0))


def test_summary_of_a_builtin_lists_every_pair():
    s = scenario_summary(builtin_scenario("ferry_crossing"))
    assert s["start_utc"] == "2020-09-15T12:00:00.000+00:00" and s["rate_hz"] == 10.0
    assert [(p["a"], p["b"]) for p in s["closest_approach"]] == [
        ("Havfruen", "Finn"),
        ("Havfruen", "milliAmpere"),
        ("Finn", "milliAmpere"),
    ]
    assert s["vessels"][2]["speed_mps"]["max"] == pytest.approx(1.8, abs=1e-3)
