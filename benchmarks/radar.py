"""Radar model speed: one rotation in the default harbour (ferry_crossing).

Baseline measured in the same process: the same fan cast through a caster rebuilt from the scene's
posed world-frame meshes every scan (what a naive implementation does) instead of the SceneCaster
(static caster built once, vessels cast in their body frames with bounding-sphere culling).
``full_scan_s``: a whole scan (cast, echoes, plots) as the simulation loop runs it
(:class:`seatwin.sim.radar.RadarSensor` in :func:`seatwin.sim.loop.frames`). Prints JSON on the last line.
"""

from __future__ import annotations

import json
import time

import numpy as np


def main() -> None:
    from seatwin.engine import make_caster
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sensors.radar import RadarConfig, RadarModel
    from seatwin.sensors.radar.geometry import fan_directions
    from seatwin.sensors.radar.world import SceneCaster, antenna_pose
    from seatwin.sim.loop import frames
    from seatwin.sim.radar import RadarSensor
    from seatwin.world.scene import Scene

    sc = builtin_scenario("ferry_crossing")
    scene = Scene.from_scenario(sc)
    own = sc.ownship.name
    cfg = RadarConfig()
    model = RadarModel(cfg, seed=0)
    times = sc.start + 2.5 * np.arange(20)
    d, _ = fan_directions(cfg, 0.0)

    t0 = time.perf_counter()
    for t in times:
        ant = antenna_pose(model, scene, own, float(t))
        o = np.broadcast_to(np.array([ant.north, ant.east, -ant.height], np.float32), d.shape)
        make_caster(scene.posed_meshes(float(t), exclude=[own])).cast(o, d, cfg.max_range_m)
    rebuild = (time.perf_counter() - t0) / len(times)

    t0 = time.perf_counter()
    for t in times:
        ant = antenna_pose(model, scene, own, float(t))
        o = np.broadcast_to(np.array([ant.north, ant.east, -ant.height], np.float32), d.shape)
        SceneCaster(scene, float(t), (own,)).cast(o, d, cfg.max_range_m)
    scene_cast = (time.perf_counter() - t0) / len(times)

    sensor = RadarSensor(model, scene, own, times=times)  # full scans through the simulation loop
    t0 = time.perf_counter()
    plots = sum(len(scan) for *_, scan in frames([sensor], float(times[0]), float(times[-1]) + 1.0))
    full = (time.perf_counter() - t0) / len(times)
    print(
        json.dumps(
            {
                "rays_per_scan": int(len(d)),
                "cast_rebuild_s": rebuild,
                "cast_scene_caster_s": scene_cast,
                "speedup": rebuild / scene_cast,
                "full_scan_s": full,
                "plots_per_scan": plots / len(times),
            }
        )
    )


if __name__ == "__main__":
    main()
