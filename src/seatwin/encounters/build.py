"""An encounter → a normal scenario (ownship and targets on their paths without avoidance), and saved as a file.

The saved scenario is what ``seatwin simulate`` replays open loop; the closed loop reads the same file: the
ownship starts where its path starts, at its speed, and its goal is where the path ends.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

from seatwin.encounters.place import Placement, place
from seatwin.encounters.space import Encounter
from seatwin.scenario import Role, Scenario, Trajectory, Vessel
from seatwin.scenario.defaults import NOMINAL_DIMENSIONS, OWNSHIP_MODEL, OWNSHIP_NAME, RAVNKLOA
from seatwin.scenario.load import save_scenario

START_TIME = 1600171200.0
"""POSIX start of generated encounters (2020-09-15 12:00 UTC, the built-in scenarios' day)."""
TARGET_MODEL = "havfruen"
"""The 3-D model (and size) of generated targets: an 8 m cabin cruiser."""


def describe(encounter: Encounter) -> str:
    """One line a person reads: each target's kind, CPA, TCPA, relative course and speed."""
    parts = [
        f"{k.value} cpa {t.cpa:+.1f} m tcpa {t.tcpa:.0f} s course {math.degrees(t.relative_course):+.0f}° {t.speed:.1f} m/s"
        for k, t in zip(encounter.kinds, encounter.targets)
    ]
    return f"ownship {encounter.own_speed:.2f} m/s; " + "; ".join(parts)


def encounter_scenario(
    encounter: Encounter, name: str, harbour: str = "none", seed: int = 0, start_time: float = START_TIME
) -> tuple[Scenario, Placement]:
    """``encounter`` as a scenario in ``harbour``, placed by ``seed`` (:func:`~seatwin.encounters.place.place`);
    the scenario's seed (its sensors' draws) is ``seed`` too."""
    placement, p = place(encounter, harbour, seed, start_time)
    src = f"encounter {name}"

    def traj(path: object, who: str) -> Trajectory:
        return Trajectory(path.time, path.north, path.east, path.heading, source=f"{src}: {who}")  # type: ignore[attr-defined]

    vessels = [
        Vessel(f"target_{i}", Role.TARGET, traj(t, f"target_{i}"), TARGET_MODEL, NOMINAL_DIMENSIONS[TARGET_MODEL])
        for i, t in enumerate(p.targets, start=1)
    ]
    vessels.append(
        Vessel(OWNSHIP_NAME, Role.OWNSHIP, traj(p.ownship, OWNSHIP_NAME), OWNSHIP_MODEL, NOMINAL_DIMENSIONS[OWNSHIP_MODEL])
    )
    scenario = Scenario(
        name,
        vessels,
        origin=RAVNKLOA,
        seed=seed,
        environment={"harbour": harbour, "water": "flat"},
        source=src,
        description=describe(encounter),
    )
    return scenario, placement


def save_encounter(
    encounter: Encounter, path: str | os.PathLike[str], harbour: str = "none", seed: int = 0
) -> tuple[Scenario, Path]:
    """Write ``encounter`` as scenario ``path`` (.yaml, with its CSV) and its parameters beside it
    (``NAME.encounter.json``: the geometry, the placement, the seed); returns the scenario and the YAML path."""
    path = Path(path)
    scenario, placement = encounter_scenario(encounter, path.stem, harbour, seed)
    yaml_path, _ = save_scenario(scenario, path)
    record = {
        "parameters": encounter.parameters(),
        "situations": [k.value for k in encounter.situations],
        "run_out": encounter.run_out,
        "placement": {
            "north": placement.north,
            "east": placement.east,
            "course_deg": math.degrees(placement.course),
            "rejected_draws": placement.rejected,
        },
        "harbour": harbour,
        "seed": seed,
    }
    path.with_suffix(".encounter.json").write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
    return scenario, yaml_path
