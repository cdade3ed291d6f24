"""Scenarios: vessels, their trajectories, readers and writers, and the built-in scenarios.

The public names are imported lazily (the YAML reader pulls in pydantic), so importing
``seatwin.scenario`` or its model stays cheap.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

_EXPORTS = {
    "Dimensions": "model",
    "Role": "model",
    "Scenario": "model",
    "Trajectory": "model",
    "Vessel": "model",
    "VesselState": "model",
    "BUILTINS": "builtin",
    "builtin_names": "builtin",
    "builtin_scenario": "builtin",
    "load_scenario": "load",
    "save_scenario": "load",
    "scenario_from_gemini_csv": "load",
    "closest_approach": "summary",
    "scenario_summary": "summary",
}

__all__ = sorted(_EXPORTS)

if TYPE_CHECKING:
    from seatwin.scenario.builtin import BUILTINS, builtin_names, builtin_scenario
    from seatwin.scenario.load import load_scenario, save_scenario, scenario_from_gemini_csv
    from seatwin.scenario.model import Dimensions, Role, Scenario, Trajectory, Vessel, VesselState
    from seatwin.scenario.summary import closest_approach, scenario_summary


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(import_module(f"seatwin.scenario.{_EXPORTS[name]}"), name)
    raise AttributeError(f"module 'seatwin.scenario' has no attribute {name!r}")
