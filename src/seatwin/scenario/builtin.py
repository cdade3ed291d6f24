"""Built-in scenarios in the default harbour, generated in code after the thesis's scenarios 1–9.

Every built-in has the ownship milliAmpere (a ferry, 1–2 m/s) and the two target boats
Havfruen and Finn (2–5 m/s), sampled at 10 Hz from a fixed POSIX start on the day of the
thesis experiments, in :data:`~seatwin.layout.DEFAULT_LAYOUT` (a north–south channel,
water for |east| < 75 m). Paths are lines and arcs (:mod:`seatwin.scenario.motion`), so
headings are continuous and point along the motion; all vessels stay on water throughout
(``tests/scenario/test_builtin.py`` checks the hull corners against the layout).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from seatwin.errors import InputError
from seatwin.scenario.defaults import NOMINAL_DIMENSIONS, RAVNKLOA
from seatwin.scenario.model import Role, Scenario, Trajectory, Vessel
from seatwin.scenario.motion import Path, SpeedProfile, follow

DAY_START = 1600171200.0
"""2020-09-15 12:00:00 UTC, the first day of the thesis experiments."""


@dataclass(frozen=True)
class BuiltinScenario:
    name: str
    thesis: str
    """The thesis scenario numbers (ch. 3.2.4) it follows."""
    description: str
    build: Callable[[str], Scenario]


def _vessels(ownship: Trajectory, havfruen: Trajectory, finn: Trajectory) -> list[Vessel]:
    """Targets first, ownship last: the Gemini CSV order (V1 Havfruen, V2 Finn, V3 milliAmpere)."""
    return [
        Vessel("Havfruen", Role.TARGET, havfruen, "havfruen", NOMINAL_DIMENSIONS["havfruen"]),
        Vessel("Finn", Role.TARGET, finn, "finn", NOMINAL_DIMENSIONS["finn"]),
        Vessel("milliAmpere", Role.OWNSHIP, ownship, "milliampere", NOMINAL_DIMENSIONS["milliampere"]),
    ]


def _scenario(name: str, vessels: list[Vessel]) -> Scenario:
    return Scenario(name, vessels, origin=RAVNKLOA, seed=0, rig="milliampere", source=f"built-in {name}")


def _crossing_profile(distance: float, speed: float, ramp: float, depart: float = 0.0) -> SpeedProfile:
    """From rest at ``depart``, cruise at ``speed``, stop after exactly ``distance`` m; ``ramp`` s ramps."""
    cruise = (distance - speed * ramp) / speed
    if cruise < 0:
        raise ValueError(f"{distance} m is too short for two {ramp} s ramps at {speed} m/s")
    t1 = depart + ramp
    return SpeedProfile(((depart, 0.0), (t1, speed), (t1 + cruise, speed), (t1 + cruise + ramp, 0.0)))


def _ferry_crossing(name: str) -> Scenario:
    """Thesis 1–2: the ferry crosses west → east at north 0 while the targets transit the channel."""
    start, duration = DAY_START, 75.0
    own_path = Path(0.0, -59.0, np.radians(90)).line(118.0)
    own = follow(own_path, _crossing_profile(118.0, 1.8, 8.0), start, duration, source=f"{name}: milliAmpere")
    # Havfruen southbound on the east side passes ahead of the ferry; Finn northbound on the
    # west side passes astern of it, 12 m clear of the west pier's tip.
    havfruen_path = Path(122.5, 22.0, np.radians(180)).line(300.0)
    havfruen = follow(havfruen_path, SpeedProfile.constant(3.5), start, duration, source=f"{name}: Havfruen")
    finn_path = Path(-135.0, -18.0, 0.0).line(300.0)
    finn = follow(finn_path, SpeedProfile.constant(3.0), start, duration, source=f"{name}: Finn")
    return _scenario(name, _vessels(own, havfruen, finn))


def _evasive_halted_ferry(name: str) -> Scenario:
    """Thesis 3–4: the ferry halts mid-channel; both targets come from the south and swerve round it."""
    start, duration = DAY_START + 600.0, 80.0
    # Underway at 1.2 m/s, stops 35 m on at east −10 (after 35.2 s) and holds there.
    own_path = Path(-80.0, -45.0, np.radians(90)).line(40.0)
    own_profile = SpeedProfile(((0.0, 1.2), (23.2, 1.2), (35.2, 0.0)))
    own = follow(own_path, own_profile, start, duration, source=f"{name}: milliAmpere")
    # Havfruen heads straight for the ferry, jogs 24 m to starboard (east), passes, jogs back.
    havfruen_path = Path(-235.0, -8.0, 0.0).line(85.0).jog(24.0, 25.0, 35.0).line(70.0).jog(-24.0, 25.0, 35.0).line(200.0)
    havfruen = follow(havfruen_path, SpeedProfile.constant(3.2), start, duration, source=f"{name}: Havfruen")
    # Finn follows and passes the ferry on its west side.
    finn_path = Path(-262.0, -12.0, 0.0).line(100.0).jog(-20.0, 20.0, 35.0).line(65.0).jog(20.0, 20.0, 35.0).line(200.0)
    finn = follow(finn_path, SpeedProfile.constant(3.0), start, duration, source=f"{name}: Finn")
    return _scenario(name, _vessels(own, havfruen, finn))


def _stop_and_evade(name: str) -> Scenario:
    """Thesis 5: Finn stops to let the crossing ferry pass; Havfruen swerves astern of it."""
    start, duration = DAY_START + 900.0, 80.0
    own_path = Path(0.0, -58.0, np.radians(90)).line(120.0)
    own = follow(own_path, SpeedProfile(((0.0, 0.0), (8.0, 1.5))), start, duration, source=f"{name}: milliAmpere")
    # Finn, northbound on the east side, stops 25 m short of the ferry's line and waits for it.
    finn_profile = SpeedProfile(((0.0, 3.0), (24.0, 3.0), (30.0, 0.0), (60.0, 0.0), (66.0, 3.0)))
    finn = follow(Path(-106.0, 20.0, 0.0).line(200.0), finn_profile, start, duration, source=f"{name}: Finn")
    # Havfruen, southbound on the west side, jogs 25 m to starboard (west) to pass astern of the
    # ferry, past the west pier's tip first, then jogs back.
    havfruen_path = (
        Path(140.0, -10.0, np.radians(180)).line(105.0).jog(25.0, 20.0, 35.0).line(20.0).jog(-25.0, 20.0, 35.0).line(100.0)
    )
    havfruen = follow(havfruen_path, SpeedProfile.constant(3.2), start, duration, source=f"{name}: Havfruen")
    return _scenario(name, _vessels(own, havfruen, finn))


def _targets_in_line(name: str) -> Scenario:
    """Thesis 6: the targets approach in line (column) almost straight at the waiting ferry."""
    start, duration = DAY_START + 1200.0, 75.0
    # The ferry waits at the east quay, then moves slowly north along it.
    own_path = Path(-20.0, 55.0, 0.0).line(60.0)
    own = follow(own_path, SpeedProfile(((40.0, 0.0), (48.0, 0.8))), start, duration, source=f"{name}: milliAmpere")
    # The column's line aims 10 m west of the ferry from the south-southwest (bearing 200°);
    # Finn follows Havfruen 20 m behind on the same path.
    aim_n, aim_e, bearing = -20.0, 45.0, np.radians(200.0)
    leader_range, spacing = 190.0, 20.0
    back = leader_range + spacing
    path = (
        Path(aim_n + back * np.cos(bearing), aim_e + back * np.sin(bearing), bearing - np.pi)
        .line(spacing + 120.0)
        .turn_to(350.0, 30.0)
        .line(200.0)
    )
    speed = SpeedProfile.constant(3.0)
    havfruen = follow(path, speed, start, duration, offset=spacing, source=f"{name}: Havfruen")
    finn = follow(path, speed, start, duration, source=f"{name}: Finn")
    return _scenario(name, _vessels(own, havfruen, finn))


def _surprise_separation(name: str) -> Scenario:
    """Thesis 7: the targets come in line, one hiding the other, then suddenly split apart."""
    start, duration = DAY_START + 2100.0, 70.0
    # The ferry waits at the east quay, then sets off west behind the passing targets.
    own_path = Path(-40.0, 58.0, np.radians(270)).line(60.0)
    own = follow(own_path, SpeedProfile(((45.0, 0.0), (53.0, 1.2))), start, duration, source=f"{name}: milliAmpere")
    # The column comes from the north-northwest on a line 20 m west of the ferry (bearing 350°).
    aim_n, aim_e, bearing = -40.0, 38.0, np.radians(350.0)
    leader_range, spacing, speed = 160.0, 15.0, SpeedProfile.constant(3.5)
    back = leader_range + spacing
    n0, e0, heading = aim_n + back * np.cos(bearing), aim_e + back * np.sin(bearing), bearing - np.pi
    # Finn, behind, holds the line past the ferry; Havfruen, ahead, breaks off hard to starboard
    # 55 m before the aim point and crosses to the west side.
    finn_path = Path(n0, e0, heading).line(back + 10.0).turn_to(180.0, 30.0).line(200.0)
    finn = follow(finn_path, speed, start, duration, source=f"{name}: Finn")
    havfruen_path = (
        Path(n0, e0, heading).line(spacing + leader_range - 55.0).turn_to(255.0, 18.0).line(45.0).turn_to(185.0, 20.0).line(200.0)
    )
    havfruen = follow(havfruen_path, speed, start, duration, offset=spacing, source=f"{name}: Havfruen")
    return _scenario(name, _vessels(own, havfruen, finn))


def _constant_bearing(name: str) -> Scenario:
    """Thesis 8: both targets hold a constant bearing from the crossing ferry, one behind the other."""
    start, duration = DAY_START + 1800.0, 70.0
    own_speed, closing, hold = 1.5, 2.2, 32.0
    own_path = Path(0.0, -55.0, np.radians(90)).line(100.0)
    own_profile = SpeedProfile(((0.0, own_speed), (55.0, own_speed), (65.0, 0.0)))
    own = follow(own_path, own_profile, start, duration, source=f"{name}: milliAmpere")
    # On the line of bearing 25° from the ferry: range falls at `closing` m/s, so each target's
    # velocity is the ferry's plus −closing along the bearing — constant, a straight line.
    # After `hold` s both turn to starboard together and pass astern of the ferry.
    u = np.array([np.cos(np.radians(25.0)), np.sin(np.radians(25.0))])
    velocity = np.array([0.0, own_speed]) - closing * u
    speed, heading = float(np.hypot(*velocity)), float(np.arctan2(velocity[1], velocity[0]))
    targets = []
    for label, r0 in (("Havfruen", 110.0), ("Finn", 128.0)):
        n0, e0 = np.array([0.0, -55.0]) + r0 * u
        path = Path(n0, e0, heading).line(speed * hold).turn_to(235.0, 20.0).line(15.0).turn_to(185.0, 25.0).line(200.0)
        targets.append(follow(path, SpeedProfile.constant(speed), start, duration, source=f"{name}: {label}"))
    return _scenario(name, _vessels(own, *targets))


def _emerging_target(name: str) -> Scenario:
    """Thesis 9: Finn emerges from behind the west pier; Havfruen holds course on the east side."""
    start, duration = DAY_START + 2400.0, 70.0
    own_path = Path(-5.0, -58.0, np.radians(90)).line(110.0)
    own = follow(own_path, SpeedProfile(((0.0, 0.0), (8.0, 1.5))), start, duration, source=f"{name}: milliAmpere")
    # Finn lies north of the west pier (north 40–52, east −75…−30), out of the ferry's sight,
    # runs east past the pier's tip, then turns north up the channel.
    finn_path = Path(64.0, -64.0, np.radians(90)).line(30.0).turn_to(0.0, 18.0).line(200.0)
    finn = follow(finn_path, SpeedProfile(((0.0, 0.5), (6.0, 3.0))), start, duration, source=f"{name}: Finn")
    havfruen_path = Path(115.0, 35.0, np.radians(180)).line(240.0)
    havfruen = follow(havfruen_path, SpeedProfile.constant(3.2), start, duration, source=f"{name}: Havfruen")
    return _scenario(name, _vessels(own, havfruen, finn))


BUILTINS: dict[str, BuiltinScenario] = {
    b.name: b
    for b in (
        BuiltinScenario(
            "ferry_crossing", "1–2", "the ferry crosses the channel west → east while the targets transit", _ferry_crossing
        ),
        BuiltinScenario(
            "evasive_halted_ferry", "3–4", "the ferry halts mid-channel; the targets swerve round it", _evasive_halted_ferry
        ),
        BuiltinScenario(
            "stop_and_evade", "5", "Finn stops for the crossing ferry; Havfruen swerves astern of it", _stop_and_evade
        ),
        BuiltinScenario(
            "targets_in_line", "6", "the targets approach in line, one hiding the other from the ferry", _targets_in_line
        ),
        BuiltinScenario(
            "surprise_separation", "7", "the targets come in line, one hiding the other, then split", _surprise_separation
        ),
        BuiltinScenario(
            "constant_bearing", "8", "both targets at one constant bearing from the crossing ferry", _constant_bearing
        ),
        BuiltinScenario(
            "emerging_target", "9", "a target emerges from behind the west pier; the other holds course", _emerging_target
        ),
    )
}


def builtin_names() -> list[str]:
    return list(BUILTINS)


def builtin_scenario(name: str) -> Scenario:
    """Generate the built-in scenario ``name`` (deterministic; a fresh object each call)."""
    try:
        entry = BUILTINS[name]
    except KeyError:
        raise InputError("scenario", f"no built-in scenario {name!r}; built-ins are: {', '.join(BUILTINS)}") from None
    scenario = entry.build(name)
    scenario.description = f"{entry.description} (after thesis scenario {entry.thesis})"
    return scenario
