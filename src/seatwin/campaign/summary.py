"""A campaign at a glance: per scenario, synthetic setting and tuning, the fidelity score over seeds, the targets'
coverage and the false tracks (what ``seatwin campaign`` prints), and the figure DIR/campaign.png."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

CAMPAIGN_PNG = "campaign.png"


@dataclass(frozen=True)
class SettingSummary:
    """One (scenario, setting, tuning) of a campaign over its seeds.

    ``score``: the mean over seeds of the overall fidelity score, ``score_min``/``score_max`` its spread over seeds
    (None where no seed's score is defined); ``coverage``: of the instants where either run tracked a target, the
    share where both did (common / (common + only one)), pooled over targets and seeds; ``false_tracks``: mean false
    tracks per run, synthetic and reference; ``failed``: jobs that failed."""

    scenario: str
    setting: str
    tuning: str
    seeds: int
    score: float | None
    score_min: float | None
    score_max: float | None
    coverage: float | None
    false_tracks_synthetic: float | None
    false_tracks_real: float | None
    failed: int


def _mean(values: list[Any]) -> float | None:
    defined = [float(v) for v in values if v is not None]
    return float(np.mean(defined)) if defined else None


def summarise_campaign(rows: list[dict[str, Any]], varied: tuple[str, ...]) -> list[SettingSummary]:
    """Group results.csv's ``rows`` (one per job, tuning and target; a failed job's row has ``error``) by scenario,
    the ``varied`` synthetic settings and tuning, in the rows' order."""

    def setting_of(row: dict[str, Any]) -> str:
        return ", ".join(f"{k} {row.get(k)}" for k in varied) or "(the synthetic settings)"

    groups: dict[tuple[str, str, str], list[dict[str, Any]]] = {}
    for row in rows:
        if not row.get("error"):
            groups.setdefault((str(row["scenario"]), setting_of(row), str(row.get("tuning") or "")), []).append(row)
    for row in rows:  # a failed job has one row, without tuning: it counts in each tuning of its setting
        if row.get("error"):
            same = [key for key in groups if key[:2] == (str(row["scenario"]), setting_of(row))]
            for key in same or [(str(row["scenario"]), setting_of(row), "")]:
                groups.setdefault(key, []).append(row)
    out = []
    for (scenario, setting, tuning), members in groups.items():
        ok = [r for r in members if not r.get("error")]
        jobs = {r["job_id"] for r in members}
        per_job: dict[str, dict[str, Any]] = {}
        for r in ok:  # the overall score and false tracks are per job (the same on each of its target rows)
            per_job.setdefault(r["job_id"], r)
        scores = [r["score_overall"] for r in per_job.values() if r.get("score_overall") is not None]
        common = sum(int(r.get("n_common") or 0) for r in ok)
        one = sum(int(r.get("n_only_real") or 0) + int(r.get("n_only_synthetic") or 0) for r in ok)
        out.append(
            SettingSummary(
                scenario,
                setting,
                tuning,
                len(jobs),
                _mean(scores),
                min(scores) if scores else None,
                max(scores) if scores else None,
                common / (common + one) if common + one else None,
                _mean([r.get("false_tracks_synthetic") for r in per_job.values()]),
                _mean([r.get("false_tracks_real") for r in per_job.values()]),
                len(jobs - set(per_job)),
            )
        )
    return out


def plot_campaign(summary: list[SettingSummary], path: str | Path, title: str = "Fidelity campaign") -> Path:
    """The mean fidelity score per setting (bars, one group per scenario) with its spread over seeds."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenarios = list(dict.fromkeys(s.scenario for s in summary))

    def label_of(s: SettingSummary) -> str:
        return f"{s.setting}, tuning {s.tuning}" if s.tuning else s.setting

    labels = list(dict.fromkeys(label_of(s) for s in summary))
    fig, ax = plt.subplots(figsize=(max(5.5, 1.6 * len(scenarios) * max(len(labels), 1) / 2 + 2), 4.2), layout="constrained")
    width = 0.8 / max(len(labels), 1)
    for j, label in enumerate(labels):
        xs, ys, lo, hi = [], [], [], []
        for i, scenario in enumerate(scenarios):
            s = next((s for s in summary if s.scenario == scenario and label_of(s) == label), None)
            if s is None or s.score is None or s.score_min is None or s.score_max is None:
                continue
            xs.append(i + (j - (len(labels) - 1) / 2) * width)
            ys.append(s.score)
            lo.append(s.score - s.score_min)
            hi.append(s.score_max - s.score)
        ax.bar(xs, ys, width, yerr=[lo, hi], capsize=3, label=label)
    ax.set_xticks(range(len(scenarios)), scenarios)
    ax.set_ylabel("fidelity score vs reference (mean, min–max over seeds)")
    ax.set_ylim(0, 1.05)
    ax.grid(alpha=0.3, axis="y")
    fig.legend(loc="outside lower center", ncols=min(len(labels), 2), fontsize=8)
    ax.set_title(title)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
