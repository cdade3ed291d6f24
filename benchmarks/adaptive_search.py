"""Adaptive search vs random sampling: runs until the first failure of a deliberately weakened agent.

The weakened agent is the reference avoidance reacting only ``--reaction`` seconds before a closest approach, fed
ground truth (its weakness is the late reaction, not perception; ground truth keeps a run under 1 CPU s). A run
fails on a collision or a pass inside the safety distance. For each seed, the number of closed-loop runs adaptive
search (``seatwin.encounters.adaptive_search``) and random sampling (``random_points``, seed 10000 + seed) need to
find the first failure, up to ``--budget`` runs each. The search (``--method``: ``surrogate``, the Gaussian-process
search of ``seatwin.encounters.search``, or ``hill``, the hill-climber ``adaptive_search``) descends ``--score``: ``robustness``
(``seatwin.verification.robustness``: the smallest time to breach the safety domain, negative when failed) or
``min_distance`` (the smallest centre distance − the safety distance: the score of the first version, flat outside
failure pockets). Paired by seed: wins, losses, ties (both censored), a two-sided sign test, the medians (a search
that finds nothing counts as budget + 1). Prints JSON on its last line.

    PYTHONPATH=src .venv/bin/python benchmarks/adaptive_search.py --family head_on --reaction 15 --seeds 20 --budget 40
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from dataclasses import replace

from scipy.stats import binomtest

from seatwin.agents import AvoidanceParameters, ReferenceAgent
from seatwin.encounters import adaptive_search, encounter_scenario, random_points, space
from seatwin.encounters.search import surrogate_search
from seatwin.verification import judge, run_closed_loop
from seatwin.verification.robustness import robustness


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--family", default="crossing_give_way")
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--first-seed", type=int, default=0)
    ap.add_argument("--budget", type=int, default=40)
    ap.add_argument("--reaction", type=float, default=20.0)
    ap.add_argument("--safety", type=float, default=10.0)
    ap.add_argument("--initial", type=int, default=6)
    ap.add_argument("--score", choices=("robustness", "min_distance"), default="robustness")
    ap.add_argument("--method", choices=("surrogate", "hill"), default="surrogate")
    ap.add_argument("--kappa", type=float, default=2.0, help="the surrogate search's lower-confidence-bound weight")
    ap.add_argument("--trace", help="append every evaluated point (JSON lines) to this file")
    ap.add_argument("--random-only", action="store_true", help="only random sampling (a pilot of the failure rate)")
    a = ap.parse_args()
    sp = space(a.family)
    runs, cpu = 0, 0.0

    def evaluate(u: object, seed: int) -> tuple[bool, float]:
        nonlocal runs, cpu
        c0 = time.process_time()
        runs += 1
        scenario, _ = encounter_scenario(sp.encounter(u), "adaptive", "none", seed)
        params = replace(AvoidanceParameters(), reaction_time=a.reaction, stand_on_time=min(a.reaction, 15.0))
        rec = run_closed_loop(scenario, ReferenceAgent("late-truth", "truth", avoidance=params))
        v = judge(rec)
        score = robustness(rec, v, a.safety) if a.score == "robustness" else v.min_distance - a.safety
        cpu += time.process_time() - c0
        if a.trace:
            with open(a.trace, "a") as f:
                f.write(
                    json.dumps({"seed": seed, "u": [round(float(x), 4) for x in u], "min_d": v.min_distance, "score": score})
                    + "\n"
                )
        return (not v.passed), (score if v.passed else min(score, -1e-3))

    t0 = time.perf_counter()
    out = []
    for seed in range(a.first_seed, a.first_seed + a.seeds):
        adaptive = None
        if not a.random_only:
            f = lambda u, s=seed: evaluate(u, s)[1]  # noqa: E731
            if a.method == "surrogate":
                trials = surrogate_search(f, sp.dimension, a.budget, seed, initial=a.initial, kappa=a.kappa)
            else:
                trials = adaptive_search(f, sp.dimension, a.budget, seed, initial=a.initial)
            adaptive = len(trials) if trials[-1].score < 0 else None
        rnd = None
        for i, u in enumerate(random_points(sp.dimension, a.budget, 10_000 + seed)):
            if evaluate(u, seed)[0]:
                rnd = i + 1
                break
        out.append({"seed": seed, "adaptive": adaptive, "random": rnd})
        print(out[-1], flush=True)
    cens = a.budget + 1
    rnd_n = [r["random"] or cens for r in out]
    summary: dict[str, object] = {
        "random_median": statistics.median(rnd_n),
        "random_found": sum(r["random"] is not None for r in out),
    }
    if not a.random_only:
        ada_n = [r["adaptive"] or cens for r in out]
        wins = sum(x < y for x, y in zip(ada_n, rnd_n))
        losses = sum(x > y for x, y in zip(ada_n, rnd_n))
        summary |= {
            "adaptive_median": statistics.median(ada_n),
            "adaptive_found": sum(r["adaptive"] is not None for r in out),
            "adaptive_fewer": wins,
            "random_fewer": losses,
            "ties": len(out) - wins - losses,
            "sign_test_p_two_sided": binomtest(wins, wins + losses).pvalue if wins + losses else None,
            "adaptive_total_runs": sum(ada_n),
            "random_total_runs": sum(rnd_n),
        }
    print(
        json.dumps(
            {
                "family": a.family,
                "reaction_s": a.reaction,
                "score": a.score,
                "method": a.method,
                "kappa": a.kappa,
                "budget": a.budget,
                "initial": a.initial,
                "runs": out,
                **summary,
                "closed_loop_runs": runs,
                "cpu_s_per_run": cpu / max(runs, 1),
                "wall_s": time.perf_counter() - t0,
            }
        )
    )


if __name__ == "__main__":
    main()
