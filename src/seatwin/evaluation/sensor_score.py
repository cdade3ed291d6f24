"""The fidelity score with the sensor-level parts of issue 22: what ``compare`` and the fidelity method report.

:func:`seatwin.evaluation.score.score_runs` gives the track-level terms and the plot-level ones of S4–S6; this
module replaces its false-track term (false tracks alive per scan, where a long ghost weighs its lifetime) by
:mod:`seatwin.evaluation.false_tracks` (S4b: each false track once, per minute; the former value is kept in its
``counts.alive_*``), adds the lidar sensor-level terms (S7, :mod:`seatwin.evaluation.lidar_terms`) and combines
the parts again (S5; docs/fidelity-score.md).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from seatwin.evaluation.evaluate import Evaluation
from seatwin.evaluation.false_tracks import false_track_score
from seatwin.evaluation.lidar_terms import lidar_returns_score, lidar_terms, run_lidar_samples
from seatwin.evaluation.plot_terms import SignedTerm
from seatwin.evaluation.score import FidelityScore, ScoreOptions, _refused, overall_score, score_runs
from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet


@dataclass
class SensorFidelityScore(FidelityScore):
    """:class:`FidelityScore` with the lidar sensor-level terms one by one (real, model, signed difference, sentence)."""

    lidar_terms: dict[str, SignedTerm] = field(default_factory=dict)

    def to_dict(self) -> dict:
        return super().to_dict() | {"lidar_terms": {k: t.to_dict() for k, t in self.lidar_terms.items()}}


def score_runs_with_sensor_terms(
    real: Sequence[Tracks],
    synthetic: Sequence[Tracks],
    truth: TruthSet,
    real_evaluations: Sequence[Evaluation],
    synthetic_evaluations: Sequence[Evaluation],
    options: ScoreOptions | None = None,
    window: tuple[float, float] | None = None,
    dont_care: TruthSet | None = None,
) -> SensorFidelityScore:
    """:func:`seatwin.evaluation.score.score_runs` (same arguments) with the false-track term S4b and the lidar
    sensor-level term S7 (``plots["lidar_returns"]``; left out, with the reason, when a run keeps no lidar
    cluster moments), and the lidar terms one by one (``lidar_terms``)."""
    o = options or ScoreOptions()
    base = score_runs(real, synthetic, truth, real_evaluations, synthetic_evaluations, o, window, dont_care)
    vessels = truth if dont_care is None else TruthSet({**truth.targets, **dont_care.targets}, truth.source)
    plots = dict(base.plots)
    false = false_track_score(real, synthetic, vessels, o, window)
    alive = base.plots["false_tracks"]
    if alive.value is not None:
        false.counts |= {
            "alive_hellinger": alive.value,
            **{f"alive_{k}": v for k, v in alive.counts.items() if k.startswith("rate_")},
        }
    plots["false_tracks"] = false
    r, s = run_lidar_samples(real, truth, dont_care, window), run_lidar_samples(synthetic, truth, dont_care, window)
    terms: dict[str, SignedTerm] = {}
    if r is None or s is None:
        plots["lidar_returns"] = _refused("no lidar cluster moments (not a lidar, or a track file)")
    else:
        plots["lidar_returns"] = lidar_returns_score(r, s, o)
        terms = lidar_terms(r, s, o)
    return SensorFidelityScore(overall_score(base.targets, plots, o), base.targets, plots, lidar_terms=terms)
