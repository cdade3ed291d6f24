"""Fit the radar model to a real recording: the use-case behind ``seatwin radar fit``.

Real plots with the targets' truth come from joyride.mat (truth inside, target area from the
replica's geometry) or from a recording with a radar topic (truth from a scenario or recording).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from seatwin.errors import InputError

if TYPE_CHECKING:
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.sensors.radar.fit import RadarFit, RadarObservations


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
        from seatwin.pipeline.track import vessel_truth
        from seatwin.recording import open_bag

        with open_bag(recording) as rec:
            scans = list(scans_from_recording(rec, ("radar",), truth=vessel_truth(rec)).scans)
        if not scans:
            raise InputError(recording, "no radar scans in the recording")
        ts = load_truth(truth if truth else recording)
        times = np.array([s.time for s in scans])
        states = ts.states_at(times)  # (J, n, 4)
        obs = RadarObservations(
            times,
            [s.positions() for s in scans],
            np.array([s.sensor_position for s in scans]),
            np.transpose(states[:, :, [0, 2]], (1, 0, 2)),
            base.detection.area_ref_m2,
            str(recording),
        )
    if first_half:
        obs = obs.subset(np.arange(len(obs) // 2))
    return obs


def fit_radar_to_recording(
    recording: str | Path,
    *,
    truth: str | None = None,
    base: str | Path | None = None,
    first_half: bool = False,
    gate: float = 60.0,
    boot: int = 200,
    clutter: str = "uniform",
    seed: int = 0,
) -> tuple[RadarFit, RadarObservations]:
    """Fit the radar model (starting from ``base`` or the built-in one) to a real recording's statistics."""
    from seatwin.sensors.radar.config import RadarConfig, load_radar_config
    from seatwin.sensors.radar.fit import fit_radar

    recording = Path(recording)
    if not recording.exists():
        raise InputError(recording, "no such file or directory")
    cfg = load_radar_config(base) if base else RadarConfig()
    obs = radar_observations(recording, truth, cfg, first_half)
    return fit_radar(obs, cfg, gate_m=gate, n_boot=boot, seed=seed, clutter=clutter), obs
