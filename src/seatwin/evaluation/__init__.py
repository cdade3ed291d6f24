"""Tracker evaluation (thesis 5.1.4) and real-versus-synthetic comparison (thesis 5.2).

Public API: the track file (:func:`read_tracks`, :func:`write_tracks`, :class:`Tracks`),
ground truth (:class:`TruthSet`, :func:`truth_from_scenario`, :func:`load_truth`),
association (:func:`associate`), metrics (:func:`rmse`, :func:`nees`, :func:`anees`,
:func:`anees_bounds`), the Hellinger distance (:func:`hellinger`, :func:`covdiff`),
:func:`evaluate` and :func:`compare`.
"""

from seatwin.evaluation.association import Association, associate
from seatwin.evaluation.compare import CompareOptions, Comparison, compare, comparison_table
from seatwin.evaluation.evaluate import Evaluation, evaluate
from seatwin.evaluation.hellinger import covdiff, hellinger
from seatwin.evaluation.metrics import anees, anees_bounds, nees, rmse
from seatwin.evaluation.tracks_io import Tracks, read_tracks, write_tracks
from seatwin.evaluation.truth import TruthSet, TruthTrack, load_truth, stationary_truth, truth_from_scenario

__all__ = [
    "Association",
    "CompareOptions",
    "Comparison",
    "Evaluation",
    "Tracks",
    "TruthSet",
    "TruthTrack",
    "anees",
    "anees_bounds",
    "associate",
    "compare",
    "comparison_table",
    "covdiff",
    "evaluate",
    "hellinger",
    "load_truth",
    "nees",
    "read_tracks",
    "rmse",
    "stationary_truth",
    "truth_from_scenario",
    "write_tracks",
]
