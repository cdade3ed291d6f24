"""Benchmark: `seatwin simulate` real-time factor and the share of wall time spent recording.

Thesis rig's lidar (VLP-16 at 1024 columns, 10 Hz, 80 % ray drop) plus ground truth of every
vessel at 10 Hz, built-in scenario, MCAP, recording included. Baseline in the same process:
the same sweeps computed without recording (so the recording cost shows as a ratio).
``recording_s`` is the time spent in the recording writer (of which ``recording_serialize_s``
encoding messages and ``recording_write_s`` handing them to the bag, flushes included);
``recording_share`` = recording_s / wall_s (target ≤ 0.10).
Prints JSON on its last line. Usage: python benchmarks/simulate.py [--duration S] [--preset NAME] [--sensors LIST]
(``--sensors`` default ``lidar``, this benchmark's subject; ``lidar,camera`` is simulate's default run).
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

from seatwin.scenario.builtin import builtin_scenario
from seatwin.sensors.lidar import lidar_for_scenario
from seatwin.sensors.lidar_config import lidar_preset
from seatwin.sim import simulate_scenario


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenario", default="ferry_crossing")
    ap.add_argument("--duration", type=float, default=30.0)
    ap.add_argument("--preset", default="vlp16-thesis")
    ap.add_argument("--sensors", default="lidar")
    ap.add_argument("--lidar-mode", default="raycast")
    args = ap.parse_args()
    sc = builtin_scenario(args.scenario)
    with tempfile.TemporaryDirectory() as tmp:
        res = simulate_scenario(
            sc,
            Path(tmp) / "run",
            duration=args.duration,
            lidar_preset=args.preset,
            lidar_mode=args.lidar_mode,
            sensors=tuple(args.sensors.split(",")),
            progress=False,
        )
        size = sum(p.stat().st_size for p in (Path(tmp) / "run").rglob("*") if p.is_file())
        parts = json.loads((Path(tmp) / "run" / "manifest.json").read_text())["recording_time_s"]
    lidar = lidar_for_scenario(sc, config=lidar_preset(args.preset), range_model=args.lidar_mode)
    n = int(args.duration * lidar.config.rate_hz)
    t0 = time.perf_counter()
    for k in range(n):
        lidar.sweep(sc.start + k / lidar.config.rate_hz, k)
    sweeps_only = time.perf_counter() - t0
    out = {
        "scenario": args.scenario,
        "preset": args.preset,
        "lidar_mode": args.lidar_mode,
        "simulated_s": res.simulated_s,
        "wall_s": round(res.wall_s, 3),
        "realtime_factor": round(res.realtime_factor, 2),
        "recording_s": round(res.recording_s, 3),
        "recording_share": round(res.recording_share, 4),
        "recording_serialize_s": round(parts["serialize_s"], 4),
        "recording_write_s": round(parts["write_s"], 4),
        "bag_mb": round(size / 1e6, 2),
        "sweeps_only_wall_s": round(sweeps_only, 3),
        "ratio_to_sweeps_only": round(res.wall_s / sweeps_only, 2),
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
