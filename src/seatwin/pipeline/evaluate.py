"""Evaluate one tracker run against ground truth (thesis 5.1.4): the use-case behind ``seatwin evaluate``."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from seatwin.errors import InputError, ParameterError
from seatwin.pipeline.track import harbour_of, moored_vessels

if TYPE_CHECKING:
    from seatwin.evaluation import Evaluation, Tracks, TruthSet


def check_overlap(tracks: Tracks, truth: TruthSet, source: str) -> None:
    """An :class:`InputError` when no tracker instant falls inside any ground truth's time span."""
    if not len(tracks.scan_times) or not len(truth):
        return
    t0, t1 = float(tracks.scan_times[0]), float(tracks.scan_times[-1])
    spans = [(tr.start, tr.end) for tr in truth.targets.values()]
    if all(t1 < a or t0 > b for a, b in spans):
        a = min(s[0] for s in spans)
        b = max(s[1] for s in spans)
        raise InputError(
            source,
            f"the tracks span [{t0!r}, {t1!r}] s but the ground truth spans [{a!r}, {b!r}] s: "
            "no common time (same clock? same scenario?)",
        )


def evaluate_run(
    tracks: str | Path | Tracks,
    truth: str | Path | TruthSet,
    *,
    gate: float = 10.0,
    confirmed_only: bool = True,
    confidence: float = 0.95,
    map_spec: str | None = None,
) -> Evaluation:
    """Per-target metrics of ``tracks`` (a track file or :class:`Tracks`) against ``truth`` (scenario, recording or set),
    and the false tracks — on land per ``map_spec`` ('harbour', 'none', a raster; default: the recording's own); tracks
    of that harbour's moored boats are don't-care, not false (:func:`recording_moored_boats`)."""
    from seatwin.evaluation import Tracks, evaluate, load_truth, read_tracks

    if not gate > 0:
        raise ParameterError("gate", f"must be positive, got {gate}")
    if not 0 < confidence < 1:
        raise ParameterError("confidence", f"must lie in (0, 1), got {confidence}")
    run = tracks if isinstance(tracks, Tracks) else read_tracks(tracks)
    truth_set = truth if not isinstance(truth, str | Path) else load_truth(truth)
    check_overlap(run, truth_set, str(run.source))
    mask, moored = harbour_of(map_spec, truth if isinstance(truth, str | Path) else None)
    ignored = moored_vessels(moored, truth_set, run.time)
    return evaluate(run, truth_set, gate=gate, confirmed_only=confirmed_only, confidence=confidence, mask=mask, dont_care=ignored)
