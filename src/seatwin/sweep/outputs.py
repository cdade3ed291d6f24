"""What ``seatwin sweep`` writes: sweep.csv, sweep.json and sweep.png, in one call."""

from __future__ import annotations

from pathlib import Path

from seatwin.sweep.figure import plot_sweep
from seatwin.sweep.results import SweepResult, write_results


def write_sweep(out: str | Path, result: SweepResult) -> tuple[Path, Path, Path]:
    """Write ``out``/sweep.csv, sweep.json (Spearman ρ per kind, direction and seed) and sweep.png; their paths."""
    out = Path(out)
    csv_path, json_path = write_results(out, result)
    return csv_path, json_path, plot_sweep(result, out / "sweep.png")
