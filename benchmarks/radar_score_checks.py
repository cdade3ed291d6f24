"""Issue 22's checks of the radar sensor score by simulation (docs/fidelity-score.md, *Evaluations of issue 22*).

    .venv/bin/python benchmarks/radar_score_checks.py calibration [PAIRS] [SCANS] [WORKERS] [DRIFTING_PAIRS] [BUDGET_S.] \
        [SEED0] [DESIGN_OFF_TOO] [PD_DRIFT] [BATCH_FLOOR_TOO]
    .venv/bin/python benchmarks/radar_score_checks.py controlled [RECORDINGS] [SCANS] [WORKERS] [BUDGET_S.] [FIRST] \
        [BATCH_FLOOR]
    .venv/bin/python benchmarks/radar_score_checks.py power [PAIRS] [SCANS] [WORKERS]

* ``calibration`` (default 50 pairs of 238 scans): the coverage of every signed plot-level term's 95 % interval
  over pairs of recordings of one known model, as ``plot_terms_calibration.py`` measures it, plain and with a
  drifting bearing offset (AR(1), φ 0.9, stationary σ 0.3°) — the autocorrelated case; seeds from SEED0 (1000);
  DESIGN_OFF_TOO 1: the plain pairs also with the detection terms' design-adjusted memory off; PD_DRIFT 1: the
  plain recordings' Pd drifts in time (``PD_DRIFT``); BATCH_FLOOR_TOO 1: the plain pairs also with the detection
  terms' batch-means floor on;
* ``controlled`` (default 40 recordings of 238 scans, indices from FIRST, default 0): parameters drawn at random
  per recording, the true model against 10 wrong ones ranked by the radar sensor score; how often the true model is
  first, and how often bearing bias +1°, σ_r × 2, σ_θ × 2 and Pd cap ∓ 0.2 are resolved; BATCH_FLOOR 1: with the
  detection terms' batch-means floor (``ScoreOptions.batch_floor``);
* ``power`` (default 20 pairs at 1×, 2×, 4× of 238 scans): the minimum detectable difference per term.

Each prints a table and, on its last line, its figures as JSON. Radar-only (no tracker): a recording is the
replica's plots on the orbit scene (:func:`seatwin.fidelity.synthetic.orbit_dataset`).
"""

from __future__ import annotations

import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace
from typing import Any

import numpy as np

from seatwin.evaluation.plot_terms import RadarPlotSample, radar_plot_terms
from seatwin.evaluation.score import ScoreOptions
from seatwin.fidelity.controlled import RESOLVE, SYNTHETIC_SEEDS, Scene, controlled_recording, orbit_sample
from seatwin.sensors.radar.config import RadarConfig

KNOWN = RadarConfig(
    noise={"range_sigma_m": 6.0, "range_bias_m": 0.0, "bearing_sigma_deg": 0.6, "bearing_bias_deg": -1.0},
    clutter={"kind": "uniform", "density_per_km2": 1.0},
    detection={"snr_ref_db": 15.0, "pd_max": 0.85},
    max_range_m=1000.0,
)
"""The known model of the calibration and power checks (plot_terms_calibration.py's)."""
AREA_KM2 = float(np.pi * (KNOWN.max_range_m**2 - KNOWN.min_range_m**2) / 1e6)
PD_DRIFT = (0.98, 0.3)
"""Evaluation 10's Pd drift: AR(1) φ 0.98 (≈ 50-scan spells), detections kept with a factor in [0.7, 1]."""


def _sample_args(args: tuple) -> RadarPlotSample:
    return orbit_sample(*args)


# --- calibration -------------------------------------------------------------------------------------------------


def _coverage(reps: list[RadarPlotSample], pairs: int, opts: ScoreOptions) -> dict[str, dict[str, float]]:
    pooled = radar_plot_terms(reps, reps, AREA_KM2, ScoreOptions(n_boot=1))
    names = [k for k, v in pooled.items() if v.real is not None]
    out: dict[str, dict[str, float]] = {k: {"diff": 0.0, "side": 0.0, "blocks": 0.0, "n": 0.0} for k in names}
    for p in range(pairs):
        terms = radar_plot_terms([reps[2 * p]], [reps[2 * p + 1]], AREA_KM2, opts)
        for k in names:
            t = terms[k]
            if t.difference_ci is None:
                continue
            out[k]["n"] += 1
            out[k]["diff"] += int(t.difference_ci[0] <= 0.0 <= t.difference_ci[1])
            out[k]["side"] += int(t.real_ci[0] <= pooled[k].real <= t.real_ci[1])
            out[k]["blocks"] += t.block
    return {
        k: {
            "pooled": float(pooled[k].real),
            "difference_covers_0": v["diff"] / v["n"],
            "a_covers_pooled": v["side"] / v["n"],
            "mean_block": v["blocks"] / v["n"],
            "pairs": v["n"],
        }  # fmt: skip
        for k, v in out.items()
        if v["n"]
    }


