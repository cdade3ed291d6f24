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


def simulated_scenario(run_dir: str | Path) -> Scenario:
    """The scenario a run recorded, cut to its recorded window and in the harbour it was simulated in (its
    manifest's ``metadata``: ``start``, ``end``, ``harbour``); an :class:`~seatwin.errors.InputError` for a folder
    that is not a seatwin run."""
    import dataclasses

    from seatwin.errors import InputError
    from seatwin.recording.manifest import read_manifest
    from seatwin.scenario.load import load_scenario

    run = Path(run_dir)
    manifest = read_manifest(run)
    meta = (manifest or {}).get("metadata") or {}
    if not manifest or "start" not in meta or "end" not in meta or not manifest.get("scenario"):
        raise InputError(run, "not a seatwin simulate run (no manifest.json with the scenario and its recorded window)")
    sc = load_scenario(run / str(manifest["scenario"]))
    t0, t1 = float(meta["start"]), float(meta["end"])
    vessels = [dataclasses.replace(v, trajectory=v.trajectory.sliced(t0, t1)) for v in sc.vessels]
    harbour = meta.get("harbour", sc.environment.get("harbour", "default"))
    return dataclasses.replace(sc, vessels=vessels, environment={**sc.environment, "harbour": harbour})


def vessels_on_water(scenario: Scenario) -> dict[str, float] | None:
    """Each vessel's share of samples on its harbour's water (None for open water, or a raster that cannot be found)."""
    from seatwin.scenario.summary import scenario_harbour_map, water_fraction

    harbour = scenario_harbour_map(scenario)
    if harbour is None:
        return None
    return {v.name: water_fraction(v.trajectory.north, v.trajectory.east, harbour) for v in scenario.vessels}


def check_simulation_figure(
    figure: str | Path, run_dir: str | Path, inputs: list[str | Path | None], *, overwrite: bool = False
) -> None:
    """Refuse, before a run, a ``figure`` path that :func:`plot_simulation` could not write afterwards: inside the run
    folder ``run_dir`` (the folder is the run's), an input, an existing file (unless ``overwrite``)."""
    from seatwin.errors import ParameterError
    from seatwin.outputs import check_output_file

    if Path(figure).resolve().is_relative_to(Path(run_dir).resolve()):
        raise ParameterError("figure", f"{figure} lies inside the run folder {run_dir}; write the figure outside it")
    check_output_file(figure, "figure", inputs=[*inputs, run_dir], overwrite=overwrite)


def plot_simulation(run_dir: str | Path, out: str | Path, *, overwrite: bool = False) -> Path:
    """Draw a run's vessels over the recorded window, over the harbour it was simulated in, into the PNG ``out``
    (:func:`seatwin.scenario.plot.plot_scenario`; an existing file only with ``overwrite``)."""
    from seatwin.outputs import check_output_file
    from seatwin.scenario.plot import plot_scenario

    check_output_file(out, "figure", inputs=[run_dir], overwrite=overwrite)
    return plot_scenario(simulated_scenario(run_dir), out)
