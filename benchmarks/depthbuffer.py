"""Depth-buffer lidar cost next to the exact ray-cast lidar, in one process.

Same world and sweeps as ``benchmarks/lidar.py`` (default harbour, milliAmpere carrying a
VLP-16, Havfruen and Finn moving). Three range models run through the same lidar pipeline:

* ``raycast`` — the baseline: each beam cast exactly;
* ``depthbuffer`` — the spherical projection filter (Table 4.1's lidar, N_c = 8,
  N_c,h = 3104, 2^24 depth levels): the pixel-centre ray of each beam cast, quantised
  (4.8–4.9) and back-projected (4.37–4.42);
* ``depthbuffer-legacy`` — the Gemini regular grid (no filter);
* ``depthbuffer-plane`` — the same depth buffers rasterised by OpenGL (EGL; llvmpipe on a
  CPU), one render per camera sector, each beam intersected with its pixel's surface plane.

Reported: beams/s of whole sweeps (every beam of the sweep counted, as in the lidar
benchmark) at the thesis's 80 % ray drop and with no drop, and the range model alone on
pre-posed batches (ranged beams/s). The rasterised plane mode is timed on ``--plane-sweeps``
sweeps (it costs N_c renders of 4433 × 3104 per sweep). Its accuracy: range error against the
exact ray cast (no drop, no noise) on the same sweeps (p50/p99/max, fallback share) and on the
``seatwin errors --verify`` scene. The last line is JSON.

    .venv/bin/python benchmarks/depthbuffer.py [--sweeps 30] [--repeats 3] [--plane-sweeps 3]
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import platform
import time
from pathlib import Path

import numpy as np


def _lidar_bench_build():  # noqa: ANN202 - the lidar benchmark's scenario, not copied
    spec = importlib.util.spec_from_file_location("_lidar_bench", Path(__file__).with_name("lidar.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)  # type: ignore[union-attr]
    return mod.build


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sweeps", type=int, default=30, help="sweeps per timed run")
    ap.add_argument("--repeats", type=int, default=3, help="timed runs; the best is reported")
    ap.add_argument("--plane-sweeps", type=int, default=3, help="sweeps for the rasterised depthbuffer-plane mode")
    args = ap.parse_args()

    from seatwin.engine.embree import default_threads
    from seatwin.sensors.depthbuffer.lidar_range import legacy_range_model
    from seatwin.sensors.depthbuffer.lidar_range import range_model as db_model
    from seatwin.sensors.lidar import lidar_for_scenario, sweep_starts
    from seatwin.sensors.rangemodel import raycast_ranges
    from seatwin.world.scene import Scene

    sc = _lidar_bench_build()()
    scene = Scene.from_scenario(sc)
    lidar = lidar_for_scenario(sc, scene)
    cfg = lidar.config
    starts = sweep_starts(sc, cfg)[: args.sweeps]
    models = {"raycast": raycast_ranges, "depthbuffer": db_model, "depthbuffer-legacy": legacy_range_model}

    def pipeline(model, config) -> float:  # noqa: ANN001
        lidar._model, lidar.config = model, config  # noqa: SLF001 - same Lidar, same posing and drop
        t0 = time.perf_counter()
        for k, s in enumerate(starts):
            lidar.sweep(s, k)
        return time.perf_counter() - t0

    no_drop = cfg.with_(drop_probability=0.0)
    lidar.config = no_drop
    batches = [lidar.beams(s, k) for k, s in enumerate(starts)]
    lidar.config = cfg

    def ranging(model) -> float:  # noqa: ANN001
        t0 = time.perf_counter()
        for b in batches:
            model(scene, b)
        return time.perf_counter() - t0

    for m in models.values():  # warm-up (builds the filter cache and the vessel casters)
        pipeline(m, cfg)
        ranging(m)
    best: dict[str, dict[str, float]] = {name: {"sweep": np.inf, "sweep0": np.inf, "range": np.inf} for name in models}
    for _ in range(args.repeats):
        for name, m in models.items():
            best[name]["sweep"] = min(best[name]["sweep"], pipeline(m, cfg))
            best[name]["sweep0"] = min(best[name]["sweep0"], pipeline(m, no_drop))
            best[name]["range"] = min(best[name]["range"], ranging(m))
    lidar.config = cfg
    beams = len(starts) * cfg.beams
    ranged = sum(len(b) for b in batches)
    out: dict[str, object] = {
        "benchmark": "depthbuffer",
        "preset": cfg.name,
        "sweeps": len(starts),
        "beams_per_sweep": cfg.beams,
        "drop_probability": cfg.drop_probability,
        "threads": default_threads(),
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
    }
    for name in models:
        key = name.replace("-", "_")
        out[f"{key}_beams_per_s"] = round(beams / best[name]["sweep"])
        out[f"{key}_beams_per_s_no_drop"] = round(beams / best[name]["sweep0"])
        out[f"{key}_range_model_beams_per_s"] = round(ranged / best[name]["range"])
    for name in ("depthbuffer", "depthbuffer-legacy"):
        key = name.replace("-", "_")
        out[f"{key}_cost_vs_raycast"] = round(best[name]["sweep"] / best["raycast"]["sweep"], 2)
        out[f"{key}_cost_vs_raycast_no_drop"] = round(best[name]["sweep0"] / best["raycast"]["sweep0"], 2)
    for name, b in best.items():
        print(
            f"{name:20s} sweep {1e3 * b['sweep'] / len(starts):7.2f} ms  no drop {1e3 * b['sweep0'] / len(starts):7.2f} ms  "
            f"range model alone {ranged / b['range'] / 1e6:6.2f} Mbeams/s"
        )
    out.update(_plane(scene, batches[: args.plane_sweeps], best["raycast"]["range"] / ranged))
    print(json.dumps(out))


def _percentiles(err: np.ndarray) -> dict[str, float]:
    return {f"p{p}": float(np.percentile(err, p)) for p in (50, 99)} | {"max": float(err.max())}


def _plane(scene, batches, raycast_s_per_beam: float) -> dict[str, object]:  # noqa: ANN001
    """Cost and range error of depthbuffer-plane on ``batches`` (no drop), against the same-process ray cast."""
    from seatwin.render import renderer_name
    from seatwin.sensors.depthbuffer.model import DepthBufferConfig
    from seatwin.sensors.depthbuffer.plane_range import plane_ranges, renderer_for
    from seatwin.sensors.depthbuffer.verify import verification_report
    from seatwin.sensors.rangemodel import raycast_ranges

    plane_ranges(scene, batches[0])  # warm-up: uploads the meshes, compiles the shaders
    t0 = time.perf_counter()
    res = [plane_ranges(scene, b) for b in batches]
    dt = time.perf_counter() - t0
    errs, fb, got = [], 0, 0
    for b, r in zip(batches, res):
        ex = raycast_ranges(scene, b)
        same = (ex.object_id >= 0) & (ex.object_id == r.object_id)
        errs.append(np.abs(r.range[same].astype(np.float64) - ex.range[same]))
        fb, got = fb + int(r.fallback.sum()), got + int((r.object_id >= 0).sum())
    err = np.concatenate(errs)
    beams = sum(len(b) for b in batches)
    ver = verification_report(plot=None)
    renderer = renderer_for(scene, DepthBufferConfig().camera(), tuple(batches[0].exclude))
    return {
        "plane_renderer": renderer_name(renderer.ctx),
        "plane_sweeps": len(batches),
        "plane_s_per_sweep": round(dt / len(batches), 3),
        "plane_range_model_beams_per_s": round(beams / dt),
        "plane_cost_vs_raycast_range_model": round(dt / beams / raycast_s_per_beam, 1),
        "plane_sweeps_range_error_m": _percentiles(err),
        "plane_sweeps_fallback_share": round(fb / max(got, 1), 4),
        "verify_range_error_m": {
            k: {"p50": ver[k]["p50"], "p99": ver[k]["p99"], "max": ver[k]["max"], "p99_with_edges": ver[k]["p99_with_edges"]}
            | ({"fallback_share": ver[k]["fallback_share"]} if "fallback_share" in ver[k] else {})
            for k in ("filter", "legacy", "plane", "plane_24bit")
            if k in ver
        },
    }


if __name__ == "__main__":
    main()
