"""Track-to-truth association (thesis 5.1.4, "Track-Truth associations").

At every tracker instant each track *subscribes* to the closest ground truth within the
gate (10 m in the thesis; horizontal distance of the position estimate). Per ground truth,
the closest subscribed track is *the target*. An instant where the truth exists but no track
subscribes to it is a *track loss*: the metrics are undefined there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet

DEFAULT_GATE_M = 10.0
NO_TRACK = -1


@dataclass
class Association:
    """Which track is each target at each tracker instant.

    Arrays are (n_targets, n_times) over ``times`` (the tracker's scan times) in ``targets`` order.
    """

    times: NDArray[np.float64]
    targets: list[str]
    track_id: NDArray[np.int64]
    """The target's track, :data:`NO_TRACK` at a loss or where the truth is undefined."""
    row: NDArray[np.int64]
    """Index of that track's row in the (possibly filtered) :class:`Tracks`, −1 where none."""
    distance: NDArray[np.float64]
    """Horizontal distance [m] of the target's track to the truth, NaN where none."""
    truth_defined: NDArray[np.bool_]
    """Whether the ground truth spans the instant (only those count as losses)."""
    gate: float

    def index(self, target: str) -> int:
        return self.targets.index(target)

    @property
    def valid(self) -> NDArray[np.bool_]:
        return self.track_id != NO_TRACK


def associate(tracks: Tracks, truth: TruthSet, gate: float = DEFAULT_GATE_M) -> Association:
    """Associate ``tracks`` (filter them first, e.g. :meth:`Tracks.confirmed_only`) with ``truth``."""
    if not gate > 0:
        raise ValueError(f"gate must be positive, got {gate}")
    names = truth.names
    times = tracks.scan_times
    n_tg, n_t = len(names), len(times)
    track_id = np.full((n_tg, n_t), NO_TRACK, dtype=np.int64)
    row_of = np.full((n_tg, n_t), -1, dtype=np.int64)
    distance = np.full((n_tg, n_t), np.nan)
    truth_defined = np.isfinite(truth.states_at(times)[..., 0]) if n_tg else np.zeros((0, n_t), bool)
    if len(tracks) and n_tg:
        ref = truth.states_at(tracks.time)  # (n_tg, n_rows, 4)
        dist = np.hypot(tracks.state[:, 0] - ref[..., 0], tracks.state[:, 2] - ref[..., 2])
        dist = np.where(np.isfinite(dist), dist, np.inf)
        # Each track subscribes to its closest ground truth within the gate.
        sub = np.argmin(dist, axis=0)
        sub_dist = dist[sub, np.arange(len(tracks))]
        ok = sub_dist <= gate
        rows = np.flatnonzero(ok)
        t_idx = np.searchsorted(times, tracks.time[rows])
        # Per (target, instant) the closest subscribed track: sort by distance, keep the first.
        order = np.lexsort((tracks.track_id[rows], sub_dist[rows], t_idx, sub[rows]))
        rows, t_idx = rows[order], t_idx[order]
        tg = sub[rows]
        first = np.ones(len(rows), dtype=bool)
        first[1:] = (tg[1:] != tg[:-1]) | (t_idx[1:] != t_idx[:-1])
        rows, t_idx, tg = rows[first], t_idx[first], tg[first]
        track_id[tg, t_idx] = tracks.track_id[rows]
        row_of[tg, t_idx] = rows
        distance[tg, t_idx] = sub_dist[rows]
    return Association(times, names, track_id, row_of, distance, truth_defined, float(gate))


def track_switches(ids: NDArray[np.int64]) -> int:
    """How often the target's track changes between consecutive associated instants (losses skipped)."""
    seq = np.asarray(ids)[np.asarray(ids) != NO_TRACK]
    return int(np.count_nonzero(seq[1:] != seq[:-1]))


def track_losses(ids: NDArray[np.int64], truth_defined: NDArray[np.bool_]) -> int:
    """Number of separate track-loss episodes after the first association (gaps inside the tracked span)."""
    valid = np.asarray(ids) != NO_TRACK
    if not valid.any():
        return 0
    span = np.arange(len(valid))
    inside = (span > np.flatnonzero(valid)[0]) & np.asarray(truth_defined)
    lost = inside & ~valid
    starts = lost & ~np.concatenate([[False], lost[:-1]])
    return int(np.count_nonzero(starts))
