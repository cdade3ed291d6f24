"""Benchmark: `seatwin simulate` real-time factor and the share of wall time spent recording.

Thesis rig's lidar (VLP-16 at 1024 columns, 10 Hz, 80 % ray drop) plus ground truth of every
vessel at 10 Hz, built-in scenario, MCAP, recording included. Baseline in the same process:
the same sweeps computed without recording (so the recording cost shows as a ratio).
``recording_s`` is the time spent in the recording writer (of which ``recording_serialize_s``
encoding messages and ``recording_write_s`` handing them to the bag, flushes included);
``recording_share`` = recording_s / wall_s (target ≤ 0.10).
Prints JSON on its last line. Usage: python benchmarks/simulate.py [--duration S] [--preset NAME] [--sensors LIST]
(``--sensors`` default ``lidar``, this benchmark's subject; ``lidar,camera`` is simulate's default run).

Bag size (issue #23): ``--compare none/raw,default`` runs the same simulation once per variant
(``COMPRESSION/IMAGE_FORMAT``; ``default`` = seatwin's defaults, lz4 chunks and raw images), ``--repeats``
times in turn (A B A B …, so a slow spell of a shared machine hits all alike), and prints per variant the bag
size, the best wall time, the real-time factor and the process CPU time, and their ratios to the first
variant: ``python benchmarks/simulate.py --sensors lidar,camera --preset vlp16 --compare none/raw,default``.
A variant may name the bag format first, ``FORMAT:COMPRESSION/IMAGE_FORMAT`` (default mcap): rosbag2 SQLite3 with
rosbag2's zstd, ``--compare sqlite3:none/raw,sqlite3:zstd/raw,sqlite3:zstd-file/raw``; ``--read`` adds the CPU time
to read each bag's messages back (inflated, not decoded).
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
    ap.add_argument("--compare", default=None, help="variants [FORMAT:]COMPRESSION/IMAGE_FORMAT or 'default', comma-separated")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--read", action="store_true", help="with --compare: also the CPU time to read each bag back")
    args = ap.parse_args()
    sc = builtin_scenario(args.scenario)
    if args.compare:
        compare(sc, args)
        return
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


def _run(sc: object, args: argparse.Namespace, variant: str) -> dict[str, float]:
    """One simulation with ``variant``'s compression and image format: wall, CPU time, RTF, bag size."""
    extra: dict[str, str] = {}
    if variant != "default":
        fmt, _, rest = variant.rpartition(":")
        compression, image_format = rest.split("/")
        extra = {"compression": compression, "image_format": image_format} | ({"fmt": fmt} if fmt else {})
    with tempfile.TemporaryDirectory() as tmp:
        cpu0 = time.process_time()
        res = simulate_scenario(
            sc,
            Path(tmp) / "run",
            duration=args.duration,
            lidar_preset=args.preset,
            lidar_mode=args.lidar_mode,
            sensors=tuple(args.sensors.split(",")),
            progress=False,
            **extra,
        )
        cpu = time.process_time() - cpu0
        size = sum(p.stat().st_size for p in (Path(tmp) / "run").rglob("*") if p.is_file())
        out = {"wall_s": res.wall_s, "cpu_s": cpu, "rtf": res.realtime_factor, "recording_s": res.recording_s}
        out["bag_mb"] = size / 1e6
        if args.read:
            out["read_cpu_s"] = _read_cpu(Path(tmp) / "run")
    return out


def _read_cpu(run: Path) -> float:
    """CPU seconds to open the run's bag and read every message's bytes (inflated, not decoded), and close it."""
    from seatwin.recording import open_bag

    cpu0 = time.process_time()
    with open_bag(run) as rec:
        for _ in rec.raw_messages():
            pass
    return time.process_time() - cpu0


def compare(sc: object, args: argparse.Namespace) -> None:
    """Every variant of ``--compare`` ``--repeats`` times in turn; the best wall and CPU time of each; ratios to the first."""
    variants = args.compare.split(",")
    runs: dict[str, list[dict[str, float]]] = {v: [] for v in variants}
    _run(sc, argparse.Namespace(**{**vars(args), "duration": min(2.0, args.duration)}), variants[0])  # warm-up: caches, imports
    for _ in range(args.repeats):
        for v in variants:
            runs[v].append(_run(sc, args, v))
    base: dict[str, float] | None = None
    table = {}
    for v in variants:
        r = runs[v]
        best = {
            "bag_mb": round(r[0]["bag_mb"], 2),
            "wall_s": round(min(x["wall_s"] for x in r), 3),
            "cpu_s": round(min(x["cpu_s"] for x in r), 3),
            "realtime_factor": round(max(x["rtf"] for x in r), 3),
            "recording_s": round(min(x["recording_s"] for x in r), 3),
            "walls_s": [round(x["wall_s"], 2) for x in r],
        }
        if "read_cpu_s" in r[0]:
            best["read_cpu_s"] = round(min(x["read_cpu_s"] for x in r), 3)
        base = base or best
        best["size_ratio"] = round(best["bag_mb"] / base["bag_mb"], 4)
        best["rtf_ratio"] = round(best["realtime_factor"] / base["realtime_factor"], 3)
        best["cpu_ratio"] = round(best["cpu_s"] / base["cpu_s"], 3)
        table[v] = best
        print(
            f"{v:>20}: {best['bag_mb']:8.2f} MB  RTF {best['realtime_factor']:6.2f} (x{best['rtf_ratio']:.3f})"
            f"  CPU {best['cpu_s']:.2f} s (x{best['cpu_ratio']:.3f})"
        )
    info = {"scenario": args.scenario, "sensors": args.sensors, "preset": args.preset, "duration_s": args.duration}
    print(json.dumps({**info, "repeats": args.repeats, "variants": table}))


if __name__ == "__main__":
    main()