def _collect(pool: ProcessPoolExecutor, fn: Any, jobs: list, budget_s: float, t0: float) -> list:
    """``fn`` over ``jobs`` in order until ``budget_s`` seconds have passed since ``t0`` (the rest is dropped)."""
    futures = [pool.submit(fn, j) for j in jobs]
    out = []
    for f in futures:
        left = budget_s - (time.perf_counter() - t0)
        if left <= 0:
            break
        try:
            out.append(f.result(timeout=left))
        except TimeoutError:
            break
    _stop(pool)
    return out


def _stop(pool: ProcessPoolExecutor) -> None:
    """Drop the pool's pending jobs and end its workers now (a budget ran out: nothing more is waited for)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())
    for proc in procs:
        proc.terminate()
    pool.shutdown(wait=False, cancel_futures=True)


def calibration(
    pairs: int = 50,
    scans: int = 238,
    workers: int = 2,
    drift_pairs: int | None = None,
    budget_s: float = 1e9,
    seed0: int = 1000,
    design_off_too: int = 0,
    pd_drift: int = 0,
    batch_floor_too: int = 0,
) -> dict[str, Any]:
    """The coverage check on recordings seeded from ``seed0``; with ``budget_s``, only the recordings simulated within
    it (plain first) are used; ``design_off_too``: the plain pairs also with the detection terms' design-adjusted
    memory off (``plain_design_off``), on the same recordings; ``pd_drift``: the "plain" recordings' Pd drifts in
    time (``orbit_sample(pd_drift=PD_DRIFT)``; fidelity-score.md, evaluation 10); ``batch_floor_too``: the plain
    pairs also with the detection terms' batch-means floor on (``plain_batch_floor``; evaluation 11)."""
    t0 = time.perf_counter()
    opts = ScoreOptions(n_boot=400, seed=0, batch_floor=False)  # the documented runs' setting; the floor: batch_floor_too
    seeds = range(seed0, seed0 + 2 * pairs)
    n_drift = pairs if drift_pairs is None else drift_pairs
    plain_drift = (Scene(), False, PD_DRIFT) if pd_drift else ()
    jobs = [(KNOWN, scans, s, *plain_drift) for s in seeds] + [(KNOWN, scans, s, Scene(), True) for s in seeds[: 2 * n_drift]]
    with ProcessPoolExecutor(workers) as pool:
        got = _collect(pool, _sample_args, jobs, budget_s, t0)
    plain, drift = got[: 2 * pairs], got[2 * pairs :]
    pairs, n_drift = len(plain) // 2, len(drift) // 2
    out: dict[str, Any] = {"pairs": pairs, "drift_pairs": n_drift, "scans": scans, "n_boot": opts.n_boot, "seed0": seed0}
    runs = [("plain", plain, pairs, opts), ("drifting", drift, n_drift, opts)]
    if design_off_too:
        runs.insert(1, ("plain_design_off", plain, pairs, replace(opts, design_memory=False)))
    if batch_floor_too:
        runs.insert(1, ("plain_batch_floor", plain, pairs, replace(opts, batch_floor=True)))
    for label, reps, n_pairs, o in runs:
        if not n_pairs:
            continue
        cov = _coverage(reps, n_pairs, o)
        out[label] = cov
        print(f"{label}: {n_pairs} pairs of {scans}-scan recordings of one model; nominal 95 %")
        print(f"{'term':<22} {'pooled':>9} {'diff covers 0':>14} {'A covers pooled':>16} {'mean block':>11} {'pairs':>6}")
        for k, v in cov.items():
            print(
                f"{k:<22} {v['pooled']:>9.4g} {v['difference_covers_0']:>14.0%} {v['a_covers_pooled']:>16.0%} "
                f"{v['mean_block']:>11.1f} {v['pairs']:>6.0f}"
            )
    out["seconds"] = round(time.perf_counter() - t0, 1)
    print(json.dumps(out))
    return out


# --- controlled ranking and resolution ---------------------------------------------------------------------------


