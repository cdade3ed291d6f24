"""Benchmark: tracker numerics over 10^5 random scans — covariances finite and symmetric PSD, r ∈ [0, 1].

    .venv/bin/python benchmarks/tracking_numerics.py [--scans 100000] [--per-run 1000] [--workers N]

Scans from :func:`seatwin.tracking.simulate.stress_scans` (five targets, two of them 2 m apart;
three sensors giving range–bearing, Cartesian and bearing-only measurements; clutter 0–200
plots per scan; detections duplicated exactly or 1 mm apart; time steps of 0, 1 ms,
0.1–2 s and 30–300 s), split into independent runs of ``--per-run`` scans (seed = run index),
half with the clutter-matched tuning and half with the preset ``synthetic`` as it is (gate
g = 1, clutter density far below the scans': crowds of false tracks). After every scan the
whole tracker state is checked with :func:`seatwin.tracking.simulate.state_violations`
(finite state and covariance; ``|P − Pᵀ| ≤ 1e-12·max|P|``; smallest eigenvalue
``≥ −1e-9·max|P|``; existence in [0, 1]). Also checked: a scan earlier than the last is an
``InputError`` and leaves the state unchanged (once per run).

Prints a summary and, on its last line, JSON with ``violations`` (target 0), the scans
checked, the most tracks at once, the extreme existence values and the condition of P.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
from concurrent.futures import ProcessPoolExecutor  # noqa: E402

import numpy as np  # noqa: E402

from seatwin.errors import InputError  # noqa: E402
from seatwin.tracking import JIPDATracker  # noqa: E402
from seatwin.tracking.simulate import state_violations, stress_scans, stress_tuning  # noqa: E402


def one_run(seed: int, n_scans: int) -> dict:
    matched = seed % 2 == 0
    tr = JIPDATracker(stress_tuning(200, matched=matched))
    violations: list[str] = []
    most, r_min, r_max, cond_max, n_meas = 0, 1.0, 0.0, 1.0, 0
    scans = stress_scans(n_scans, seed)
    for k, scan in enumerate(scans):
        tr.step(scan)
        n_meas += scan.z.shape[0]
        v = state_violations(tr.P, tr.r, tr.x)
        if v:
            violations.append(f"run {seed} scan {k}: {'; '.join(v)}")
        if tr.r.size:
            most = max(most, tr.r.size)
            r_min, r_max = min(r_min, float(tr.r.min())), max(r_max, float(tr.r.max()))
            ev = np.linalg.eigvalsh(tr.P)
            cond_max = max(cond_max, float((ev[:, -1] / np.maximum(ev[:, 0], 1e-300)).max()))
    # going back in time: a clear error, state untouched
    back = dataclasses.replace(scans[-1], time=scans[-1].time - 1.0)
    x, P, r = tr.x.copy(), tr.P.copy(), tr.r.copy()
    try:
        tr.step(back)
        violations.append(f"run {seed}: a backwards scan was accepted")
    except InputError:
        if not (np.array_equal(x, tr.x) and np.array_equal(P, tr.P) and np.array_equal(r, tr.r)):
            violations.append(f"run {seed}: a rejected backwards scan changed the state")
    return {
        "violations": violations,
        "scans": n_scans,
        "measurements": n_meas,
        "most_tracks": most,
        "r_min": r_min,
        "r_max": r_max,
        "cond_max": cond_max,
    }


def main() -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scans", type=int, default=100_000)
    ap.add_argument("--per-run", type=int, default=1000)
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args()
    n_runs = -(-args.scans // args.per_run)
    t0 = time.perf_counter()
    with ProcessPoolExecutor(max_workers=args.workers) as pool:
        parts = list(pool.map(one_run, range(n_runs), [args.per_run] * n_runs))
    wall = time.perf_counter() - t0
    violations = [v for p in parts for v in p["violations"]]
    return {
        "violations": len(violations),
        "first_violations": violations[:5],
        "scans": sum(p["scans"] for p in parts),
        "runs": n_runs,
        "measurements": sum(p["measurements"] for p in parts),
        "most_tracks_at_once": max(p["most_tracks"] for p in parts),
        "existence_min": min(p["r_min"] for p in parts),
        "existence_max": max(p["r_max"] for p in parts),
        "covariance_condition_max": float(f"{max(p['cond_max'] for p in parts):.3g}"),
        "wall_s": round(wall, 1),
        "workers": args.workers,
    }


if __name__ == "__main__":
    res = main()
    print(
        f"{res['scans']} scans in {res['runs']} runs ({res['measurements']} measurements, up to "
        f"{res['most_tracks_at_once']} tracks): {res['violations']} violations; existence in "
        f"[{res['existence_min']:.3g}, {res['existence_max']:.6f}]; max cond(P) {res['covariance_condition_max']}"
    )
    print(json.dumps(res))
