"""Fidelity sweep: does AHED rise when the sensor model is deliberately made worse?

A reference synthetic dataset is compared (through the tracker, thesis 5.2) with copies made
by degraded lidar models at increasing strength; AHED should rank with the strength.
"""

from seatwin.sweep.degradations import DEGRADATIONS, Degradation, degradation, degradations
from seatwin.sweep.figure import plot_sweep
from seatwin.sweep.outputs import write_sweep
from seatwin.sweep.results import KindSpearman, StrengthSummary, SweepResult, SweepRow, spearman_by_kind, summarise, write_results
from seatwin.sweep.runner import run_sweep
from seatwin.sweep.settings import SweepSettings

__all__ = [
    "DEGRADATIONS",
    "Degradation",
    "KindSpearman",
    "StrengthSummary",
    "SweepResult",
    "SweepRow",
    "SweepSettings",
    "degradation",
    "degradations",
    "plot_sweep",
    "run_sweep",
    "spearman_by_kind",
    "summarise",
    "write_results",
    "write_sweep",
]
