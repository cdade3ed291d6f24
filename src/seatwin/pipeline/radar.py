"""The marine radar: fit it to a real recording; simulate it along a scenario (plots CSV, spokes .npz, recording).

The radar runs in the one simulation loop (:mod:`seatwin.sim`): with a run directory the loop
records it (plots on the radar topic, ground truth, tf) and the exports see each frame as it is
captured; without one the loop's frames are only exported.
"""

from __future__ import annotations

import contextlib
import csv
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from seatwin.errors import InputError, ParameterError
from seatwin.settings import validated

if TYPE_CHECKING:
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.sensors.radar.fit import RadarFit, RadarObservations

PLOT_COLUMNS = ("time", "north", "east", "range_m", "azimuth_rad", "kind", "object_id")


def radar_observations(recording: Path, truth: str | None, base: RadarConfig, first_half: bool = False) -> RadarObservations:
    """Real plots with the targets' truth: joyride.mat (truth inside) or a recording with a radar topic (truth
    from ``truth`` — a scenario or recording — or the recording itself); only the first half of the scans if asked."""
    import numpy as np

    from seatwin.sensors.radar.fit import RadarObservations

    if recording.suffix.lower() == ".mat":
        from seatwin.fidelity.joyride import load_joyride, observations

        obs = observations(load_joyride(recording), base)
    else:
        from seatwin.evaluation import load_truth
        from seatwin.perception.from_recording import scans_from_recording
        from seatwin.recording import open_bag

        with open_bag(recording) as rec:
            scans = list(scans_from_recording(rec, ("radar",)).scans)
        if not scans:
            raise InputError(recording, "no radar scans in the recording")
        ts = load_truth(truth if truth else recording)
        times = np.array([s.time for s in scans])
        states = ts.states_at(times)  # (J, n, 4)
        obs = RadarObservations(
            times, [s.positions() for s in scans], np.array([s.sensor_position for s in scans]),
            np.transpose(states[:, :, [0, 2]], (1, 0, 2)), base.detection.area_ref_m2, str(recording),
        )
    if first_half:
        obs = obs.subset(np.arange(len(obs) // 2))
    return obs


def fit_radar_to_recording(recording: str | Path, *, truth: str | None = None, base: str | Path | None = None,
                           first_half: bool = False, gate: float = 60.0, boot: int = 200, clutter: str = "uniform",
                           seed: int = 0) -> tuple[RadarFit, RadarObservations]:
    """Fit the radar model (starting from ``base`` or the built-in one) to a real recording's statistics."""
    from seatwin.sensors.radar.config import RadarConfig, load_radar_config
    from seatwin.sensors.radar.fit import fit_radar

    recording = Path(recording)
    if not recording.exists():
        raise InputError(recording, "no such file or directory")
    cfg = load_radar_config(base) if base else RadarConfig()
    obs = radar_observations(recording, truth, cfg, first_half)
    return fit_radar(obs, cfg, gate_m=gate, n_boot=boot, seed=seed, clutter=clutter), obs


@dataclass
class RadarSimulation:
    """How many rotations and plots were simulated, and where they went."""

    n_scans: int
    n_plots: int
    outputs: list[Path]


def simulate_radar(scenario: str | Path, *, plots_csv: Path | None = None, run_dir: Path | None = None,
                   spokes_dir: Path | None = None, radar_config: str | None = None, seed: int | None = None,
                   duration: float | None = None, fmt: str = "mcap") -> RadarSimulation:
    """The radar on ``scenario``'s ownship for ``duration`` seconds (default: all of it), bit-identical per ``seed``."""
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
    settings = validated(SimulationSettings, {"sensors": ("radar",), "radar_config": radar_config, "seed": seed, "fmt": fmt,
                                              "radar_spokes": spokes_dir is not None})
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
                    rows.writerow([repr(float(t)), f"{s.north[i]:.3f}", f"{s.east[i]:.3f}", f"{s.range_m[i]:.3f}",
                                   f"{s.azimuth[i]:.6f}", KIND_NAMES[int(s.kind[i])], int(s.object_id[i])])

        if run_dir is not None:
            simulate_scenario(sc, run_dir, settings, duration=duration, progress=False, on_frame=export)
        else:
            radar = [s for s in scenario_sensors(sc, settings) if isinstance(s, RadarSensor)]
            t0, t1 = time_window(sc.start, sc.end, None, duration)
            for t, i, k, data in frames(radar, t0, t1):
                export(radar[i], t, k, data)
    outputs = [p for p in (plots_csv, run_dir, spokes_dir) if p is not None]
    return RadarSimulation(counts["scans"], counts["plots"], outputs)
