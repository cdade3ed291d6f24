"""Sweep results: one row per (kind, strength, seed), the per-strength spread, Spearman ρ per kind, CSV/JSON."""

from __future__ import annotations

import csv
import json
import math
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from seatwin.sweep.degradations import degradation
from seatwin.sweep.settings import SweepSettings

REFERENCE_KIND = "reference"
METRICS = ("score", "sensor", "ahed")
"""S5; the sensor-level part (S7 for a lidar), which ranks sensor models (fidelity-score.md, evaluation 12); AHED."""
CSV_FIELDS = (
    "kind",
    "strength",
    "seed",
    "reference_seed",
    "score",
    "score_ci_low",
    "score_ci_high",
    "ahed",
    "n_common",
    "fraction_only_one",
    "targets_with_ahed",
    "sensor",
    "sensor_ci_low",
    "sensor_ci_high",
)


@dataclass(frozen=True)
class SweepRow:
    """One copy (or the reference model) compared with the reference run of another seed.

    ``score``: the overall fidelity score (S5) with its bootstrap interval; ``sensor``: its sensor-level part
    (S7, the lidar's own outputs against the truth) with its interval; ``ahed`` the mean over targets of AHED
    (5.34); ``None`` where undefined. ``fraction_only_one`` is the mean over
    targets of the share of instants only one dataset tracked the target (what AHED cannot see).
    """

    kind: str
    strength: float
    seed: int
    reference_seed: int
    score: float | None
    score_ci_low: float | None
    score_ci_high: float | None
    ahed: float | None
    n_common: int
    fraction_only_one: float | None
    targets_with_ahed: int
    sensor: float | None = None
    sensor_ci_low: float | None = None
    sensor_ci_high: float | None = None

    def value(self, metric: str) -> float | None:
        if metric not in METRICS:
            raise ValueError(f"unknown sweep metric {metric!r}: expected one of {', '.join(METRICS)}")
        return getattr(self, metric)


@dataclass(frozen=True)
class StrengthSummary:
    """A metric over the seeds at one strength: mean, min, max, standard deviation, and how many seeds had one."""

    strength: float
    n_seeds: int
    n_defined: int
    mean: float | None
    min: float | None
    max: float | None
    std: float | None
    fraction_only_one_mean: float | None


@dataclass(frozen=True)
class KindSpearman:
    """Spearman ρ of the distance from the reference, ``|strength − reference|``, against a metric, for one
    kind in one direction (``degraded`` or ``cleaner``), the reference model's points included.

    ``rho_points``: over every seed's points; ``rho_means``: over the per-strength means;
    ``rho_per_seed``: each seed on its own (two points give ±1), with its band ``seed_min``–``seed_max``.
    None where undefined; a point without a value is left out.
    """

    metric: str
    direction: str
    rho_points: float | None
    rho_means: float | None
    rho_per_seed: dict[int, float | None]
    seed_min: float | None
    seed_max: float | None


@dataclass
class SweepResult:
    """Everything a sweep measured, with the settings that produced it (``offset`` resolved)."""

    settings: SweepSettings
    rows: list[SweepRow] = field(default_factory=list)

    def kind_rows(self, kind: str, with_reference: bool = True) -> list[SweepRow]:
        """The rows of ``kind`` (and the reference model's points placed at the kind's reference value)."""
        out = [r for r in self.rows if r.kind == kind]
        if with_reference:
            ref = degradation(kind).reference
            out = [replace(r, kind=REFERENCE_KIND, strength=ref) for r in self.rows if r.kind == REFERENCE_KIND] + out
        return out

    @property
    def kinds(self) -> list[str]:
        return list(self.settings.kinds)

    def floor(self, metric: str = "score") -> list[float]:
        """The reference model against the reference run of another seed: what independent draws alone give."""
        return [v for r in self.rows if r.kind == REFERENCE_KIND and (v := r.value(metric)) is not None]

    def to_json(self) -> dict[str, Any]:
        """The ``sweep.json`` document: settings, rows, per-kind summaries and ρ per metric and direction, the floor."""
        return {
            "settings": self.settings.describe(),
            "rows": [asdict(r) for r in self.rows],
            "summary": {m: {k: [asdict(s) for s in summarise(self.kind_rows(k), m)] for k in self.kinds} for m in METRICS},
            "spearman": {
                m: {k: {d: asdict(r) for d, r in by_dir.items()} for k, by_dir in spearman_by_kind(self, m).items()}
                for m in METRICS
            },
            "floor": {m: {"values": self.floor(m), "mean": _mean(self.floor(m))} for m in METRICS},
        }


