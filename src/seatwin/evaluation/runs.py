"""Tracker runs as :class:`Tracks`: adapt an in-memory tracker output, or track scans.

Recordings are tracked by ``seatwin track`` (:mod:`seatwin.cli.track`, which owns the
recording → scans → tracker loop); ``seatwin compare`` calls it for recording inputs.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

from seatwin.evaluation.tracks_io import Tracks

TRACK_FILE_SUFFIXES = (".csv",)


def tracks_from_table(table, scan_times: Sequence[float] | np.ndarray = (), source: str = "<tracker>") -> Tracks:  # noqa: ANN001
    """A :class:`seatwin.tracking.TrackTable` (fields ``time, track_id, existence, x, P, confirmed``) as
    :class:`Tracks`; ``scan_times`` are the tracker's scan instants (needed to see instants without a track)."""
    return Tracks(table.time, table.track_id, table.existence, table.x, table.P, table.confirmed,
                  np.asarray(scan_times, dtype=float), source=source)


def track_scans(scans: Iterable, tuning: str, source: str = "<scans>") -> Tracks:  # noqa: ANN001
    """Run the tracker (:func:`seatwin.tracking.track`) with ``tuning`` (a preset name or file) over ``scans``."""
    from seatwin.tracking import load_tuning, track

    scans = list(scans)
    table = track(scans, load_tuning(tuning))
    return tracks_from_table(table, [s.time for s in scans], source=f"{source} (tuning {tuning})")
