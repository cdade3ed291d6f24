"""Ravnkloa harbour geometry: world-building time, triangles and lidar sweep cost, flat land vs the shore skyline.

Gemini Scenario6 in the aligned Ravnkloa raster (moored boats included), VLP-16 on milliAmpere, the full
lidar pipeline (default settings). Each of ``--sweeps`` sweeps is timed ``--repeats`` times for both
worlds, interleaved, and the best time per sweep kept (robust to other processes sharing the cores).
Needs ``shared/data`` (``$SEATWIN_DATA``).

    .venv/bin/python benchmarks/harbour.py [--sweeps 40] [--repeats 5]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sweeps", type=int, default=40)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--scenario", default="Scenario6.csv")
    args = ap.parse_args()

    from seatwin.layout import harbour_map
    from seatwin.layout.harbours import find_data_file
    from seatwin.scenario.load import load_scenario
    from seatwin.sensors.lidar import lidar_for_scenario, sweep_starts
    from seatwin.world.harbour import SHORE_SKYLINE, harbour_from_raster
    from seatwin.world.scene import Scene

    sc = load_scenario(find_data_file(f"gemini-scenarios/{args.scenario}", "the Gemini scenario"))
    raster = harbour_map("ravnkloa")
    out: dict[str, dict[str, float]] = {}
    lidars = {}
    for name, skyline in (("flat", None), ("skyline", SHORE_SKYLINE)):
        t0 = time.perf_counter()
        static = harbour_from_raster(raster, skyline=skyline)  # type: ignore[arg-type]
        build_s = time.perf_counter() - t0
        vessels = {v.name: v for v in sc.vessels}
        scene = Scene.from_scenario(sc)
        scene = Scene(static, {n: (scene.vessel_models[n], vessels[n].trajectory) for n in scene.vessel_names})
        lidars[name] = lidar_for_scenario(sc, scene)
        out[name] = {"build_s": build_s, "triangles": float(sum(len(o.mesh.faces) for o in static))}
    starts = sweep_starts(sc, lidars["flat"].config)[: args.sweeps]
    best = {n: np.full(len(starts), np.inf) for n in lidars}
    points = dict.fromkeys(lidars, 0)
    for r in range(args.repeats + 1):
        for k, s in enumerate(starts):
            for n, lidar in lidars.items():
                t0 = time.perf_counter()
                pts = lidar.sweep(s, k)
                dt = time.perf_counter() - t0
                if r == 0:
                    points[n] += len(pts)
                else:
                    best[n][k] = min(best[n][k], dt)
    for n in lidars:
        out[n]["sweep_ms_median"] = float(np.median(best[n]) * 1e3)
        out[n]["points_per_sweep"] = points[n] / len(starts)
        print(
            f"{n:8s} build {out[n]['build_s']:.3f} s, {out[n]['triangles']:.0f} triangles, "
            f"sweep {out[n]['sweep_ms_median']:.2f} ms (median of best), {out[n]['points_per_sweep']:.0f} points/sweep"
        )
    print(json.dumps(out))


if __name__ == "__main__":
    main()