def _mean(v: list[float]) -> float | None:
    return float(np.mean(v)) if v else None


def summarise(rows: list[SweepRow], metric: str = "score") -> list[StrengthSummary]:
    """Per strength (ascending): the spread of ``metric`` over seeds."""
    out = []
    for s in sorted({r.strength for r in rows}):
        v = np.array([x for r in rows if r.strength == s and (x := r.value(metric)) is not None], dtype=float)
        frac = [r.fraction_only_one for r in rows if r.strength == s and r.fraction_only_one is not None]
        out.append(
            StrengthSummary(
                s,
                sum(1 for r in rows if r.strength == s),
                int(v.size),
                float(v.mean()) if v.size else None,
                float(v.min()) if v.size else None,
                float(v.max()) if v.size else None,
                float(v.std(ddof=1)) if v.size > 1 else None,
                float(np.mean(frac)) if frac else None,
            )
        )
    return out


def _rho(x: list[float], y: list[float]) -> float | None:
    from scipy.stats import spearmanr

    if len(x) < 2 or len(set(x)) < 2 or len(set(y)) < 2:
        return None
    value = float(spearmanr(x, y).statistic)
    return value if math.isfinite(value) else None


def spearman_by_kind(result: SweepResult, metric: str = "score") -> dict[str, dict[str, KindSpearman]]:
    """Per kind and direction (``degraded``, and ``cleaner`` where swept): ρ of distance from the reference
    against ``metric`` (:class:`KindSpearman`)."""
    out: dict[str, dict[str, KindSpearman]] = {}
    for kind in result.kinds:
        d = degradation(kind)
        rows = [r for r in result.kind_rows(kind) if r.value(metric) is not None]
        out[kind] = {}
        for direction in ("degraded", "cleaner"):
            sel = [r for r in rows if r.kind == REFERENCE_KIND or d.direction(r.strength) == direction]
            if not any(r.kind != REFERENCE_KIND for r in sel):
                continue
            per_seed = {
                seed: _rho(
                    [abs(r.strength - d.reference) for r in sel if r.seed == seed],
                    [r.value(metric) for r in sel if r.seed == seed],
                )
                for seed in sorted({r.seed for r in sel})
            }
            summary = [s for s in summarise(sel, metric) if s.mean is not None]
            defined = [v for v in per_seed.values() if v is not None]
            out[kind][direction] = KindSpearman(
                metric,
                direction,
                _rho([abs(r.strength - d.reference) for r in sel], [r.value(metric) for r in sel]),
                _rho([abs(s.strength - d.reference) for s in summary], [s.mean for s in summary]),
                per_seed,
                min(defined) if defined else None,
                max(defined) if defined else None,
            )
    return out


def write_results(out_dir: str | Path, result: SweepResult) -> tuple[Path, Path]:
    """Write ``sweep.csv`` (one line per row) and ``sweep.json`` (:meth:`SweepResult.to_json`) into ``out_dir``."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    csv_path, json_path = out_dir / "sweep.csv", out_dir / "sweep.json"
    with csv_path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=CSV_FIELDS)
        w.writeheader()
        for r in result.rows:
            d = asdict(r)
            w.writerow({k: ("" if d[k] is None else d[k]) for k in CSV_FIELDS})
    json_path.write_text(json.dumps(result.to_json(), indent=2) + "\n")
    return csv_path, json_path
