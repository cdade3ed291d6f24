"""Tracks in the real harbour: quay ghosts, tracks on land, impossible speeds, and the don't-care rule (issue 21).

    .venv/bin/python benchmarks/harbour_tracks.py [--duration S] [--data ../shared/data] [--ravnkloa-only]

Part 1, the four Gemini scenarios (``gemini-scenarios/Scenario{3..6}.csv``, whole, or the first
``--duration`` seconds of each): each is simulated in its own harbour (Ravnkloa raster) with lidar
only and with radar only (``seatwin simulate S.csv --sensors lidar|radar``), tracked with the
recording's default tuning and mask (``seatwin track RUN``) and evaluated against the scenario's
truth (``seatwin evaluate``, 10 m). Per scenario and sensor:

* ``confirmed``: distinct confirmed tracks;
* ``false`` / ``false_per_min``: confirmed tracks never associated with a target (tracks of nothing),
  and per simulated minute; ``moored``: confirmed tracks of the harbour's moored boats (real objects without
  ground truth: don't-care, not false; :func:`seatwin.evaluation.evaluate.false_tracks`);
* ``land_any`` / ``land_20``: confirmed tracks with any / at least 20 % of their confirmed rows on
  land (the run's water mask, not dilated);
* ``fast``: confirmed tracks faster than the tuning's v_max + speed_gate_margin for more than 3
  consecutive scans of their confirmed life;
* ``coverage``: each target's share of instants with a confirmed track within 10 m (mean over targets).

Part 2, the eight Ravnkloa shore-radar recordings (``ravnkloa/radar-2023/*.csv``, imported with the
base map): confirmed tracks with more than 20 % of their rows on land (default tuning ``ravnkloa``),
and the vessels that the don't-care rule :func:`seatwin.fidelity.joyride.untruthed_vessels` accepts
(no target: every confirmed track is off-target) with the ``joyride`` tuning that the fidelity method
uses and with the default tuning, with and without a single-scan jump > 50 m, and when every confirmed
track is made to jump 150 m once (half-way through its confirmed life).

Prints a table and, on its last line, JSON.
"""

from __future__ import annotations

import argparse
import json
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ("Scenario3", "Scenario4", "Scenario5", "Scenario6")
JUMP_M = 50.0
INJECTED_JUMP_M = 150.0


def _runs(mask: np.ndarray) -> int:
    """Longest run of True in ``mask``."""
    best = cur = 0
    for v in mask:
        cur = cur + 1 if v else 0
        best = max(best, cur)
    return best


def track_figures(tracks: Any, mask: Any, v_limit: float) -> dict[str, int]:
    """Confirmed tracks on land (any / ≥ 20 % of rows) and faster than ``v_limit`` for > 3 consecutive scans."""
    conf = tracks.confirmed
    ids = np.unique(tracks.track_id[conf])
    land_any = land_20 = fast = 0
    for k in ids:
        m = conf & (tracks.track_id == k)
        s = tracks.state[m]
        land = ~np.asarray(mask.is_water(s[:, 0], s[:, 2]), bool)
        land_any += int(land.any())
        land_20 += int(land.mean() >= 0.2)
        fast += int(_runs(np.hypot(s[:, 1], s[:, 3]) > v_limit) > 3)
    return {"confirmed": int(len(ids)), "land_any": land_any, "land_20": land_20, "fast": fast}


def scenario_row(csv: Path, sensor: str, duration: float | None, tmp: Path) -> dict[str, Any]:
    from seatwin.pipeline import track_recording
    from seatwin.pipeline.evaluate import evaluate_run
    from seatwin.pipeline.simulate import simulate_run
    from seatwin.pipeline.track import recording_mask
    from seatwin.tracking import load_tuning

    run = tmp / f"{csv.stem}-{sensor}"
    res = simulate_run(csv, run, duration=duration, progress=False, sensors=(sensor,))
    tr = track_recording(run)
    mask = recording_mask(run)
    cfg = load_tuning(tr.tuning)
    ev = evaluate_run(tr.tracks, run)
    minutes = res.simulated_s / 60.0
    fig = track_figures(tr.tracks, mask, cfg.v_max + cfg.speed_gate_margin)
    cov = [s.coverage for s in ev.summaries if s.coverage is not None]
    n_false = ev.false_tracks.n_tracks if ev.false_tracks else 0
    return {
        "scenario": csv.stem,
        "sensor": sensor,
        "minutes": round(minutes, 2),
        **{k: fig[k] for k in ("confirmed",)},
        "false": n_false,
        "false_per_min": round(n_false / minutes, 2),
        "moored": ev.false_tracks.n_dont_care if ev.false_tracks else 0,
        **{k: fig[k] for k in ("land_any", "land_20", "fast")},
        "coverage": round(float(np.mean(cov)), 3) if cov else None,
        "coverage_by_target": {s.target: None if s.coverage is None else round(s.coverage, 3) for s in ev.summaries},
    }


