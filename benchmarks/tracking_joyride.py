"""Validation of the tracker on the real joyride radar dataset (docs/validation.md, tracking).

    .venv/bin/python benchmarks/tracking_joyride.py [../shared/data/joyride/joyride.mat]

1. :func:`seatwin.perception.datasets.import_joyride` → a recording;
   :func:`seatwin.pipeline.track_recording` with the radar and the ``joyride`` preset (not
   fitted to this file's ground truth) → tracks.
2. Metrics with :func:`seatwin.evaluation.evaluate` at association radii 10 m and 50 m:
   coverage, position/velocity RMSE, ANEES with χ² bounds, tracks, switches, false tracks.
3. Calibration: the radar's bearing bias is estimated on the first half of the scans only
   (median bearing error of the plot nearest the GNSS target position, plots within 100 m),
   the tracker is re-run with that bias removed, and the figures are given on the second half.

Prints a table and, on its last line, the figures as JSON.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import yaml

if TYPE_CHECKING:
    from seatwin.evaluation import Tracks, TruthSet

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_MAT = ROOT.parent / "shared" / "data" / "joyride" / "joyride.mat"


def calibrate_bearing_bias(mat: Path, fraction: float = 0.5, max_distance: float = 100.0) -> tuple[float, int]:
    """Median bearing error [rad] (measured − true) of the plot nearest the target, first ``fraction`` of scans."""
    from seatwin.perception.datasets import read_joyride

    ds = read_joyride(mat)
    tg, s = ds.targets["target"], ds.sensor
    errs = []
    for k in range(int(len(ds.time) * fraction)):
        p = ds.plots[k]
        if not len(p):
            continue
        d = np.hypot(p[:, 0] - tg[k, 0], p[:, 1] - tg[k, 2])
        i = int(np.argmin(d))
        if d[i] > max_distance:
            continue
        b_true = np.arctan2(tg[k, 2] - s[k, 2], tg[k, 0] - s[k, 0])
        b_meas = np.arctan2(p[i, 1] - s[k, 2], p[i, 0] - s[k, 0])
        errs.append(np.angle(np.exp(1j * (b_meas - b_true))))
    return float(np.median(errs)), len(errs)


def metrics(tracks: Tracks, truth: TruthSet, gate: float, t_from: float | None = None) -> dict:
    """Figures of one run at one association radius (optionally only instants ≥ ``t_from``)."""
    from seatwin.evaluation import evaluate

    if t_from is not None:
        keep = tracks.time >= t_from
        tracks = type(tracks)(
            tracks.time[keep],
            tracks.track_id[keep],
            tracks.existence[keep],
            tracks.state[keep],
            tracks.covariance[keep],
            tracks.confirmed[keep],
            scan_times=tracks.scan_times[tracks.scan_times >= t_from],
            source=tracks.source,
        )
    ev = evaluate(tracks, truth, gate=gate)
    s = ev.summaries[0]
    confirmed = sorted({int(i) for i in tracks.track_id[tracks.confirmed]})
    on_target = set(s.track_ids)
    return {
        "gate_m": gate,
        "scans": s.n_instants,
        "coverage": s.coverage,
        "rmse_position_m": s.rmse_position,
        "rmse_velocity_mps": s.rmse_velocity,
        "anees": s.anees,
        "anees_bounds": [s.anees_lower, s.anees_upper],
        "confirmed_tracks": len(confirmed),
        "target_tracks": len(on_target),
        "track_switches": s.track_switches,
        "false_tracks": len([i for i in confirmed if i not in on_target]),
    }


def main(mat: Path) -> dict:
    from seatwin.evaluation import load_truth
    from seatwin.perception.datasets import import_joyride
    from seatwin.pipeline import track_recording

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        rd = tmp / "joyride_run"
        import_joyride(mat, rd)
        truth = load_truth(str(rd))
        base = track_recording(rd, sensors=("radar",), tuning="joyride").tracks
        t = base.scan_times
        t_half = float(t[len(t) // 2])
        bias, n_cal = calibrate_bearing_bias(mat)
        tuning = tmp / "joyride_calibrated.yaml"
        tuning.write_text(
            yaml.safe_dump({"base": "joyride", "name": "joyride+bias", "sensors": {"radar": {"bearing_bias": bias}}})
        )
        cal = track_recording(rd, sensors=("radar",), tuning=str(tuning)).tracks
        result = {
            "uncalibrated_full": [metrics(base, truth, g) for g in (10.0, 50.0)],
            "uncalibrated_second_half": [metrics(base, truth, g, t_half) for g in (10.0, 50.0)],
            "calibrated_second_half": [metrics(cal, truth, g, t_half) for g in (10.0, 50.0)],
            "bearing_bias_deg": float(np.degrees(bias)),
            "calibration_plots": n_cal,
            "second_half_from": t_half,
        }
    return result


def _table(result: dict) -> str:
    keys = [
        "coverage",
        "rmse_position_m",
        "rmse_velocity_mps",
        "anees",
        "anees_bounds",
        "confirmed_tracks",
        "target_tracks",
        "track_switches",
        "false_tracks",
        "scans",
    ]
    lines = []
    for name in ("uncalibrated_full", "uncalibrated_second_half", "calibrated_second_half"):
        for m in result[name]:
            cells = []
            for k in keys:
                v = m[k]
                if isinstance(v, list):
                    cells.append(f"{k}=[{v[0]:.2f},{v[1]:.2f}]" if v[0] is not None else f"{k}=-")
                elif isinstance(v, float):
                    cells.append(f"{k}={v:.3f}")
                else:
                    cells.append(f"{k}={v}")
            lines.append(f"{name:26s} r={m['gate_m']:>4.0f} m  " + "  ".join(cells))
    return "\n".join(lines)


if __name__ == "__main__":
    mat = Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_MAT
    if not mat.is_file():
        raise SystemExit(f"{mat}: joyride.mat not found (it lives in ../shared/data/joyride)")
    res = main(mat)
    print(_table(res))
    print(f"bearing bias (first half, {res['calibration_plots']} plots): {res['bearing_bias_deg']:.3f} deg")
    print(json.dumps(res))
