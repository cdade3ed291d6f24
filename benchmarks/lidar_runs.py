"""Shared by the lidar score benchmarks: simulate-and-track runs of built-in scenarios, cached, in parallel.

A run is (scenario, model, seed): the lidar only, a ``duration``-second window centred in the scenario, the
``synthetic`` tuning, the recording's own water mask (the built-in harbour). Runs are cached as pickles under
``--cache`` (keyed by every input), so the calibration and the ranking share them and a rerun is cheap. Results
never depend on ``--workers``: every run is a pure function of its key, and results are gathered in job order.
"""

from __future__ import annotations

import hashlib
import json
import pickle
import tempfile
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

MODELS: dict[str, dict[str, Any]] = {
    "default": {},
    "depthbuffer": {"lidar_mode": "depthbuffer"},
    "depthbuffer-legacy": {"lidar_mode": "depthbuffer-legacy"},
    "range_noise_0.1": {"range_noise": 0.1},
}
"""The candidate lidar models of issue 22 (SimulationSettings changes from the default VLP-16 ray caster)."""
TUNING = "synthetic"


def run_key(scenario: str, model: str, seed: int, duration: float) -> str:
    text = json.dumps([scenario, MODELS[model], seed, duration, TUNING, 2], sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def simulate_run(scenario: str, model: str, seed: int, duration: float, cache: str) -> dict[str, Any]:
    """Simulate and track one run (or read it from ``cache``): its tracks, evaluation and truth."""
    path = Path(cache) / f"{scenario}-{model}-{seed}-{duration:g}-{run_key(scenario, model, seed, duration)}.pkl"
    if path.exists():
        return pickle.loads(path.read_bytes())
    from seatwin.campaign.grid import window_offset
    from seatwin.evaluation import evaluate
    from seatwin.evaluation.truth import truth_from_scenario
    from seatwin.pipeline.track import recording_mask, track_recording
    from seatwin.scenario.load import load_scenario
    from seatwin.sim import simulate_scenario

    sc = load_scenario(scenario)
    offset = window_offset(sc.end - sc.start, duration, None, scenario)
    with tempfile.TemporaryDirectory(prefix="seatwin-lidarbench-") as tmp:
        rec = Path(tmp) / "run"
        simulate_scenario(
            sc, rec, start=sc.start + offset, duration=duration, progress=False, seed=seed, sensors=("lidar",), **MODELS[model]
        )
        tracks = track_recording(rec, tuning=TUNING).tracks
        mask = recording_mask(rec)
    tracks.source = f"{model} run of {scenario}, seed {seed}"
    truth = truth_from_scenario(sc)
    ev = evaluate(tracks, truth, mask=mask)
    out = {"tracks": tracks, "evaluation": ev, "truth": truth}
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp_path = path.with_suffix(".tmp")
    tmp_path.write_bytes(pickle.dumps(out))
    tmp_path.replace(path)
    return out


def _job(args: tuple[str, str, int, float, str]) -> str:
    simulate_run(*args)
    return "ok"


def ensure_runs(jobs: list[tuple[str, str, int]], duration: float, cache: str, workers: int) -> None:
    """Simulate every (scenario, model, seed) of ``jobs`` not yet in ``cache``, on ``workers`` processes."""
    todo = [(s, m, k, duration, cache) for s, m, k in dict.fromkeys(jobs)]
    if workers <= 1:
        for j in todo:
            _job(j)
        return
    with ProcessPoolExecutor(workers) as pool:
        list(pool.map(_job, todo))


def load_runs(jobs: list[tuple[str, str, int]], duration: float, cache: str) -> list[dict[str, Any]]:
    """The cached runs of ``jobs`` (simulated by :func:`ensure_runs`), in order."""
    return [simulate_run(s, m, k, duration, cache) for s, m, k in jobs]


def score_pair(
    real: list[dict[str, Any]], synthetic: list[dict[str, Any]], block: int | None = 10, run_spread: bool = True
) -> Any:
    """The fidelity score with the sensor terms (``score_runs_with_sensor_terms``) of ``synthetic`` against ``real`` runs
    (``run_spread``: ``ScoreOptions.run_spread``, the target terms' run-to-run spread when ≥ 2 synthetic runs)."""
    from seatwin.evaluation.score import ScoreOptions
    from seatwin.evaluation.sensor_score import score_runs_with_sensor_terms

    return score_runs_with_sensor_terms(
        [r["tracks"] for r in real],
        [s["tracks"] for s in synthetic],
        real[0]["truth"],
        [r["evaluation"] for r in real],
        [s["evaluation"] for s in synthetic],
        ScoreOptions(block=block, run_spread=run_spread),
    )


def parallel_map(fn: Any, items: list[Any], workers: int) -> list[Any]:
    """``[fn(x) for x in items]`` on ``workers`` processes (in order: the result never depends on ``workers``)."""
    if workers <= 1:
        return [fn(x) for x in items]
    with ProcessPoolExecutor(workers) as pool:
        return list(pool.map(fn, items))
