"""A campaign's results: DIR/results.csv (one row per job, tuning and target) and DIR/campaign.json (grid, engine, timings).

The per-target columns come from one place, :func:`target_row`; "real" in their names is the
reference run (the stand-in for real data), "synthetic" the job's run.
"""

from __future__ import annotations

import csv
import io
import json
import platform
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from seatwin.campaign.engine import RunReport, write_atomic
from seatwin.campaign.grid import CampaignGrid

if TYPE_CHECKING:
    from seatwin.campaign.summary import SettingSummary
    from seatwin.evaluation.compare import Comparison, TargetComparison

RESULTS_CSV = "results.csv"
CAMPAIGN_JSON = "campaign.json"
JOB_COLUMNS: tuple[str, ...] = ("job_id", "scenario", "seed", "reference_seed")
TARGET_COLUMNS: tuple[str, ...] = (
    "tuning",
    "target",
    "score",
    "score_ci_low",
    "score_ci_high",
    "score_reason",
    "score_overall",
    "score_overall_ci_low",
    "score_overall_ci_high",
    "score_sensor",
    "score_sensor_ci_low",
    "score_sensor_ci_high",
    "ahed",
    "ahed_printed",
    "n_instants",
    "n_common",
    "n_only_real",
    "n_only_synthetic",
    "n_both_missing",
    "fraction_only_one",
    "anees_real",
    "anees_synthetic",
    "false_tracks_real",
    "false_tracks_synthetic",
)
"""What :func:`target_row` returns, in column order."""


SENSOR_PARTS = ("lidar_returns", "radar_sensor")
"""The score's sensor-level part by sensor (S7 for a lidar; the radar sensor score): what ranks *sensor models*
(docs/fidelity-score.md, evaluation 12), where S5 ranks whole pipelines."""


def target_row(t: TargetComparison, comparison: Comparison) -> dict[str, Any]:
    """The per-target columns of results.csv (:data:`TARGET_COLUMNS`) of one target of one comparison."""
    real, synth = comparison.real.false_tracks, comparison.synthetic.false_tracks
    overall = comparison.score and comparison.score.overall
    plots = comparison.score.plots if comparison.score else {}
    sensor = next((plots[k] for k in SENSOR_PARTS if k in plots and plots[k].value is not None), None)
    return {
        "tuning": comparison.tuning,
        "target": t.target,
        "score": t.score,
        "score_ci_low": t.score_ci_low,
        "score_ci_high": t.score_ci_high,
        "score_reason": t.score_reason,
        "score_overall": overall and overall.value,
        "score_overall_ci_low": overall and overall.ci_low,
        "score_overall_ci_high": overall and overall.ci_high,
        "score_sensor": sensor and sensor.value,
        "score_sensor_ci_low": sensor and sensor.ci_low,
        "score_sensor_ci_high": sensor and sensor.ci_high,
        "ahed": t.ahed,
        "ahed_printed": t.ahed_printed,
        "n_instants": t.n_instants,
        "n_common": t.n_common,
        "n_only_real": t.n_only_real,
        "n_only_synthetic": t.n_only_synthetic,
        "n_both_missing": t.n_both_missing,
        "fraction_only_one": t.fraction_only_one,
        "anees_real": t.anees_real,
        "anees_synthetic": t.anees_synthetic,
        "false_tracks_real": None if real is None else real.n_tracks,
        "false_tracks_synthetic": None if synth is None else synth.n_tracks,
    }


def comparison_rows(comparison: Comparison) -> list[dict[str, Any]]:
    """Every target's row of one comparison."""
    return [target_row(t, comparison) for t in comparison.targets]


@dataclass
class CampaignResult:
    """A finished campaign: its rows (as results.csv), the engine's report, and the files written."""

    grid: CampaignGrid
    report: RunReport
    columns: tuple[str, ...]
    rows: list[dict[str, Any]] = field(default_factory=list)
    csv_path: Path | None = None
    json_path: Path | None = None
    summary: list[SettingSummary] = field(default_factory=list)
    """Per scenario, setting and tuning: the score over seeds, coverage, false tracks (:mod:`.summary`)."""
    png_path: Path | None = None
    """DIR/campaign.png, the scores per setting; None when no score is defined."""

    @property
    def n_failed(self) -> int:
        return sum(not self.report.records[j.id].ok for j in self.grid.jobs)


