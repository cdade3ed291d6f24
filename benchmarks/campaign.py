"""Benchmark: a campaign's per-job cost, and Ray's scaling from 1 to 2 workers against the same jobs run in this process.

    .venv/bin/python benchmarks/campaign.py [--seeds N] [--duration S] [--workers 1,2]

Campaign: ferry_crossing, ``--seeds`` seeds, ``--duration`` s windows, lidar_mode depthbuffer and
raycast against a raycast reference, tuning synthetic: ``2 × seeds`` synthetic jobs and ``seeds``
reference jobs. It is run three ways into fresh folders — in this process one by one (the
baseline), then on a local Ray instance of 1 and of 2 CPUs, each worker started and warmed
first (``ray_start_s``, not in the wall times) — and the three results.csv must be byte-identical
(``results_identical``). Every job uses one thread (``SEATWIN_THREADS=1``, BLAS pinned to 1), as
a Ray task of one CPU does, so the workers are the only parallelism.

Figures: ``per_job_s`` (mean wall and CPU seconds of the job function per kind, in this process);
per run, ``wall_s``, the jobs' ``job_cpu_s`` and ``cores_used`` (CPU / wall: what the machine
gave, with its load average); ``speedup_2_vs_1`` (wall), ``efficiency`` (speed-up / 2) and
``cpu_2_vs_1`` / ``cpu_ray1_vs_sequential`` (the jobs' CPU ratio: the cost of running under Ray
and two at a time, whatever else loads the machine); ``projection``: CPU hours of a
1000-scenario campaign with the same grid per scenario, and its wall time on 100 and 1000
dedicated cores (independent jobs: CPU / cores).

Prints a short table and, on its last line, the JSON.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "SEATWIN_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import logging  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from seatwin.campaign import CampaignSpec, run_campaign  # noqa: E402
from seatwin.campaign.results import CampaignResult  # noqa: E402


def warm_worker() -> int:
    """Import what a job imports (seatwin's simulator, tracker, comparison, Embree), then hold the worker a moment,
    so that each of the instance's workers is started and warm before the campaign is timed."""
    import seatwin.campaign.job  # noqa: F401
    import seatwin.engine.embree  # noqa: F401
    import seatwin.evaluation.compare  # noqa: F401
    import seatwin.pipeline.track  # noqa: F401
    import seatwin.sim  # noqa: F401

    time.sleep(1.0)
    return os.getpid()


def per_job(result: CampaignResult) -> dict[str, float]:
    """Mean wall and CPU seconds of the job function per kind, and the split of a synthetic job."""
    out: dict[str, float] = {}
    for kind, jobs in (("reference", result.grid.reference_jobs), ("synthetic", result.grid.synthetic_jobs)):
        recs = [result.report.records[j.id] for j in jobs]
        out[kind] = sum(r.elapsed_s for r in recs) / len(recs)
        out[f"{kind}_cpu"] = sum(r.cpu_s for r in recs) / len(recs)
    syn = [result.report.records[j.id].result["timings"] for j in result.grid.synthetic_jobs]
    for part in ("simulate_s", "track_s", "compare_s"):
        out[f"synthetic_{part}"] = sum(t[part] for t in syn) / len(syn)
    return out


def timed(spec: CampaignSpec, out: Path, **kw: object) -> dict[str, float]:
    """Run the campaign into ``out``: wall seconds, the jobs' CPU seconds, and the cores that bought (CPU / wall)."""
    t0 = time.perf_counter()
    result = run_campaign(spec, out, **kw)  # type: ignore[arg-type]
    wall = time.perf_counter() - t0
    cpu = result.report.describe()["job_cpu_s_this_run"]
    return {"wall_s": wall, "job_cpu_s": cpu, "cores_used": cpu / wall, "load": os.getloadavg()[0]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--duration", type=float, default=10.0)
    ap.add_argument("--workers", default="1,2")
    args = ap.parse_args()
    import ray

    spec = CampaignSpec(
        scenarios=("ferry_crossing",),
        seeds=tuple(range(1, args.seeds + 1)),
        duration=args.duration,
        synthetic={"lidar_mode": ("depthbuffer", "raycast")},
        reference={"lidar_mode": "raycast"},
        tunings=("synthetic",),
    )
    figures: dict = {"seeds": args.seeds, "duration_s": args.duration, "cores": os.cpu_count(), "load_before": os.getloadavg()[0]}
    runs: dict[str, dict[str, float]] = {}
    start: dict[str, float] = {}
    with tempfile.TemporaryDirectory(prefix="seatwin-bench-campaign-") as tmp:
        runs["sequential"] = timed(spec, Path(tmp) / "seq", engine="sequential")
        base = run_campaign(spec, Path(tmp) / "seq", engine="sequential")  # all cached: reads the records back
        expected = (Path(tmp) / "seq" / "results.csv").read_bytes()
        identical = True
        for n in (int(x) for x in args.workers.split(",")):
            t0 = time.perf_counter()
            ray.init(num_cpus=n, include_dashboard=False, logging_level=logging.WARNING, log_to_driver=False)
            warm = ray.remote(num_cpus=1)(warm_worker)
            pids = ray.get([warm.remote() for _ in range(n)])
            assert len(set(pids)) == n, pids
            start[str(n)] = time.perf_counter() - t0
            try:
                runs[f"ray_{n}"] = timed(spec, Path(tmp) / f"ray{n}", workers=n)
            finally:
                ray.shutdown()
            identical &= (Path(tmp) / f"ray{n}" / "results.csv").read_bytes() == expected
    n_jobs = len(base.grid.jobs)
    pj = per_job(base)
    figures.update(jobs=n_jobs, per_job_s=pj, runs=runs, ray_start_s=start, results_identical=identical)
    if "ray_1" in runs and "ray_2" in runs:
        figures["speedup_2_vs_1"] = runs["ray_1"]["wall_s"] / runs["ray_2"]["wall_s"]
        figures["efficiency"] = figures["speedup_2_vs_1"] / 2
        figures["cpu_2_vs_1"] = runs["ray_2"]["job_cpu_s"] / runs["ray_1"]["job_cpu_s"]
    if "ray_1" in runs:
        figures["cpu_ray1_vs_sequential"] = runs["ray_1"]["job_cpu_s"] / runs["sequential"]["job_cpu_s"]

    # 1000 scenarios with this grid each: CPU from the per-job CPU figures; wall on dedicated cores (jobs independent)
    n_syn, n_ref = 1000 * 2 * args.seeds, 1000 * args.seeds
    cpu_s = n_syn * pj["synthetic_cpu"] + n_ref * pj["reference_cpu"]
    figures["projection"] = {
        "scenarios": 1000,
        "synthetic_jobs": n_syn,
        "reference_jobs": n_ref,
        "cpu_hours": cpu_s / 3600,
        "wall_h_100_cores": cpu_s / 100 / 3600,
        "wall_h_1000_cores": cpu_s / 1000 / 3600,
    }
    print(f"{n_jobs} jobs ({args.seeds} seeds, {args.duration:g} s windows) on {os.cpu_count()} cores")
    print(
        f"per job: reference {pj['reference']:.2f} s ({pj['reference_cpu']:.2f} CPU s), "
        f"synthetic {pj['synthetic']:.2f} s ({pj['synthetic_cpu']:.2f} CPU s)"
    )
    for k, v in runs.items():
        used = f"{v['cores_used']:.2f} cores used, load {v['load']:.1f}"
        print(f"{k:12s} {v['wall_s']:7.2f} s wall, {v['job_cpu_s']:6.2f} CPU s, {used}")
    if "speedup_2_vs_1" in figures:
        print(f"speed-up 2 vs 1 worker: {figures['speedup_2_vs_1']:.2f}; CPU 2 vs 1: {figures['cpu_2_vs_1']:.2f}")
    p = figures["projection"]
    print(f"1000 scenarios: {p['cpu_hours']:.1f} CPU h; {p['wall_h_100_cores']:.2f} h on 100 cores")
    print(json.dumps(figures))


if __name__ == "__main__":
    main()
