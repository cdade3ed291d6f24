"""Adaptive search vs random sampling: runs until the first failure of a deliberately weakened agent.

The weakened agent is the reference avoidance reacting only ``--reaction`` seconds before a closest approach, fed
ground truth (its weakness is the late reaction, not perception; ground truth keeps a run at ~1 s). A run's score is
its smallest centre distance minus the safety distance (< 0: a failure). For each seed, the number of closed-loop runs
adaptive search (``seatwin.encounters.adaptive_search``) and random sampling need to find the first failure, up to
``--budget`` runs. Prints JSON on its last line.

    PYTHONPATH=src .venv/bin/python benchmarks/adaptive_search.py --family crossing_give_way --seeds 5
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import replace

from seatwin.agents import AvoidanceParameters, ReferenceAgent
from seatwin.encounters import adaptive_search, encounter_scenario, random_points, space
from seatwin.verification import judge, run_closed_loop


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--family", default="crossing_give_way")
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--budget", type=int, default=60)
    ap.add_argument("--reaction", type=float, default=6.0)
    ap.add_argument("--safety", type=float, default=10.0)
    a = ap.parse_args()
    sp = space(a.family)
    runs = 0

    def score(u: object, seed: int) -> float:
        nonlocal runs
        runs += 1
        scenario, _ = encounter_scenario(sp.encounter(u), "adaptive", "none", seed)
        agent = ReferenceAgent(
            "late-truth", "truth", avoidance=replace(AvoidanceParameters(), reaction_time=a.reaction, stand_on_time=a.reaction)
        )
        v = judge(run_closed_loop(scenario, agent))
        return v.min_distance - a.safety

    t0 = time.perf_counter()
    out = []
    for seed in range(a.seeds):
        trials = adaptive_search(lambda u, s=seed: score(u, s), sp.dimension, a.budget, seed, initial=6)
        adaptive = len(trials) if trials[-1].score < 0 else None
        rnd = None
        for i, u in enumerate(random_points(sp.dimension, a.budget, 10_000 + seed)):
            if score(u, seed) < 0:
                rnd = i + 1
                break
        out.append({"seed": seed, "adaptive": adaptive, "random": rnd})
        print(out[-1], flush=True)
    print(
        json.dumps(
            {
                "family": a.family,
                "reaction_s": a.reaction,
                "budget": a.budget,
                "runs": out,
                "closed_loop_runs": runs,
                "wall_s": time.perf_counter() - t0,
            }
        )
    )


if __name__ == "__main__":
    main()
