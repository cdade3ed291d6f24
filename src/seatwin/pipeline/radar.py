"""Simulate the marine radar along a scenario: plots as CSV, raw spokes as .npz, and/or a recording.

The radar runs in the one simulation loop (:mod:`seatwin.sim`): with a run directory the loop
records it (plots on the radar topic, ground truth, tf) and the exports see each frame as it is
captured; without one the loop's frames are only exported.
"""

from __future__ import annotations

import contextlib
import csv
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from seatwin.errors import InputError, ParameterError
from seatwin.settings import validated

PLOT_COLUMNS = ("time", "north", "east", "range_m", "azimuth_rad", "kind", "object_id")


@dataclass
class RadarSimulation:
    """How many rotations and plots were simulated, and where they went."""

    n_scans: int
    n_plots: int
    outputs: list[Path]


def simulate_radar(
    scenario: str | Path,
    *,
    plots_csv: Path | None = None,
    run_dir: Path | None = None,
    spokes_dir: Path | None = None,
    radar_config: str | None = None,
    seed: int | None = None,
    start_offset: float = 0.0,
    duration: float | None = None,
    fmt: str = "mcap",
) -> RadarSimulation:
    """The radar on ``scenario``'s ownship from ``start_offset`` seconds after its start for ``duration`` seconds
    (default: to its end), bit-identical per ``seed``."""
    import numpy as np

    from seatwin.scenario.load import load_scenario
    from seatwin.sensors.radar.plots import KIND_NAMES
    from seatwin.sim import SimulationSettings, frames, scenario_sensors, simulate_scenario
    from seatwin.sim.radar import RadarSensor
    from seatwin.sim.timing import time_window

    if plots_csv is None and run_dir is None and spokes_dir is None:
        raise ParameterError("plots_csv", "nothing to write: give a plots CSV, a run directory and/or a spokes folder")
    sc = load_scenario(str(scenario))
    if sc.ownship is None:
        raise InputError(scenario, "the scenario has no ownship to carry the radar")
    settings = validated(
        SimulationSettings,
        {"sensors": ("radar",), "radar_config": radar_config, "seed": seed, "fmt": fmt, "radar_spokes": spokes_dir is not None},
    )
    t0, t1 = time_window(sc.start, sc.end, sc.start + start_offset, duration)  # checked before anything is written
    counts = {"scans": 0, "plots": 0}
    with contextlib.ExitStack() as stack:
        rows = None
        if plots_csv is not None:
            plots_csv.parent.mkdir(parents=True, exist_ok=True)
            rows = csv.writer(stack.enter_context(plots_csv.open("w", newline="")))
            rows.writerow(PLOT_COLUMNS)
        if spokes_dir is not None:
            spokes_dir.mkdir(parents=True, exist_ok=True)

        def export(sensor: Any, t: float, frame: int, s: Any) -> None:
            if not isinstance(sensor, RadarSensor):
                return
            counts["scans"] += 1
            counts["plots"] += len(s)
            if spokes_dir is not None:
                req = s.spokes.to_request_dict()
                req["radar_spokes"] = s.spokes.intensities
                np.savez_compressed(spokes_dir / f"scan_{frame:06d}.npz", **{key: np.asarray(v) for key, v in req.items()})
            if rows is not None:
                for i in range(len(s)):
                    rows.writerow(
                        [
                            repr(float(t)),
                            f"{s.north[i]:.3f}",
                            f"{s.east[i]:.3f}",
                            f"{s.range_m[i]:.3f}",
                            f"{s.azimuth[i]:.6f}",
                            KIND_NAMES[int(s.kind[i])],
                            int(s.object_id[i]),
                        ]
                    )

        if run_dir is not None:
            simulate_scenario(
                sc, run_dir, settings, start=sc.start + start_offset, duration=duration, progress=False, on_frame=export
            )
        else:
            radar = [s for s in scenario_sensors(sc, settings) if isinstance(s, RadarSensor)]
            for t, i, k, data in frames(radar, t0, t1):
                export(radar[i], t, k, data)
    outputs = [p for p in (plots_csv, run_dir, spokes_dir) if p is not None]
    return RadarSimulation(counts["scans"], counts["plots"], outputs)
