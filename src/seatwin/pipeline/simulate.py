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
    start_offset: float | None = None,
    duration: float | None = None,
    date: dt.date | None = None,
    progress: bool | Callable[[float, float], None] = True,
    on_frame: Callable[[Any, float, int, Any], None] | None = None,
    on_write: Callable[[str, str, int, bytes | memoryview], None] | None = None,
    overwrite: bool = False,
    **changes: Any,
) -> SimulationResult:
    """Simulate ``scenario`` (built-in name, .yaml, Gemini .csv — ``date`` for TimeOfDay CSVs — or a
    :class:`Scenario`) into the new run directory ``out`` from POSIX ``start`` or ``start_offset`` seconds after the
    scenario's start (default: its start); ``changes`` override ``settings`` fields (without ``settings``, the
    sensors are :data:`seatwin.defaults.DEFAULT_SENSORS` unless ``sensors`` is given); ``on_frame(sensor, t,
    frame, data)`` sees every frame (``--stream``), ``on_write(topic, type, log time ns, bytes)`` every message
    recorded (a live view: :class:`~seatwin.recording.live.LiveServer`). ``out`` must be new or empty; ``overwrite`` replaces an
    earlier run there (never an input, never a file seatwin did not write)."""
    from seatwin.recording.manifest import check_new_run
    from seatwin.scenario import Scenario
    from seatwin.scenario.load import load_scenario
    from seatwin.sim import simulate_scenario
    from seatwin.sim.run import run_inputs
    from seatwin.sim.settings import SimulationSettings

    if start is not None and start_offset is not None:
        from seatwin.errors import ParameterError

        raise ParameterError("start_offset", "give a start time or an offset after the scenario's start, not both")
    sc = scenario if isinstance(scenario, Scenario) else load_scenario(str(scenario), date=date)
    chosen = SimulationSettings.model_construct(**{**(settings or SimulationSettings()).model_dump(), **changes})
    inputs = [*([] if isinstance(scenario, Scenario) else [scenario]), *run_inputs(sc, chosen)]
    check_new_run(out, "out", inputs=inputs, overwrite=overwrite)  # the same check as simulate_scenario's, naming ``out``
    if start_offset is not None:
        span = sc.end - sc.start
        if not 0 <= float(start_offset) < span:
            from seatwin.errors import ParameterError

            raise ParameterError(
                "start_offset", f"{float(start_offset):g} s is outside the scenario: expected 0 to {span:g} s after its start"
            )
        start = sc.start + float(start_offset)
    return simulate_scenario(
        sc,
        out,
        settings,
        start=start,
        duration=duration,
        progress=progress,
        on_frame=on_frame,
        on_write=on_write,
        overwrite=overwrite,
        **changes,
    )