def result_rows(grid: CampaignGrid, report: RunReport) -> tuple[tuple[str, ...], list[dict[str, Any]]]:
    """results.csv's columns and rows: per synthetic job (grid order) its rows, or one row with its error."""
    varied = grid.spec.varied
    columns = (*JOB_COLUMNS, *varied, *TARGET_COLUMNS, "error")
    rows = []
    for job in grid.synthetic_jobs:
        p = job.params
        head = {"job_id": job.id, "scenario": p["scenario"], "seed": p["seed"], "reference_seed": p["reference_seed"]}
        head.update({name: p["settings"][name] for name in varied})
        record = report.records[job.id]
        if not record.ok:
            rows.append({**head, "error": record.error})
            continue
        rows.extend({**head, **row, "error": None} for row in record.result["rows"])
    return columns, rows


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, list | dict):
        return json.dumps(value, separators=(",", ":"))
    return str(value)


def csv_text(columns: tuple[str, ...], rows: list[dict[str, Any]]) -> str:
    """results.csv: empty cells for None, floats in full (``repr``), lists as JSON."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    writer.writerows([_cell(row.get(c)) for c in columns] for row in rows)
    return buf.getvalue()


def _versions(report: RunReport) -> dict[str, str | None]:
    import numpy as np

    from seatwin import __version__

    return {"seatwin": __version__, "python": platform.python_version(), "numpy": np.__version__, "ray": report.ray_version}


def _timings(grid: CampaignGrid, report: RunReport) -> dict[str, Any]:
    """Per-job and total times: the job function's own seconds per kind, and the run's wall time."""
    out: dict[str, Any] = {"wall_s": report.wall_s}
    for kind, jobs in (("reference", grid.reference_jobs), ("synthetic", grid.synthetic_jobs)):
        recs = [report.records[j.id] for j in jobs if report.records[j.id].ok]
        times, cpu = [r.elapsed_s for r in recs], [r.cpu_s for r in recs]
        out[kind] = {
            "n": len(recs),
            "total_s": float(sum(times)),
            "mean_s": float(sum(times) / len(times)) if times else None,
            "max_s": float(max(times)) if times else None,
            "cpu_total_s": float(sum(cpu)),
            "cpu_mean_s": float(sum(cpu) / len(cpu)) if cpu else None,
        }
    return out


def campaign_json(grid: CampaignGrid, report: RunReport, n_rows: int) -> dict[str, Any]:
    """campaign.json: the engine and how it ran, the grid, the timings, the versions, and every job's outcome."""
    jobs = []
    for job in grid.jobs:
        r = report.records[job.id]
        p = job.params
        entry = {
            "id": job.id,
            "kind": p["kind"],
            "scenario": p["scenario"],
            "seed": p["seed"],
            "settings": p["settings"],
            "status": "ok" if r.ok else "failed",
            "cached": r.cached,
            "elapsed_s": r.elapsed_s,
            "cpu_s": r.cpu_s,
            "host": r.host,
            "error": r.error,
        }
        if job.needs:
            entry["needs"] = list(job.needs)
        if r.ok and isinstance(r.result, dict) and "timings" in r.result:
            entry["timings"] = r.result["timings"]
        jobs.append(entry)
    run = report.describe()
    return {
        "engine": run.pop("engine"),
        "run": run,
        "grid": grid.describe(),
        "rows": n_rows,
        "failed": sum(not report.records[j.id].ok for j in grid.jobs),
        "timings": _timings(grid, report),
        "versions": _versions(report),
        "jobs": jobs,
    }


def write_results(out_dir: str | Path, grid: CampaignGrid, report: RunReport) -> CampaignResult:
    """Write DIR/results.csv and DIR/campaign.json (each atomically); the result with its rows."""
    out_dir = Path(out_dir)
    columns, rows = result_rows(grid, report)
    result = CampaignResult(grid, report, columns, rows, out_dir / RESULTS_CSV, out_dir / CAMPAIGN_JSON)
    for path, text in (
        (result.csv_path, csv_text(columns, rows)),
        (result.json_path, json.dumps(campaign_json(grid, report, len(rows)), indent=1)),
    ):
        write_atomic(path, text)
    return result
