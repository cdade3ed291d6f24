"""Benchmark: the cost of a ``seatwin verify`` campaign on the local Ray engine, projected to 10,000 encounters.

Three measurements, on one local Ray instance of ``--workers`` CPUs started first (``ray_start_s``):

1. **Ray per-task overhead** — ``--noop`` jobs that return a verify-sized row at once, through the same engine
   (``run_jobs``: submission, the object store, the driver writing each job's record file): wall per task, the
   driver's CPU per task (``time.process_time`` of this process), and the record files' size per task.
2. **Perfect perception** — ``run_verification`` with ``agents: [perfect]`` over the five families ×
   ``--perfect-encounters`` (open water): wall, the jobs' CPU per run (mean, by family), simulated seconds per run,
   results.csv bytes per row, record bytes per job.
3. **Lidar + radar** — the same with ``agents: [reference]`` (the fitted lidar and radar models, JIPDA) over
   ``head_on`` and ``crossing_give_way`` × ``--sensor-encounters``.

Projection: 10,000 encounters each run by the perfect and the reference agent (20,000 tasks): CPU hours =
10,000 × (CPU per perfect run + CPU per reference run) + 20,000 × the per-task overhead (driver CPU, counted as
serial); wall on a cluster of N dedicated cores = CPU / N, bounded below by the driver's serial time (20,000 ×
its CPU per task), plus Ray's start-up. Prints the JSON on its last line.

    PYTHONPATH=src .venv/bin/python benchmarks/verify_cost.py --workers 2 --perfect-encounters 60 --sensor-encounters 2
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

ROW = {f"column_{i}": 0.123456 for i in range(40)}
"""A row the size of a verify result (about 40 columns)."""


def noop_job(params: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    return {**ROW, "index": params["index"]}


def _dir_bytes(path: Path) -> int:
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file())


def _verify(spec_text: str, root: Path, name: str, workers: int) -> dict[str, Any]:
    from seatwin.verification.campaign import run_verification

    spec = root / f"{name}.yaml"
    spec.write_text(spec_text)
    out = root / name
    c0, t0 = time.process_time(), time.perf_counter()
    res = run_verification(spec, out, engine="ray", workers=workers)
    wall, driver_cpu = time.perf_counter() - t0, time.process_time() - c0
    rows = [r for r in res.rows if r.get("passed") is not None]
    by_family = {f: statistics.mean(r["cpu_s"] for r in rows if r["family"] == f) for f in sorted({r["family"] for r in rows})}
    n = len(rows)
    return {
        "runs": n,
        "failed_jobs": res.report.n_failed,
        "wall_s": wall,
        "wall_s_per_run": wall / n,
        "driver_cpu_s": driver_cpu,
        "cpu_s_per_run": statistics.mean(r["cpu_s"] for r in rows),
        "cpu_s_per_run_max": max(r["cpu_s"] for r in rows),
        "cpu_s_per_run_by_family": by_family,
        "job_wall_s_per_run": statistics.mean(r["wall_s"] for r in rows),
        "simulated_s_per_run": statistics.mean(r["simulated_s"] for r in rows),
        "cores_used": sum(r["cpu_s"] for r in rows) / wall,
        "results_csv_bytes_per_row": (out / "results.csv").stat().st_size / n,
        "record_bytes_per_job": _dir_bytes(out / "jobs") / n,
        "failure_rate": sum(not r["passed"] for r in rows) / n,
    }


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--noop", type=int, default=300)
    ap.add_argument("--perfect-encounters", type=int, default=60, help="per family (5 families)")
    ap.add_argument("--sensor-encounters", type=int, default=2, help="per family (head_on, crossing_give_way)")
    ap.add_argument("--cores", type=int, nargs="+", default=[16, 64, 256, 1024])
    a = ap.parse_args()
    import ray

    from seatwin.campaign.engine import Job, run_jobs

    out: dict[str, Any] = {"workers": a.workers, "load_average_start": os.getloadavg()}
    t0 = time.perf_counter()
    ray.init(num_cpus=a.workers, include_dashboard=False, log_to_driver=False)
    ray.get([ray.remote(num_cpus=1)(lambda: 0).remote() for _ in range(a.workers)])  # workers started and warm
    out["ray_start_s"] = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        jobs = [Job({"kind": "noop", "index": i}) for i in range(a.noop)]
        c0, t0 = time.process_time(), time.perf_counter()
        rep = run_jobs(jobs, noop_job, root / "noop", engine="ray", workers=a.workers)
        wall = time.perf_counter() - t0
        out["noop"] = {
            "tasks": a.noop,
            "failed": rep.n_failed,
            "wall_s_per_task": wall / a.noop,
            "driver_cpu_s_per_task": (time.process_time() - c0) / a.noop,
            "record_bytes_per_task": _dir_bytes(root / "noop" / "jobs") / a.noop,
        }
        print("noop", out["noop"], flush=True)
        families = "[head_on, crossing_give_way, crossing_stand_on, overtaking, multi]"
        out["perfect"] = _verify(
            f"agents: [perfect]\nfamilies: {families}\nencounters: {a.perfect_encounters}\nworst: 0\n", root, "perfect", a.workers
        )
        print("perfect", out["perfect"], flush=True)
        out["lidar_radar"] = _verify(
            f"agents: [reference]\nfamilies: [head_on, crossing_give_way]\nencounters: {a.sensor_encounters}\nworst: 0\n",
            root,
            "lidar_radar",
            a.workers,
        )
        print("lidar_radar", out["lidar_radar"], flush=True)
    ray.shutdown()
    out["load_average_end"] = os.getloadavg()
    overhead = out["noop"]["driver_cpu_s_per_task"]
    n = 10_000
    cpu = n * (out["perfect"]["cpu_s_per_run"] + out["lidar_radar"]["cpu_s_per_run"]) + 2 * n * overhead
    serial = 2 * n * overhead
    out["projection_10k"] = {
        "tasks": 2 * n,
        "cpu_hours": cpu / 3600,
        "cpu_hours_perfect_only": (n * out["perfect"]["cpu_s_per_run"] + n * overhead) / 3600,
        "driver_serial_s": serial,
        "wall_min_by_cores": {c: (max(cpu / c, serial) + out["ray_start_s"]) / 60 for c in a.cores},
        "results_csv_mb": 2 * n * out["perfect"]["results_csv_bytes_per_row"] / 1e6,
        "records_mb": n * (out["perfect"]["record_bytes_per_job"] + out["lidar_radar"]["record_bytes_per_job"]) / 1e6,
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
