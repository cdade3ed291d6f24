"""Evaluate one tracker run against ground truth (thesis 5.1.4): the use-case behind ``seatwin evaluate``."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError

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


def recording_mask(spec: str | Path | None) -> object | None:
    """The water mask a run directory's manifest names (:func:`seatwin.pipeline.track.map_hint`), else None."""
    from seatwin.perception.map_mask import load_mask
    from seatwin.pipeline.track import map_hint
    from seatwin.recording.manifest import read_manifest

    if spec is None or not Path(spec).is_dir():
        return None
    hint = map_hint(read_manifest(Path(spec)), Path(spec))
    return None if hint is None else load_mask(hint)


def recording_moored_boats(spec: str | Path | None) -> NDArray[np.float64]:
    """(n, 2) north/east of the moored boats of the harbour a run directory's manifest names (its map hint:
    :func:`seatwin.layout.moored_boat_positions`); none for anything else. They are real objects without ground
    truth: tracks on them are don't-care, not false tracks."""
    from seatwin.layout import moored_boat_positions
    from seatwin.pipeline.track import map_hint
    from seatwin.recording.manifest import read_manifest

    if spec is None or not Path(spec).is_dir():
        return np.empty((0, 2))
    hint = map_hint(read_manifest(Path(spec)), Path(spec))
    return np.empty((0, 2)) if hint is None else moored_boat_positions(hint)


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


def harbour_of(map_spec: str | Path | None, run_dir: str | Path | None) -> tuple[object | None, NDArray[np.float64]]:
    """The water mask and the moored boats' (n, 2) positions of ``map_spec``, or else of the harbour the run directory
    ``run_dir``'s manifest names (none for anything else)."""
    if map_spec is not None:
        from seatwin.layout import moored_boat_positions
        from seatwin.perception.map_mask import load_mask

        return load_mask(map_spec), moored_boat_positions(map_spec)
    return recording_mask(run_dir), recording_moored_boats(run_dir)


def moored_vessels(points: NDArray[np.float64], truth: TruthSet, times: NDArray[np.float64] | None = None) -> TruthSet | None:
    """Moored boats at ``points`` as don't-care vessels, still over the span of ``truth`` and ``times`` (a day either
    side: a moored boat is there all along); None when there are none."""
    from seatwin.evaluation import stationary_truth

    if not len(points):
        return None
    spans = [t for tr in truth.targets.values() for t in (tr.start, tr.end)]
    if times is not None and len(times):
        spans += [float(np.min(times)), float(np.max(times))]
    if not spans:
        return None
    return stationary_truth(points, min(spans) - 86400.0, max(spans) + 86400.0)