def controlled(
    recordings: int = 40, scans: int = 238, workers: int = 2, budget_s: float = 1e9, first: int = 0, batch_floor: int = 0
) -> dict[str, Any]:
    """The controlled check of recordings ``first`` … ``first + recordings − 1``; with ``budget_s``, only the
    recordings done within it (in index order) count; ``batch_floor``: with the detection terms' batch-means floor."""
    t0 = time.perf_counter()
    rows = []
    with ProcessPoolExecutor(workers) as pool:
        futures = [
            pool.submit(controlled_recording, i, scans, batch_floor=bool(batch_floor)) for i in range(first, first + recordings)
        ]
        for f in futures:
            left = budget_s - (time.perf_counter() - t0)
            if left <= 0:
                break
            try:
                rows.append(f.result(timeout=left))
            except TimeoutError:
                break
            print(json.dumps({"row": rows[-1]}), flush=True)
        _stop(pool)
    recordings = len(rows)
    if not recordings:
        print("no recording finished within the budget")
        return {"recordings": 0}
    n_first = sum(r["true_first"] for r in rows)
    print(f"{recordings} recordings of {scans} scans, parameters drawn at random; 11 candidate models, {SYNTHETIC_SEEDS} seeds")
    print(f"true model first in {n_first} of {recordings} ({n_first / recordings:.0%})")
    for r in rows:
        if not r["true_first"]:
            print(f"  recording {r['index']}: true model ranked {r['rank_of_true']}, first {r['runner_up']}; true {r['true']}")
    out: dict[str, Any] = {"recordings": recordings, "scans": scans, "true_first": n_first / recordings, "resolution": {}}
    print(f"{'wrong model':<18} {'term intervals disjoint':>24} {'score intervals disjoint':>25} {'score lead resolved':>20}")
    for label in RESOLVE:
        kinds = ("term_disjoint", "score_disjoint", "lead_resolved")
        share = {k: sum(r["resolved"][label][k] for r in rows) / recordings for k in kinds}
        out["resolution"][label] = share
        bin_note = ""
        if "busiest_bin_disjoint" in rows[0]["resolved"][label]:
            share["busiest_bin_disjoint"] = sum(r["resolved"][label]["busiest_bin_disjoint"] for r in rows) / recordings
            bin_note = f"   (first protocol's term, the busiest range bin: {share['busiest_bin_disjoint']:.0%})"
        print(
            f"{label:<18} {share['term_disjoint']:>24.0%} {share['score_disjoint']:>25.0%} {share['lead_resolved']:>20.0%}"
            + bin_note
        )
    out["rows"] = rows
    out["seconds"] = round(time.perf_counter() - t0, 1)
    print(json.dumps({k: v for k, v in out.items() if k != "rows"}))
    return out


# --- power -------------------------------------------------------------------------------------------------------

POWER_TERMS = {
    "bearing_bias": ("°", 1.0),
    "range_bias": ("m", 1.0),
    "bearing_sigma": ("× σ_θ", 1.0 / KNOWN.noise.bearing_sigma_deg),
    "range_sigma": ("× σ_r", 1.0 / KNOWN.noise.range_sigma_m),
    "pd_250_500m": ("", 1.0),
    "pd_all": ("", 1.0),
    "clutter_per_scan": ("× rate", None),
}
"""The terms of the power check, their parameter unit and the factor from the term's unit to it (None: relative to the
pooled value)."""


def power_pair(args: tuple[int, int]) -> dict[str, float]:
    """Each term's minimum detectable difference (``SignedTerm.detectable``) for one same-model pair at ``scans`` scans."""
    scans, p = args
    base = 3_000_000 + 1000 * p + scans
    real = [orbit_sample(KNOWN, scans, base)]
    synth = [orbit_sample(KNOWN, scans, base + 1 + s) for s in range(SYNTHETIC_SEEDS)]
    terms = radar_plot_terms(real, synth, AREA_KM2, ScoreOptions(n_boot=300, seed=p))
    out = {}
    for k in POWER_TERMS:
        d = terms[k].detectable
        out[k] = float("nan") if d is None else d
        out[k + "/value"] = float(terms[k].real) if terms[k].real is not None else float("nan")
    return out


def power(pairs: int = 20, scans: int = 238, workers: int = 2) -> dict[str, Any]:
    t0 = time.perf_counter()
    lengths = [scans, 2 * scans, 4 * scans]
    mdd: dict[str, dict[int, float]] = {k: {} for k in POWER_TERMS}
    with ProcessPoolExecutor(workers) as pool:
        for n in lengths:
            rows = list(pool.map(power_pair, [(n, p) for p in range(pairs)]))
            for k, (_, f) in POWER_TERMS.items():
                scale = f if f is not None else 1.0 / float(np.nanmean([r[k + "/value"] for r in rows]))
                mdd[k][n] = float(np.nanmean([r[k] for r in rows])) * scale
    print(f"Minimum detectable difference (95 % two-sided, 80 % power), {pairs} same-model pairs per length; "
          f"real 1 recording, model {SYNTHETIC_SEEDS} seeds")  # fmt: skip
    print(f"{'term':<18} {'unit':<8} " + " ".join(f"{n:>10d}" for n in lengths) + f" {'1×/4×':>7} {'length that halves it':>22}")
    out: dict[str, Any] = {"pairs": pairs, "lengths": lengths, "mdd": {}}
    for k, (unit, _) in POWER_TERMS.items():
        m = [mdd[k][n] for n in lengths]
        slope = float(np.polyfit(np.log(lengths), np.log(m), 1)[0])  # MDD ∝ length^slope
        halves = float(2.0 ** (-1.0 / slope)) if slope < 0 else float("inf")
        out["mdd"][k] = {"unit": unit, **{str(n): v for n, v in zip(lengths, m)}, "exponent": slope, "halving_factor": halves}
        print(f"{k:<18} {unit:<8} " + " ".join(f"{v:>10.3g}" for v in m) + f" {m[0] / m[2]:>7.2f} {halves:>20.1f} ×")
    out["seconds"] = round(time.perf_counter() - t0, 1)
    print(json.dumps(out))
    return out


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "calibration"
    fn = {"calibration": calibration, "controlled": controlled, "power": power}[what]
    fn(*(float(a) if "." in a else int(a) for a in sys.argv[2:11]))
