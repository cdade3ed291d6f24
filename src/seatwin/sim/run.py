"""A scenario → a recorded synthetic dataset: the ownship's rig and ground truth through the loop."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from seatwin.errors import InputError
from seatwin.recording.config import check_format
from seatwin.recording.manifest import MANIFEST_NAME
from seatwin.scenario import Scenario
from seatwin.sim.loop import SimulationResult, simulate, time_window
from seatwin.sim.sensors import GroundTruthSensor, LidarSensor

RESOLVED_SCENARIO = "scenario.yaml"


def simulate_scenario(
    scenario: Scenario,
    run_dir: str | Path,
    *,
    start: float | None = None,
    duration: float | None = None,
    seed: int | None = None,
    lidar_preset: str = "vlp16",
    lidar_mode: str = "raycast",
    ray_drop: float | None = None,
    range_noise: float | None = None,
    dissipation: bool = False,
    mount_yaw_bias_deg: float = 0.0,
    fmt: str = "mcap",
    ground_truth_rate_hz: float = 10.0,
    progress: bool = True,
) -> SimulationResult:
    """Simulate the ownship's lidar (and record every vessel's ground truth) along ``scenario``.

    ``seed`` overrides the scenario's seed; ``ray_drop``/``range_noise`` (σ, m) override the
    preset's; ``dissipation`` switches range-dependent return probability on.
    ``mount_yaw_bias_deg`` simulates the lidar turned by that much more than its nominal mount
    while ``/tf_static`` still records the nominal mount (a miscalibrated extrinsic).
    """
    from seatwin.scenario.load import save_scenario
    from seatwin.sensors.lidar import lidar_for_scenario
    from seatwin.sensors.lidar_config import MILLIAMPERE_LIDAR_MOUNT, RangeDissipation, lidar_preset as preset

    run_dir = Path(run_dir)
    check_format(fmt)
    if scenario.ownship is None:
        raise InputError(scenario.source, "the scenario has no ownship to carry the sensors")
    if (run_dir / MANIFEST_NAME).exists():
        raise InputError(run_dir, "a recording exists here already; choose a new run directory")
    t0, t1 = time_window(scenario.start, scenario.end, start, duration)
    if seed is not None:
        scenario = dataclasses.replace(scenario, seed=int(seed))
    config = preset(lidar_preset)
    if ray_drop is not None:
        if not 0.0 <= ray_drop < 1.0:
            raise InputError("--ray-drop", f"expected a probability in [0, 1), got {ray_drop!r}")
        config = config.with_(drop_probability=float(ray_drop))
    if range_noise is not None:
        if range_noise < 0:
            raise InputError("--range-noise", f"expected a non-negative σ in metres, got {range_noise!r}")
        config = config.with_(range_accuracy=2.0 * float(range_noise))
    if dissipation:
        config = config.with_(dissipation=RangeDissipation())
    if not np.isfinite(mount_yaw_bias_deg):
        raise InputError("mount_yaw_bias_deg", f"expected a finite angle in degrees, got {mount_yaw_bias_deg!r}")
    mount = dataclasses.replace(MILLIAMPERE_LIDAR_MOUNT, yaw_deg=MILLIAMPERE_LIDAR_MOUNT.yaw_deg + float(mount_yaw_bias_deg))
    lidar = lidar_for_scenario(scenario, config=config, mount=mount, range_model=lidar_mode)
    run_dir.mkdir(parents=True, exist_ok=True)
    yaml_path, _ = save_scenario(scenario, run_dir / RESOLVED_SCENARIO)
    sensors = [GroundTruthSensor(scenario, ground_truth_rate_hz), LidarSensor(lidar, recorded_mount=MILLIAMPERE_LIDAR_MOUNT)]
    return simulate(
        sensors,
        run_dir,
        t0,
        t1,
        fmt=fmt,
        progress=progress,
        writer_kwargs={
            "origin": scenario.origin,
            "seed": scenario.seed,
            "scenario_file": yaml_path,
            "metadata": {"scenario": scenario.name, "start": t0, "end": t1},
        },
    )