def dont_care(tracks: Any) -> dict[str, int]:
    """Tracks the don't-care rule accepts as vessels (no target: every track is off-target); how many of them
    have a single-scan jump > 50 m; and how many it accepts when every track jumps 150 m once, half-way
    through its confirmed life (clutter re-attaching to another feature)."""
    import dataclasses

    from seatwin.fidelity.joyride import AWAY_M, JoyrideData, untruthed_vessels

    t = np.unique(tracks.time)
    data = JoyrideData(t, [np.empty((0, 2))] * len(t), np.full((len(t), 4), AWAY_M), np.zeros((len(t), 4)))
    vessels = untruthed_vessels(tracks, data, gate_m=60.0)
    jumpy = 0
    for rows in vessels.values():
        steps = np.hypot(np.diff(rows[:, 1]), np.diff(rows[:, 3]))
        jumpy += int(steps.size > 0 and steps.max() > JUMP_M)
    state = tracks.state.copy()
    for k in np.unique(tracks.track_id[tracks.confirmed]):
        rows = np.flatnonzero(tracks.confirmed & (tracks.track_id == k))
        state[rows[len(rows) // 2 :], 2] += INJECTED_JUMP_M
    injected = untruthed_vessels(dataclasses.replace(tracks, state=state), data, gate_m=60.0)
    return {
        "accepted": len(vessels),
        "accepted_with_jump": jumpy,
        "accepted_without_jump": len(vessels) - jumpy,
        "accepted_jump_injected": len(injected),
    }


def ravnkloa_row(csv: Path, base_map: Path, tmp: Path) -> dict[str, Any]:
    from seatwin.perception.datasets import import_ravnkloa_radar
    from seatwin.pipeline import track_recording
    from seatwin.pipeline.track import recording_mask
    from seatwin.tracking import load_tuning

    rd = tmp / csv.stem
    import_ravnkloa_radar(csv, rd, "mcap", map_path=str(base_map))
    mask = recording_mask(rd)
    tr = track_recording(rd)
    cfg = load_tuning(tr.tuning)
    fig = track_figures(tr.tracks, mask, cfg.v_max + cfg.speed_gate_margin)
    joy = track_recording(rd, tuning="joyride").tracks
    joy_cfg = load_tuning("joyride")
    joy_fig = track_figures(joy, mask, joy_cfg.v_max + joy_cfg.speed_gate_margin)
    return {
        "file": csv.stem,
        "tuning": tr.tuning,
        "confirmed": fig["confirmed"],
        "land_20": fig["land_20"],
        "land_any": fig["land_any"],
        "fast": fig["fast"],
        "joyride_land_20": joy_fig["land_20"],
        "joyride_fast": joy_fig["fast"],
        "dont_care_joyride": dont_care(joy),
        "dont_care_default": dont_care(tr.tracks),
    }


def main(data: Path, duration: float | None, skip_scenarios: bool = False) -> dict[str, Any]:
    out: dict[str, Any] = {"duration": duration, "scenarios": [], "ravnkloa": []}
    with tempfile.TemporaryDirectory() as tmp:
        if not skip_scenarios:
            for name in SCENARIOS:
                for sensor in ("lidar", "radar"):
                    row = scenario_row(data / "gemini-scenarios" / f"{name}.csv", sensor, duration, Path(tmp))
                    out["scenarios"].append(row)
                    print(" ".join(f"{k}={v}" for k, v in row.items() if k != "coverage_by_target"), flush=True)
        folder = data / "ravnkloa"
        for csv in sorted((folder / "radar-2023").glob("*.csv")):
            row = ravnkloa_row(csv, folder / "ravnkloa_radar_base_map.yaml", Path(tmp))
            out["ravnkloa"].append(row)
            print(" ".join(f"{k}={v}" for k, v in row.items()), flush=True)
    totals: dict[str, Any] = {}
    for sensor in ("lidar", "radar"):
        rows = [r for r in out["scenarios"] if r["sensor"] == sensor]
        if rows:
            minutes = sum(r["minutes"] for r in rows)
            totals[sensor] = {
                "minutes": round(minutes, 2),
                **{k: sum(r[k] for r in rows) for k in ("confirmed", "false", "moored", "land_any", "land_20", "fast")},
                "false_per_min": round(sum(r["false"] for r in rows) / minutes, 2),
            }
    rav = out["ravnkloa"]
    if rav:
        totals["ravnkloa"] = {
            "land_20": sum(r["land_20"] for r in rav),
            "fast": sum(r["fast"] for r in rav),
            "joyride_land_20": sum(r["joyride_land_20"] for r in rav),
            "joyride_fast": sum(r["joyride_fast"] for r in rav),
            **{
                f"{tun}_{k}": sum(r[f"dont_care_{tun}"][k] for r in rav)
                for tun in ("joyride", "default")
                for k in ("accepted", "accepted_with_jump", "accepted_jump_injected")
            },
        }
    out["totals"] = totals
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=ROOT.parent / "shared" / "data")
    ap.add_argument("--duration", type=float, default=None, help="simulate only the first S seconds of each scenario")
    ap.add_argument("--ravnkloa-only", action="store_true", help="only the Ravnkloa radar recordings")
    args = ap.parse_args()
    result = main(args.data, args.duration, args.ravnkloa_only)
    print("totals:", json.dumps(result["totals"]))
    print(json.dumps(result))
