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


@dataclass(frozen=True)
class StrengthSummary:
    """AHED over the seeds at one strength: mean, min, max, standard deviation, and how many seeds had one."""

    strength: float
    n_seeds: int
    n_ahed: int
    ahed_mean: float | None
    ahed_min: float | None
    ahed_max: float | None
    ahed_std: float | None
    fraction_only_one_mean: float | None


@dataclass(frozen=True)
class KindSpearman:
    """Spearman ρ of strength against AHED for one kind, three ways (None where undefined).

    ``rho_points``: over every per-seed point, the seed-matched reference (AHED 0) included;
    ``rho_means``: over the per-strength means (reference included);
    ``rho_degraded``: over the per-seed points of the degraded copies only (None with < 2 strengths).
    A seed without an AHED (no common instants) is left out of all three.
    """

    rho_points: float | None
    rho_means: float | None
    rho_degraded: float | None


@dataclass
class SweepResult:
    """Everything a sweep measured, with the settings that produced it (``offset`` resolved)."""

    settings: SweepSettings
    rows: list[SweepRow] = field(default_factory=list)

    def kind_rows(self, kind: str, with_reference: bool = True) -> list[SweepRow]:
        """The rows of ``kind`` (and the seed-matched reference points placed at the kind's reference value)."""
        out = [r for r in self.rows if r.kind == kind]
        if with_reference:
            ref = degradation(kind).reference
            out = [replace(r, kind=REFERENCE_KIND, strength=ref) for r in self.rows if r.kind == REFERENCE_KIND] + out
        return out

    @property
    def kinds(self) -> list[str]:
        return list(self.settings.kinds)

    @property
    def floor(self) -> list[float]:
        """AHED between references of different seeds: the difference random draws alone make."""
        return [r.ahed for r in self.rows if r.kind == FLOOR_KIND and r.ahed is not None]

    def floor_mean_max(self) -> tuple[float | None, float | None]:
        """Mean and maximum of :attr:`floor` (None without seed pairs)."""
        floor = self.floor
        return (float(np.mean(floor)), float(np.max(floor))) if floor else (None, None)

    def to_json(self) -> dict[str, Any]:
        """The ``sweep.json`` document: settings, rows, per-kind summaries and ρ, the seed-to-seed floor."""
        mean, top = self.floor_mean_max()
        return {
            "settings": self.settings.describe(),
            "rows": [asdict(r) for r in self.rows],
            "summary": {k: [asdict(s) for s in summarise(self.kind_rows(k))] for k in self.kinds},
            "spearman": {k: asdict(r) for k, r in spearman_by_kind(self).items()},
            "seed_to_seed_floor": {"values": self.floor, "mean": mean, "max": top},
        }


def summarise(rows: list[SweepRow]) -> list[StrengthSummary]:
    """Per strength (ascending): the spread of AHED over seeds."""
    out = []
    for s in sorted({r.strength for r in rows}):
        v = np.array([r.ahed for r in rows if r.strength == s and r.ahed is not None], dtype=float)
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

    if len(x) < 3 or len(set(x)) < 2 or len(set(y)) < 2:
        return None
    value = float(spearmanr(x, y).statistic)
    return value if math.isfinite(value) else None


def spearman_by_kind(result: SweepResult) -> dict[str, KindSpearman]:
    """Spearman ρ of strength against AHED, per kind (:class:`KindSpearman`)."""
    out: dict[str, KindSpearman] = {}
    for kind in result.kinds:
        rows = [r for r in result.kind_rows(kind) if r.ahed is not None]
        deg = [r for r in rows if r.kind == kind]
        summary = [s for s in summarise(rows) if s.ahed_mean is not None]
        out[kind] = KindSpearman(
            _rho([r.strength for r in rows], [r.ahed for r in rows]),
            _rho([s.strength for s in summary], [s.ahed_mean for s in summary]),
            _rho([r.strength for r in deg], [r.ahed for r in deg]),
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
