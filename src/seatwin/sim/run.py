"""A scenario → a recorded synthetic dataset: the ownship's sensors and every vessel's ground truth through the loop."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path
from typing import Any

from seatwin.errors import InputError
from seatwin.recording.manifest import RUN_SCENARIO_FILES, check_new_run
from seatwin.scenario import Scenario
from seatwin.settings import validated
from seatwin.sim.loop import SimulationResult, simulate
from seatwin.sim.sensors import GroundTruthSensor, LidarSensor, SimSensor
from seatwin.sim.settings import SimulationSettings
from seatwin.sim.timing import time_window

RESOLVED_SCENARIO = RUN_SCENARIO_FILES[0]


def seeded(scenario: Scenario, settings: SimulationSettings) -> Scenario:
    """``scenario`` with the run's seed (``settings.seed`` when given)."""
    return scenario if settings.seed is None else dataclasses.replace(scenario, seed=int(settings.seed))


def scenario_sensors(scenario: Scenario, settings: SimulationSettings) -> list[SimSensor]:
    """Ground truth and the ownship's sensors of ``settings.sensors``, all in one scene built once.

    Random draws are keyed by :func:`seeded`'s seed. The lidar's ``mount_yaw_bias_deg`` turns the
    simulated mount while /tf_static records the nominal one (a miscalibrated extrinsic).
    """
    from seatwin.sensors.lidar import lidar_for_scenario
    from seatwin.sensors.lidar_config import MILLIAMPERE_LIDAR_MOUNT, RangeDissipation, lidar_preset, load_lidar_config
    from seatwin.world.scene import Scene

    if scenario.ownship is None:
        raise InputError(scenario.source, "the scenario has no ownship to carry the sensors")
    scenario = seeded(scenario, settings)
    scene = Scene.from_scenario(scenario, harbour=settings.harbour)
    sensors: list[SimSensor] = [GroundTruthSensor(scenario, settings.ground_truth_rate_hz)]
    if "lidar" in settings.sensors:
        config = load_lidar_config(settings.lidar_config) if settings.lidar_config else lidar_preset(settings.lidar_preset)
        if settings.ray_drop is not None:
            config = config.with_(drop_probability=float(settings.ray_drop))
        if settings.range_noise is not None:
            config = config.with_(range_accuracy=2.0 * float(settings.range_noise))
        if settings.dissipation and config.dissipation is None:
            config = config.with_(dissipation=RangeDissipation())
        nominal = MILLIAMPERE_LIDAR_MOUNT
        mount = nominal.with_(yaw_deg=nominal.yaw_deg + settings.mount_yaw_bias_deg)
        lidar = lidar_for_scenario(scenario, scene=scene, config=config, mount=mount, range_model=settings.lidar_mode)
        sensors.append(LidarSensor(lidar, recorded_mount=nominal))
    if "radar" in settings.sensors:
        from seatwin.sensors.radar.config import RadarConfig, load_radar_config
        from seatwin.sensors.radar.model import RadarModel
        from seatwin.sim.radar import RadarSensor

        cfg = load_radar_config(settings.radar_config) if settings.radar_config else RadarConfig()
        sensors.append(
            RadarSensor(RadarModel(cfg, seed=scenario.seed), scene, scenario.ownship.name, with_spokes=settings.radar_spokes)
        )
    if "camera" in settings.sensors:
        from seatwin.sensors.camera.config import CameraConfig
        from seatwin.sim.camera import CameraSensor

        cam = CameraConfig(
            hfov_deg=settings.camera_hfov_deg, distortion=settings.camera_distortion, labels=settings.camera_labels
        )
        sensors.append(CameraSensor(cam, scene, scenario.ownship.name))
    return sensors


def run_harbour(scenario: Scenario, settings: SimulationSettings) -> str:
    """The harbour a run simulates in: ``settings.harbour`` (a name, or a raster path relative to the
    current directory) over the scenario's own (a raster named in a scenario file is relative to it);
    a name as its canonical name, a raster as an absolute path."""
    from seatwin.layout import harbour_name

    spec = settings.harbour if settings.harbour is not None else scenario.environment.get("harbour", "default")
    name = harbour_name(spec)
    if name is not None:
        return name
    path = Path(str(spec))
    if not path.is_absolute() and settings.harbour is None:
        path = Path(scenario.source).parent / path  # a raster named in a scenario file is relative to it
    return str(path.resolve())


