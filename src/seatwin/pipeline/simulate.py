"""Simulate a scenario into a recording: the use-case behind ``seatwin simulate``."""

from __future__ import annotations

import datetime as dt
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from seatwin.scenario import Scenario
    from seatwin.sim import SimulationResult, SimulationSettings


def simulate_run(
    scenario: str | Path | Scenario,
    out: str | Path,
    settings: SimulationSettings | None = None,
    *,
    start: float | None = None,
    duration: float | None = None,
    date: dt.date | None = None,
    progress: bool | Callable[[float, float], None] = True,
    **changes: Any,
) -> SimulationResult:
    """Simulate ``scenario`` (built-in name, .yaml, Gemini .csv — ``date`` for TimeOfDay CSVs — or a
    :class:`Scenario`) into the new run directory ``out``; ``changes`` override ``settings`` fields."""
    from seatwin.scenario import Scenario
    from seatwin.scenario.load import load_scenario
    from seatwin.sim import simulate_scenario

    sc = scenario if isinstance(scenario, Scenario) else load_scenario(str(scenario), date=date)
    return simulate_scenario(sc, out, settings, start=start, duration=duration, progress=progress, **changes)
