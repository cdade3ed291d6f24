"""Coverage of the lidar intervals: N pairs of independent recordings of one model (issue 22, item 2; lidar).

Pair i is the default model at seed ``base + (K + 1) i`` (A, "real") and the K next seeds (B, "model", its runs
pooled; ``--model-runs K``, default 1) on one scenario's centred window. Criteria (fixed in docs/fidelity-score.md
before the runs): a signed lidar term is covered when the 95 % interval of B − A holds 0 and when A's own
interval holds the pooled value (all recordings); a distance (S7 lidar terms, S4b false tracks, the other S5
parts, S5) when its interval's lower bound is 0. Blocks chosen from the data; with K = 1 also blocks of 10 scans
(the former default), with K ≥ 2 the target terms without (``within``) and with (``spread``) the run-to-run
spread (docs/fidelity-score.md). Also the spread of the false-track term, former (alive per scan) and new (each
track once, per minute), over the pairs.

    .venv/bin/python benchmarks/lidar_calibration.py --pairs 50 --workers 16 --out /tmp/lidar_calibration.json
    .venv/bin/python benchmarks/lidar_calibration.py --pairs 50 --model-runs 3 --duration 20 --base 2040 --workers 2
    .venv/bin/python benchmarks/lidar_calibration.py --pairs 50 --model-runs 3 --duration 20 --base 2040 --workers 2 \
        --targets-only

``--terms-only``: the signed lidar terms alone, with the time design (docs/fidelity-score.md, *Time design of the
lidar terms*) on and off over the same pairs, and the mean width of each difference's interval (evaluation 14):

    .venv/bin/python benchmarks/lidar_calibration.py --pairs 50 --duration 20 --base 5000 --workers 2 --terms-only
    .venv/bin/python benchmarks/lidar_calibration.py --pairs 50 --duration 60 --base 5200 --workers 2 --terms-only
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

from lidar_runs import ensure_runs, load_runs, parallel_map, score_pair  # noqa: E402


def _holds(ci: Any, x: float) -> bool | None:
    return None if ci is None or ci[0] is None else bool(ci[0] - 1e-12 <= x <= ci[1] + 1e-12)


VARIANTS = {1: ((10, True, "block10"), (None, True, "data")), 2: ((None, False, "within"), (None, True, "spread"))}
"""Score variants per number of model runs (1, or ≥ 2): (block, run_spread, tag)."""


def score_one(pair: tuple[int, ...], scenario: str, duration: float, cache: str, pooled: dict[str, float]) -> dict[str, Any]:
    """Coverage flags of one pair (A, B = the model's runs), for each score variant."""
    from seatwin.evaluation.lidar_terms import lidar_terms, run_lidar_samples

    a, *b = load_runs([(scenario, "default", s) for s in pair], duration, cache)
    out: dict[str, Any] = {"seeds": pair, "signed": {}, "distance": {}}
    sa, sb = run_lidar_samples([a["tracks"]], a["truth"]), run_lidar_samples([r["tracks"] for r in b], a["truth"])
    for k, t in lidar_terms(sa, sb).items():  # type: ignore[arg-type]
        if t.difference is not None:
            out["signed"][k] = {
                "diff_covers_0": _holds(t.difference_ci, 0.0),
                "a_covers_pooled": _holds(t.real_ci, pooled.get(k, np.nan)),
            }
    for block, spread, tag in VARIANTS[min(len(b), 2)]:
        f = score_pair([a], b, block, spread)
        parts = {"S5": f.overall, **f.plots, **{f"target {k}": v for k, v in f.targets.items()}}
        out["distance"][tag] = {
            k: {"value": v.value, "ci": [v.ci_low, v.ci_high], "covers_0": None if v.ci_low is None else v.ci_low <= 1e-12}
            for k, v in parts.items()
            if v.value is not None
        }
        if tag in ("block10", "within"):
            ft = f.plots["false_tracks"]
            out["false_tracks"] = {"new": ft.value, "former": ft.counts.get("alive_hellinger"), **ft.counts}
    return out


def score_terms(pair: tuple[int, ...], scenario: str, duration: float, cache: str, pooled: dict[str, float]) -> dict[str, Any]:
    """Coverage flags and the difference's interval width of every signed lidar term of one pair, with the time
    design on and off."""
    from seatwin.evaluation.lidar_terms import lidar_terms, run_lidar_samples
    from seatwin.evaluation.score import ScoreOptions

    a, *b = load_runs([(scenario, "default", s) for s in pair], duration, cache)
    sa, sb = run_lidar_samples([a["tracks"]], a["truth"]), run_lidar_samples([r["tracks"] for r in b], a["truth"])
    out: dict[str, Any] = {"seeds": pair, "signed": {}}
    for tag, design in (("design", True), ("plain", False)):
        for k, t in lidar_terms(sa, sb, ScoreOptions(lidar_design=design)).items():  # type: ignore[arg-type]
            if t.difference is not None:
                out["signed"].setdefault(tag, {})[k] = {
                    "difference": t.difference,
                    "width": float(np.diff(t.difference_ci)[0]),  # type: ignore[arg-type]
                    "diff_covers_0": _holds(t.difference_ci, 0.0),
                    "a_covers_pooled": _holds(t.real_ci, pooled.get(k, np.nan)),
                }
    return out


def _count(c: tuple[int, int]) -> str:
    return f"{c[0]}/{c[1]}"


def terms_table(res: list[dict[str, Any]], pooled: dict[str, float]) -> dict[str, Any]:
    """Per term and setting: the coverage shares, the mean interval width and the pairs' spread of the difference."""
    table: dict[str, Any] = {}
    print("| lidar term | pooled | design on: diff / A | off: diff / A | mean width on / off | SD of the difference |")
    for k, v in pooled.items():
        row: dict[str, Any] = {"pooled": v}
        for tag in ("design", "plain"):
            got = [r["signed"].get(tag, {}).get(k) for r in res]
            got = [g for g in got if g is not None]
            row[tag] = {
                "diff_covers_0": share([g["diff_covers_0"] for g in got]),
                "a_covers_pooled": share([g["a_covers_pooled"] for g in got]),
                "mean_width": float(np.mean([g["width"] for g in got])) if got else None,
                "sd_difference": float(np.std([g["difference"] for g in got], ddof=1)) if len(got) > 1 else None,
            }
        on, off = row["design"], row["plain"]
        table[k] = row
        w = "–" if on["mean_width"] is None else f"{on['mean_width']:.4g} / {off['mean_width']:.4g}"
        sd = "–" if on["sd_difference"] is None else f"{on['sd_difference']:.4g}"
        print(
            f"| {k} | {v:.4g} | {_count(on['diff_covers_0'])} / {_count(on['a_covers_pooled'])} | "
            f"{_count(off['diff_covers_0'])} / {_count(off['a_covers_pooled'])} | {w} | {sd} |"
        )
    return table


def score_targets(pair: tuple[int, ...], scenario: str, duration: float, cache: str) -> dict[str, Any]:
    """``--targets-only``: coverage flags of the target terms S1–S3 and of their mean S̄ (S5 without its plot parts),
    without (``within``) and with (``spread``) the run-to-run spread."""
    from seatwin.evaluation.score import ScoreOptions, TargetErrors, overall_score, target_score

    a, *b = load_runs([(scenario, "default", s) for s in pair], duration, cache)
    out: dict[str, Any] = {"seeds": pair, "distance": {}}
    for spread, tag in ((False, "within"), (True, "spread")):
        o = ScoreOptions(block=None, run_spread=spread)
        targets = {
            n: target_score(
                [TargetErrors.from_series(a["evaluation"].series[n])],
                [TargetErrors.from_series(r["evaluation"].series[n]) for r in b],
                o,
                stream=n,
            )
            for n in a["evaluation"].series
        }
        parts = {"S-bar (S5 without plot parts)": overall_score(targets, {}, o), **{f"target {k}": v for k, v in targets.items()}}
        out["distance"][tag] = {
            k: {"value": v.value, "ci": [v.ci_low, v.ci_high], "covers_0": None if v.ci_low is None else v.ci_low <= 1e-12}
            for k, v in parts.items()
            if v.value is not None
        }
    return out


def share(flags: list[bool | None]) -> tuple[int, int]:
    got = [f for f in flags if f is not None]
    return sum(got), len(got)


def main() -> None:
    from seatwin.evaluation.lidar_terms import lidar_terms, run_lidar_samples

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=50)
    ap.add_argument("--scenario", default="ferry_crossing")
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--base", type=int, default=2000)
    ap.add_argument("--model-runs", type=int, default=1, help="K: runs (seeds) of the model pooled on side B")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--cache", default="/tmp/seatwin-lidarbench")
    ap.add_argument("--out", default=None)
    ap.add_argument("--targets-only", action="store_true", help="only the target terms and their mean (K ≥ 2)")
    ap.add_argument("--terms-only", action="store_true", help="only the signed lidar terms, time design on and off")
    a = ap.parse_args()
    t0 = time.perf_counter()
    k = a.model_runs + 1
    seeds = list(range(a.base, a.base + k * a.pairs))
    ensure_runs([(a.scenario, "default", s) for s in seeds], a.duration, a.cache, a.workers)
    t1 = time.perf_counter()
    pairs = [tuple(seeds[k * i : k * (i + 1)]) for i in range(a.pairs)]
    if a.targets_only:
        res = parallel_map(partial(score_targets, scenario=a.scenario, duration=a.duration, cache=a.cache), pairs, a.workers)
        print(f"{a.pairs} pairs (1 against {a.model_runs} runs), target terms only: scoring {time.perf_counter() - t1:.0f} s")
        table = {}
        for tag in ("within", "spread"):
            for name in sorted({n for r in res for n in r["distance"][tag]}):
                c = share([r["distance"][tag].get(name, {}).get("covers_0") for r in res])
                vals = [r["distance"][tag][name]["value"] for r in res if name in r["distance"][tag]]
                width = [np.diff(r["distance"][tag][name]["ci"])[0] for r in res if name in r["distance"][tag]]
                table[f"{tag}: {name}"] = {"covers_0": c, "mean": float(np.mean(vals)), "mean_width": float(np.mean(width))}
                print(f"{tag}: {name}: holds 0 in {c[0]}/{c[1]}, mean value {np.mean(vals):.3f}, mean width {np.mean(width):.3f}")
        if a.out:
            Path(a.out).write_text(json.dumps({"args": vars(a), "table": table, "pairs": res}, indent=1))
        return
    runs = load_runs([(a.scenario, "default", s) for s in seeds], a.duration, a.cache)
    every = run_lidar_samples([r["tracks"] for r in runs], runs[0]["truth"])
    pooled = {k: t.real for k, t in lidar_terms(every, every).items() if t.real is not None}  # type: ignore[arg-type]
    if a.terms_only:
        res = parallel_map(
            partial(score_terms, scenario=a.scenario, duration=a.duration, cache=a.cache, pooled=pooled), pairs, a.workers
        )
        took = f"runs {t1 - t0:.0f} s, scoring {time.perf_counter() - t1:.0f} s"
        print(f"{a.pairs} pairs of {a.scenario} ({a.duration:g} s): {took}")
        table = terms_table(res, pooled)
        if a.out:
            Path(a.out).write_text(json.dumps({"args": vars(a), "table": table, "pairs": res}, indent=1))
        return
    res = parallel_map(
        partial(score_one, scenario=a.scenario, duration=a.duration, cache=a.cache, pooled=pooled), pairs, a.workers
    )
    took = f"runs {t1 - t0:.0f} s, scoring {time.perf_counter() - t1:.0f} s"
    print(f"{a.pairs} pairs (1 against {a.model_runs} runs) of {a.scenario} ({a.duration:g} s): {took}")
    print("| lidar term | pooled value | difference covers 0 | A covers pooled |")
    table: dict[str, Any] = {"signed": {}, "distance": {}}
    for k, v in pooled.items():
        d, p = (
            share([r["signed"].get(k, {}).get("diff_covers_0") for r in res]),
            share([r["signed"].get(k, {}).get("a_covers_pooled") for r in res]),
        )
        table["signed"][k] = {"pooled": v, "diff_covers_0": d, "a_covers_pooled": p}
        print(f"| {k} | {v:.4g} | {d[0]}/{d[1]} | {p[0]}/{p[1]} |")
    for _, _, tag in VARIANTS[min(a.model_runs, 2)]:
        names = sorted({k for r in res for k in r["distance"][tag]})
        for k in names:
            c = share([r["distance"][tag].get(k, {}).get("covers_0") for r in res])
            vals = [r["distance"][tag][k]["value"] for r in res if k in r["distance"][tag]]
            table["distance"].setdefault(tag, {})[k] = {"covers_0": c, "mean": float(np.mean(vals))}
            print(f"{tag}: {k}: interval holds 0 in {c[0]}/{c[1]}, mean value {np.mean(vals):.3f}")
    ft = {w: [r["false_tracks"][w] for r in res if r["false_tracks"].get(w) is not None] for w in ("new", "former")}
    for w, v in ft.items():
        if v:
            print(
                f"false-track term ({w}): min {min(v):.3f}, max {max(v):.3f}, mean {np.mean(v):.3f}, sd {np.std(v, ddof=1):.3f}"
            )
    if a.out:
        Path(a.out).write_text(json.dumps({"args": vars(a), "table": table, "false_tracks": ft, "pairs": res}, indent=1))


if __name__ == "__main__":
    main()
