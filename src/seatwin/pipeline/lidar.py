"""One lidar sweep of a scenario, seen from above: the use-case behind ``seatwin lidar snapshot``."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from seatwin.errors import InputError, ParameterError


@dataclass
class LidarSnapshot:
    """The figure written and the number of points of the sweep."""

    path: Path
    n_points: int


def lidar_snapshot(
    scenario: Any,
    offset: float,
    out: str | Path,
    *,
    preset: str = "vlp16",
    lidar_mode: str = "raycast",
    ray_drop: float | None = None,
    extent: float = 110.0,
    harbour: str | None = None,
    overwrite: bool = False,
) -> LidarSnapshot:
    """The sweep of ``scenario``'s ownship lidar (``preset``, ``lidar_mode``, ``ray_drop``: default the preset's) that
    starts ``offset`` seconds after the scenario's start, plotted from above over its harbour (or ``harbour``) with
    the vessels' outlines, ``extent`` metres around the ownship, into the PNG ``out`` (an existing one only with
    ``overwrite``; checked before the work)."""
    from seatwin.outputs import check_output_file
    from seatwin.scenario import Scenario
    from seatwin.scenario.load import load_scenario
    from seatwin.sensors.lidar import lidar_for_scenario, sweep_to_world
    from seatwin.sensors.lidar_config import lidar_preset
    from seatwin.sensors.plot import plot_sweep_top_view
    from seatwin.world.scene import Scene

    sc = scenario if isinstance(scenario, Scenario) else load_scenario(str(scenario))
    check_output_file(
        out, "out", inputs=[None if isinstance(scenario, Scenario) else scenario, harbour, *sc.files], overwrite=overwrite
    )
    cfg = lidar_preset(preset)
    if ray_drop is not None:
        cfg = cfg.with_(drop_probability=ray_drop)
    if not extent > 0:
        raise ParameterError("extent", f"expected a positive number of metres, got {extent:g}")
    if sc.ownship is None:
        raise InputError(sc.source, "the scenario has no ownship to carry the lidar")
    start = sc.start + offset
    if not (sc.start <= start <= sc.end - cfg.period):
        raise ParameterError(
            "offset", f"{offset:g} s is outside the scenario: a sweep must start within 0 to {sc.duration - cfg.period:.1f} s"
        )
    frame = int(round(offset * cfg.rate_hz))
    scene = Scene.from_scenario(sc, harbour=harbour)
    lidar = lidar_for_scenario(sc, scene, config=cfg, range_model=lidar_mode)
    sweep = lidar.sweep(start, frame)
    world = sweep_to_world(lidar, sweep)
    plot_sweep_top_view(
        lidar.scene,
        sweep,
        world,
        Path(out),
        extent=extent,
        ownship=sc.ownship.name,
        title=f"{sc.name}  t = {offset:.1f} s  ({cfg.name}, {lidar_mode}, {len(sweep)} points)",
    )
    return LidarSnapshot(Path(out), len(sweep))
