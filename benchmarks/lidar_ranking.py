"""Does the fidelity score rank the true lidar model first? (issue 22, lidar; docs/validation.md)

The "real" run is the default model at seed ``s + 1000``; the candidates (``lidar_runs.MODELS``) each at seed
``s``; every scenario's 60 s window centred in it. A case is a (scenario, seed); the default model ranks first
when its S5 is below that of depthbuffer-legacy and range noise 0.1 m (the criterion fixed in
docs/fidelity-score.md before the runs). Also: against all candidates, by S7 (lidar terms) alone, by S5 without
S7, and per lidar term how often each wrong model is resolved, and in which direction.

    .venv/bin/python benchmarks/lidar_ranking.py --seeds 1 2 3 --workers 2 --out /tmp/lidar_ranking.json

``--pool K`` pools K independent runs a side (K× the data; evaluation 8 of docs/fidelity-score.md): the
candidates at seeds ``100·s + j`` and the real side at ``100·s + 1000 + j``, j = 0..K−1.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from lidar_runs import MODELS, ensure_runs, load_runs, parallel_map, score_pair  # noqa: E402

REAL_OFFSET = 1000
CRITERION = ("depthbuffer-legacy", "range_noise_0.1")


def pool_seeds(seed: int, pool: int) -> list[int]:
    """The candidates' seeds of case ``seed`` (the real side's: each + ``REAL_OFFSET``): ``[seed]`` for one run a
    side, else ``100·seed + j`` for j < ``pool``."""
    return [seed] if pool == 1 else [100 * seed + j for j in range(pool)]


def score_case(case: tuple[str, int], duration: float, cache: str, models: tuple[str, ...], pool: int = 1) -> dict[str, Any]:
    """Every candidate's S5, S7 and S5 without S7 against the case's real runs, and its lidar terms."""
    from seatwin.evaluation.lidar_terms import lidar_terms, run_lidar_samples
    from seatwin.evaluation.score import overall_score

    scenario, seed = case
    seeds = pool_seeds(seed, pool)
    real = load_runs([(scenario, "default", k + REAL_OFFSET) for k in seeds], duration, cache)
    out: dict[str, Any] = {"scenario": scenario, "seed": seed, "pool": pool, "models": {}}
    for model in models:
        cand = load_runs([(scenario, model, k) for k in seeds], duration, cache)
        f = score_pair(real, cand)
        without = overall_score(f.targets, {k: v for k, v in f.plots.items() if k != "lidar_returns"})
        rs = run_lidar_samples([r["tracks"] for r in real], real[0]["truth"])
        cs = run_lidar_samples([c["tracks"] for c in cand], real[0]["truth"])
        terms = {} if rs is None or cs is None else lidar_terms(rs, cs)
        out["models"][model] = {
            "S5": f.overall.value,
            "S5_ci": [f.overall.ci_low, f.overall.ci_high],
            "S7": f.plots["lidar_returns"].value,
            "S5_without_S7": without.value,
            "false_tracks": {
                k: f.plots["false_tracks"].counts.get(k)
                for k in ("alive_hellinger", "false_tracks_real", "false_tracks_synthetic")
            }
            | {"value": f.plots["false_tracks"].value},
            "parts": {k: v.value for k, v in f.plots.items()} | {"targets_mean": f.overall.counts.get("targets_mean")},
            "terms": {
                k: {"difference": t.difference, "resolved": t.resolved, "sentence": t.sentence()} for k, t in terms.items()
            },
        }
    return out


def first(case: dict[str, Any], key: str, against: tuple[str, ...]) -> bool | None:
    """Whether the default model's ``key`` is below every model of ``against`` (None if any is undefined)."""
    vals = {m: case["models"][m][key] for m in ("default", *against)}
    if any(v is None for v in vals.values()):
        return None
    return all(vals["default"] < vals[m] for m in against)


def main() -> None:
    from seatwin.scenario.builtin import builtin_names

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenarios", nargs="*", default=builtin_names())
    ap.add_argument("--seeds", nargs="*", type=int, default=[1, 2, 3])
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--models", nargs="*", default=list(MODELS), choices=list(MODELS))
    ap.add_argument("--pool", type=int, default=1, help="independent runs pooled a side (K× the data)")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--cache", default="/tmp/seatwin-lidarbench")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    t0 = time.perf_counter()
    seeds = {s: pool_seeds(s, a.pool) for s in a.seeds}
    jobs = [(sc, "default", k + REAL_OFFSET) for sc in a.scenarios for s in a.seeds for k in seeds[s]]
    jobs += [(sc, m, k) for sc in a.scenarios for s in a.seeds for m in a.models for k in seeds[s]]
    ensure_runs(jobs, a.duration, a.cache, a.workers)
    t1 = time.perf_counter()
    cases = parallel_map(
        partial(score_case, duration=a.duration, cache=a.cache, models=tuple(a.models), pool=a.pool),
        [(sc, s) for sc in a.scenarios for s in a.seeds],
        a.workers,
    )
    others = tuple(m for m in a.models if m != "default")
    summary = {}
    for label, key, against in (
        ("S5 vs legacy + noise 0.1 (criterion)", "S5", CRITERION),
        ("S5 vs every other candidate", "S5", others),
        ("S7 alone vs legacy + noise 0.1", "S7", CRITERION),
        ("S7 alone vs every other candidate", "S7", others),
        ("S5 without S7 vs legacy + noise 0.1", "S5_without_S7", CRITERION),
        *((f"S5 vs {m} alone", "S5", (m,)) for m in others),
        *((f"S7 vs {m} alone", "S7", (m,)) for m in others),
    ):
        got = [first(c, key, against) for c in cases]
        summary[label] = {"first": sum(g is True for g in got), "cases": sum(g is not None for g in got)}
    resolved: dict[str, dict[str, Any]] = {}
    for m in others:
        for k in cases[0]["models"][m]["terms"]:
            ts = [c["models"][m]["terms"].get(k) for c in cases]
            ts = [t for t in ts if t and t["difference"] is not None]
            if ts:
                resolved.setdefault(m, {})[k] = {
                    "resolved": sum(t["resolved"] for t in ts),
                    "positive": sum(t["resolved"] and t["difference"] > 0 for t in ts),
                    "computed": len(ts),
                }
    print(f"runs {t1 - t0:.0f} s, scoring {time.perf_counter() - t1:.0f} s, {len(cases)} cases")
    print("| case | " + " | ".join(f"{m} S5 / S7" for m in a.models) + " |")
    for c in cases:
        cells = [
            " / ".join("–" if c["models"][m][k] is None else f"{c['models'][m][k]:.3f}" for k in ("S5", "S7")) for m in a.models
        ]
        print(f"| {c['scenario']} s{c['seed']} | " + " | ".join(cells) + " |")
    for k, v in summary.items():
        print(f"{k}: default first in {v['first']} of {v['cases']}")
    ft = [c["models"]["default"]["false_tracks"] for c in cases]
    for key, label in (("value", "new (each track once, per minute)"), ("alive_hellinger", "former (alive per scan)")):
        v = [x[key] for x in ft if x[key] is not None]
        if v:
            print(f"false-track term, default, {label}: {min(v):.3f}–{max(v):.3f}, mean {np.mean(v):.3f} over {len(v)} cases")
    for m, terms in resolved.items():
        print(m, {k: f"{v['resolved']}/{v['computed']} ({v['positive']} +)" for k, v in terms.items() if v["resolved"]})
    if a.out:
        Path(a.out).write_text(json.dumps({"args": vars(a), "summary": summary, "resolved": resolved, "cases": cases}, indent=1))


if __name__ == "__main__":
    main()
