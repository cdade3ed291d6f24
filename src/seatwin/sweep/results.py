"""Sweep results: one row per (kind, strength, seed), the per-strength spread, Spearman ρ per kind, CSV/JSON."""

from __future__ import annotations

import csv
import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

REFERENCE_KIND = "reference"
FLOOR_KIND = "seed-to-seed"
CSV_FIELDS = ("kind", "strength", "seed", "reference_seed", "ahed", "n_common", "fraction_only_one", "targets_with_ahed")


@dataclass(frozen=True)
class SweepRow:
    """AHED of one degraded copy against its reference (or of two references, for the seed-to-seed floor).

    ``ahed`` is the mean over targets of the per-target AHED (5.34); ``None`` where no target had
    common instants. ``fraction_only_one`` is the mean over targets of the share of instants only
    one dataset tracked the target (what AHED cannot see).
    """

    kind: str
    strength: float
    seed: int
    reference_seed: int
    ahed: float | None
    n_common: int
    fraction_only_one: float | None
    targets_with_ahed: int


@dataclass
class SweepResult:
    """Everything a sweep measured, with the settings that produced it."""

    settings: dict[str, Any]
    rows: list[SweepRow] = field(default_factory=list)

    def kind_rows(self, kind: str, with_reference: bool = True) -> list[SweepRow]:
        """The rows of ``kind`` (and the seed-matched reference points placed at the kind's reference value)."""
        out = [r for r in self.rows if r.kind == kind]
        if with_reference:
            ref = self.settings["references"][kind]
            out = [SweepRow(REFERENCE_KIND, ref, r.seed, r.reference_seed, r.ahed, r.n_common, r.fraction_only_one,
                            r.targets_with_ahed) for r in self.rows if r.kind == REFERENCE_KIND] + out
        return out

    @property
    def kinds(self) -> list[str]:
        return list(self.settings["kinds"])

    @property
    def floor(self) -> list[float]:
        """AHED between references of different seeds: the difference random draws alone make."""
        return [r.ahed for r in self.rows if r.kind == FLOOR_KIND and r.ahed is not None]


def summarise(rows: list[SweepRow]) -> list[dict[str, Any]]:
    """Per strength (ascending): mean, min, max, standard deviation of AHED over seeds, and how many seeds had one."""
    out = []
    for s in sorted({r.strength for r in rows}):
        v = np.array([r.ahed for r in rows if r.strength == s and r.ahed is not None], dtype=float)
        n_seeds = sum(1 for r in rows if r.strength == s)
        frac = [r.fraction_only_one for r in rows if r.strength == s and r.fraction_only_one is not None]
        out.append({
            "strength": s, "n_seeds": n_seeds, "n_ahed": int(v.size),
            "ahed_mean": float(v.mean()) if v.size else None,
            "ahed_min": float(v.min()) if v.size else None,
            "ahed_max": float(v.max()) if v.size else None,
            "ahed_std": float(v.std(ddof=1)) if v.size > 1 else None,
            "fraction_only_one_mean": float(np.mean(frac)) if frac else None,
        })
    return out


def _rho(x: list[float], y: list[float]) -> float | None:
    from scipy.stats import spearmanr

    if len(x) < 3 or len(set(x)) < 2 or len(set(y)) < 2:
        return None
    value = float(spearmanr(x, y).statistic)
    return value if math.isfinite(value) else None


def spearman_by_kind(result: SweepResult) -> dict[str, dict[str, float | None]]:
    """Spearman ρ of strength against AHED, per kind, three ways.

    ``rho_points``: over every per-seed point, the seed-matched reference (AHED 0) included;
    ``rho_means``: over the per-strength means (reference included);
    ``rho_degraded``: over the per-seed points of the degraded copies only (None with < 2 strengths).
    A seed without an AHED (no common instants) is left out of all three.
    """
    out: dict[str, dict[str, float | None]] = {}
    for kind in result.kinds:
        rows = [r for r in result.kind_rows(kind) if r.ahed is not None]
        deg = [r for r in rows if r.kind == kind]
        summary = [s for s in summarise(rows) if s["ahed_mean"] is not None]
        out[kind] = {
            "rho_points": _rho([r.strength for r in rows], [r.ahed for r in rows]),
            "rho_means": _rho([s["strength"] for s in summary], [s["ahed_mean"] for s in summary]),
            "rho_degraded": _rho([r.strength for r in deg], [r.ahed for r in deg]),
        }
    return out


def result_table(result: SweepResult) -> dict[str, Any]:
    """The JSON document: settings, rows, per-kind summaries and ρ, the seed-to-seed floor."""
    floor = result.floor
    return {
        "settings": result.settings,
        "rows": [asdict(r) for r in result.rows],
        "summary": {k: summarise(result.kind_rows(k)) for k in result.kinds},
        "spearman": spearman_by_kind(result),
        "seed_to_seed_floor": {"values": floor, "mean": float(np.mean(floor)) if floor else None,
                               "max": float(np.max(floor)) if floor else None},
    }


def write_results(out_dir: str | Path, result: SweepResult) -> tuple[Path, Path]:
    """Write ``sweep.csv`` (one line per row) and ``sweep.json`` (:func:`result_table`) into ``out_dir``."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    csv_path, json_path = out_dir / "sweep.csv", out_dir / "sweep.json"
    with csv_path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=CSV_FIELDS)
        w.writeheader()
        for r in result.rows:
            d = asdict(r)
            w.writerow({k: ("" if d[k] is None else d[k]) for k in CSV_FIELDS})
    json_path.write_text(json.dumps(result_table(result), indent=2) + "\n")
    return csv_path, json_path
