"""One entry point for scenarios: a built-in name, a scenario YAML or a Gemini CSV."""

from __future__ import annotations

import datetime as dt
import os
from pathlib import Path
from typing import Literal

from seatwin.errors import InputError
from seatwin.scenario.builtin import builtin_names, builtin_scenario
from seatwin.scenario.defaults import NOMINAL_DIMENSIONS, OWNSHIP_MODEL, OWNSHIP_NAME, RAVNKLOA, TARGETS_BY_COLUMN
from seatwin.scenario.gemini_csv import MAX_SPEED, read_gemini_csv
from seatwin.scenario.model import Role, Scenario, Vessel
from seatwin.scenario.yaml_format import read_scenario_yaml, write_scenario_yaml

YAML_SUFFIXES = (".yaml", ".yml")
GEMINI_HARBOUR = "ravnkloa"
"""The harbour of a Gemini CSV read on its own: the published scenarios are Ravnkloa trajectories in
the frame of the Ravnkloa land raster (a scenario YAML names its own ``environment.harbour``)."""


def scenario_from_gemini_csv(path: str | os.PathLike[str], date: dt.date | None = None, max_speed: float = MAX_SPEED) -> Scenario:
    """A Gemini CSV as a scenario: the highest-numbered vessel (V3) is the ownship milliAmpere,
    V1 and V2 the targets Havfruen and Finn; any other vessel n is a target ``V{n}`` (model generic).
    Its harbour is :data:`GEMINI_HARBOUR` (the CSV's local NED frame is Ravnkloa's).
    """
    path = Path(path)
    trajectories = read_gemini_csv(path, date=date, max_speed=max_speed)
    own = max(trajectories)
    vessels = []
    for n, traj in trajectories.items():
        if n == own:
            name, role, model = OWNSHIP_NAME, Role.OWNSHIP, OWNSHIP_MODEL
        else:
            name, model = TARGETS_BY_COLUMN.get(n, (f"V{n}", "generic"))
            role = Role.TARGET
        vessels.append(Vessel(name, role, traj, model, NOMINAL_DIMENSIONS.get(model)))
    return Scenario(
        name=path.stem,
        vessels=vessels,
        origin=RAVNKLOA,
        source=str(path),
        environment={"harbour": GEMINI_HARBOUR, "water": "flat"},
    )


def load_scenario(spec: str | os.PathLike[str], date: dt.date | None = None, max_speed: float = MAX_SPEED) -> Scenario:
    """Load a scenario from a built-in name, a ``.yaml``/``.yml`` file or a Gemini ``.csv``.

    ``date`` (UTC) places a CSV with ``TimeOfDay`` times (it overrides a YAML's ``date``).
    ``max_speed`` [m/s]: a vessel moving faster between two rows of the CSV is an error (a teleport).
    An unknown name or a missing file raises :class:`InputError` listing the built-ins.
    """
    text = os.fspath(spec)
    path = Path(text)
    if not path.exists() and text in builtin_names():
        return builtin_scenario(text)
    if not path.exists():
        raise InputError(text, f"no such scenario file or built-in scenario; built-ins are: {', '.join(builtin_names())}")
    if path.is_dir():
        raise InputError(text, "is a directory; expected a scenario .yaml, a Gemini .csv or a built-in name")
    suffix = path.suffix.lower()
    if suffix in YAML_SUFFIXES:
        return read_scenario_yaml(path, date=date, max_speed=max_speed)
    if suffix == ".csv":
        return scenario_from_gemini_csv(path, date=date, max_speed=max_speed)
    raise InputError(text, f"unknown scenario file type {suffix!r}: expected .yaml, .yml or .csv")


def save_scenario(
    scenario: Scenario, path: str | os.PathLike[str], time_format: Literal["posix", "time_of_day"] = "posix"
) -> tuple[Path, Path]:
    """Write ``scenario`` as a YAML (``path``) with its Gemini CSV beside it; return both paths."""
    return write_scenario_yaml(scenario, path, time_format=time_format)