def water_mask_hint(scenario: Scenario, settings: SimulationSettings) -> str:
    """The water mask ``seatwin track`` should use on this run: the harbour it was simulated in
    (``harbour``: the built-in layout, ``none``, ``ravnkloa`` by name — resolved wherever the run is
    tracked, so the run stays portable — or a raster's absolute path)."""
    from seatwin.layout import harbour_file

    harbour = run_harbour(scenario, settings)
    if harbour in ("default", "none", "ravnkloa"):
        return "harbour" if harbour == "default" else harbour
    return str(harbour_file(harbour).resolve())  # type: ignore[union-attr]


def run_inputs(scenario: Scenario, settings: SimulationSettings) -> list[str]:
    """The files a simulation of ``scenario`` reads (scenario, trajectories, radar and lidar configurations, harbour raster),
    which its outputs must never replace."""
    harbour = settings.harbour if settings.harbour is not None else scenario.environment.get("harbour")
    return [*scenario.files, *(str(p) for p in (settings.radar_config, settings.lidar_config, harbour) if p is not None)]


def simulate_scenario(
    scenario: Scenario,
    run_dir: str | Path,
    settings: SimulationSettings | None = None,
    *,
    start: float | None = None,
    duration: float | None = None,
    progress: bool | Callable[[float, float], None] = True,
    on_frame: Callable[[SimSensor, float, int, Any], None] | None = None,
    on_write: Callable[[str, str, int, bytes | memoryview], None] | None = None,
    overwrite: bool = False,
    **changes: Any,
) -> SimulationResult:
    """Simulate the ownship's sensors along ``scenario`` into a new recording in ``run_dir``.

    ``settings`` (default :class:`SimulationSettings`), with ``changes`` to its fields
    (``lidar_mode="depthbuffer"``, ``ray_drop=0.5``…); ``start`` POSIX seconds (default: the
    scenario's start), ``duration`` seconds (default: to its end); ``on_frame`` as in :func:`simulate`;
    ``on_write`` sees every message recorded (:attr:`~seatwin.recording.RecordingWriter.on_write`: a live view).
    ``run_dir`` must be new or empty; with ``overwrite`` an earlier run there is replaced once everything
    is validated (:func:`~seatwin.recording.manifest.check_new_run`: a user's other files stay).
    """
    from seatwin.outputs import remove_outputs
    from seatwin.scenario.load import save_scenario

    settings = validated(SimulationSettings, {**(settings or SimulationSettings()).model_dump(), **changes})
    run_dir = Path(run_dir)
    stale = check_new_run(run_dir, "run_dir", inputs=run_inputs(scenario, settings), overwrite=overwrite)
    t0, t1 = time_window(scenario.start, scenario.end, start, duration)
    scenario = seeded(scenario, settings)
    sensors = scenario_sensors(scenario, settings)
    harbour = run_harbour(scenario, settings)
    from seatwin.scenario.on_water import warn_on_land

    warn_on_land(scenario, harbour)
    # The run's scenario.yaml names the harbour the run was simulated in.
    scenario = dataclasses.replace(scenario, environment={**scenario.environment, "harbour": harbour})
    remove_outputs(stale)
    try:
        run_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(run_dir, f"cannot create the run directory: {exc.strerror or exc}") from None
    yaml_path, _ = save_scenario(scenario, run_dir / RESOLVED_SCENARIO)
    return simulate(
        sensors,
        run_dir,
        t0,
        t1,
        fmt=settings.fmt,
        progress=progress,
        on_frame=on_frame,
        writer_kwargs={
            "on_write": on_write,
            "ros_distro": settings.ros_distro,
            **settings.writer_options(),
            "origin": scenario.origin,
            "seed": scenario.seed,
            "scenario_file": yaml_path,
            "metadata": {
                "scenario": scenario.name,
                "start": t0,
                "end": t1,
                "settings": settings.model_dump(mode="json"),
                "harbour": harbour,
                "tracking": {"map": water_mask_hint(scenario, settings)},
            },
        },
    )
