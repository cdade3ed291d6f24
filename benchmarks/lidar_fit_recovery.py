"""Does ``fit_lidar`` recover a known lidar model? (issue 22 item 5, lidar; docs/validation.md)

Each case draws a "real" model at random within realistic ranges (range noise σ 0.01–0.1 m, log-uniform; ray drop
0.5–0.9; dissipation half range 35–90 m, log-uniform), simulates it along a built-in scenario at seed
``1000 + case`` (every ``--every``-th sweep of the window), and fits the three parameters with the candidates at
seeds ``0 …`` (:func:`seatwin.fidelity.lidar_fit.fit_lidar`). Reports per case and parameter the truth, the
estimate, the 95 % interval and whether it covers the truth, and the CPU time of each fit.

    .venv/bin/python benchmarks/lidar_fit_recovery.py --cases 6 --out /tmp/lidar_fit_recovery.json
"""

from __future__ import annotations

import argparse
import json
import time
from typing import Any

import numpy as np

RANGES = {
    "range_noise_m": (0.01, 0.1, True),
    "drop_probability": (0.5, 0.9, False),
    "dissipation_half_range_m": (35.0, 90.0, True),
}


def draw_truth(rng: np.random.Generator) -> dict[str, float]:
    """One model drawn within :data:`RANGES` (log-uniform where flagged)."""
    out = {}
    for k, (lo, hi, log) in RANGES.items():
        out[k] = float(np.exp(rng.uniform(np.log(lo), np.log(hi)))) if log else float(rng.uniform(lo, hi))
    return out


def run_case(case: int, args: argparse.Namespace) -> dict[str, Any]:
    from seatwin.evaluation.truth import truth_from_scenario
    from seatwin.fidelity.lidar_fit import FitSetup, candidate_config, fit_lidar, simulated_samples
    from seatwin.perception.map_mask import load_mask
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sensors.lidar_config import VLP16

    sc = builtin_scenario(args.scenario)
    truth_params = draw_truth(np.random.default_rng([args.seed, case]))
    starts = sc.start + np.arange(args.offset, args.offset + args.duration, args.every / VLP16.rate_hz)
    frames = np.rint((starts - sc.start) * VLP16.rate_hz).astype(np.int64)
    seeds = tuple(range(args.seeds))
    setup = FitSetup(sc, starts, frames, truth_from_scenario(sc), None, load_mask("harbour"), None, "raycast", seeds)
    real = simulated_samples(setup, candidate_config(VLP16, truth_params), 1000 + case)
    t0 = time.process_time()
    fit = fit_lidar([real], setup, VLP16, rounds=args.rounds, n_boot=args.boot, seed=case)
    cpu = time.process_time() - t0
    rows = {}
    for k, v in fit.parameters.items():
        lo, hi = v["ci95"]
        rows[k] = {"truth": truth_params[k], "estimate": v["estimate"], "ci95": [lo, hi], "covered": lo <= truth_params[k] <= hi}
    return {"case": case, "parameters": rows, "distance": fit.distance, "candidates": len(fit.candidates), "cpu_s": cpu}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=6)
    ap.add_argument("--scenario", default="ferry_crossing")
    ap.add_argument("--offset", type=float, default=15.0, help="Window start after the scenario's start [s].")
    ap.add_argument("--duration", type=float, default=45.0, help="Window length [s] (ranges ~100 → 24 → 90 m).")
    ap.add_argument("--every", type=int, default=3, help="Use every n-th sweep.")
    ap.add_argument("--seeds", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--boot", type=int, default=200)
    ap.add_argument("--seed", type=int, default=22)
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    cases = []
    for c in range(args.cases):
        r = run_case(c, args)
        cases.append(r)
        line = "  ".join(
            f"{k[:12]} {v['truth']:.3g}→{v['estimate']:.3g} [{v['ci95'][0]:.3g}, {v['ci95'][1]:.3g}]"
            + ("" if v["covered"] else " MISS")
            for k, v in r["parameters"].items()
        )
        print(f"case {c}: {line}  ({r['candidates']} candidates, {r['cpu_s']:.0f} s CPU)", flush=True)
    covered = {k: sum(r["parameters"][k]["covered"] for r in cases) for k in RANGES}
    print("covered:", covered, "of", len(cases), "; mean CPU per fit", np.mean([r["cpu_s"] for r in cases]).round(1), "s")
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            json.dump({"args": vars(args), "cases": cases, "covered": covered}, f, indent=1)


if __name__ == "__main__":
    main()
