"""(S4b) The false-track term: false tracks per minute, each track one unit.

The term it replaces counted false tracks *alive per scan*: a track's weight was its lifetime, so a few long
ghosts (a quay edge followed for a minute) decided it, and it swung 0.018 → 0.394 between two seed pairs of the
same model (issue 22). Here each false track counts once, at the scan it is first confirmed; the rate is per
minute of scans; the distance is the Poisson Hellinger distance of the two rates; the bootstrap resamples the
per-scan series of these counts in blocks, so its units are the tracks themselves (each is one count), never
the scans of one long track (docs/fidelity-score.md, *False tracks*).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from seatwin.evaluation.bootstrap import circular_block_indices
from seatwin.evaluation.score import ScoreOptions, ScoreValue, _refused, _replicates, _with_ci, in_window, poisson_hellinger
from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet

FALSE_SHARE = 0.5
"""A confirmed track is false when more than this share of its confirmed rows in the window are farther than the
gate from every vessel (a track of a target that strays now and then is not a false one)."""
BLOCK_S = 10.0
"""Bootstrap block [s] of the births series; fixed: a false track's birth is one count, so consecutive scans are
nearly independent, and blocks of 10 s keep a burst of births (clutter that seeds several tracks) together."""


def _far(times: NDArray[np.float64], pos: NDArray[np.float64], vessels: TruthSet, gate: float) -> NDArray[np.bool_]:
    """For each row (time, north/east), whether it is farther than ``gate`` from every vessel defined at that time."""
    far = np.ones(len(times), bool)
    for n in vessels.names:
        v = vessels[n].state_at(times)[:, [0, 2]]
        d = np.hypot(pos[:, 0] - v[:, 0], pos[:, 1] - v[:, 1])
        far &= ~(np.isfinite(d) & (d <= gate))
    return far


def false_track_births(
    tracks: Tracks, vessels: TruthSet, gate: float, window: tuple[float, float] | None = None
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Per scan of ``tracks`` (within ``window``), the false tracks first confirmed at it, and those scans' times."""
    times = tracks.scan_times[in_window(tracks.scan_times, window)]
    births = np.zeros(len(times), np.int64)
    rows = tracks.confirmed & in_window(tracks.time, window)
    if not rows.any() or not len(times):
        return births, times
    t, ids, pos = tracks.time[rows], tracks.track_id[rows], tracks.state[rows][:, [0, 2]]
    far = _far(t, pos, vessels, gate)
    for tid in np.unique(ids):
        mine = ids == tid
        if far[mine].mean() > FALSE_SHARE:
            births[min(int(np.searchsorted(times, t[mine].min())), len(times) - 1)] += 1
    return births, times


def _minutes(times: NDArray[np.float64]) -> float:
    """The span of a run's scans [min]: (n − 1) mean intervals plus one (each scan stands for one interval)."""
    if len(times) < 2:
        return 0.0
    return float((times[-1] - times[0]) * len(times) / (len(times) - 1) / 60.0)


def false_track_score(
    real: Sequence[Tracks],
    synthetic: Sequence[Tracks],
    vessels: TruthSet,
    options: ScoreOptions | None = None,
    window: tuple[float, float] | None = None,
) -> ScoreValue:
    """(S4b) Poisson Hellinger distance of the false tracks per minute (each confirmed false track once) of the
    real and the synthetic runs, pooled per side; ``vessels``: targets and don't-care vessels."""
    o = options or ScoreOptions()
    sides = []
    for runs in (real, synthetic):
        parts = [false_track_births(tr, vessels, o.clutter_gate, window) for tr in runs]
        sides.append([(b, _minutes(t), len(t)) for b, t in parts if len(t) >= 2])
    n_r, n_s = (sum(p[2] for p in side) for side in sides)
    if n_r < o.n_min or n_s < o.n_min:
        return _refused(f"fewer than {o.n_min} scans ({n_r} real, {n_s} synthetic)", n_scans_real=n_r)

    def rate(side: list[tuple[NDArray[np.int64], float, int]], idx: list[NDArray[np.int64]] | None = None) -> float:
        count = sum(float(b.sum() if idx is None else b[i].sum()) for (b, _, _), i in zip(side, idx or [None] * len(side)))
        return count / sum(m for _, m, _ in side)

    def block(side: list[tuple[NDArray[np.int64], float, int]]) -> list[int]:
        return [max(1, round(BLOCK_S / (60.0 * m / n))) for _, m, n in side]

    blocks = [block(s) for s in sides]
    lam_r, lam_s = rate(sides[0]), rate(sides[1])
    reps = _replicates(
        o,
        "score/false_track_births",
        lambda rng: poisson_hellinger(
            rate(sides[0], [circular_block_indices(n, k, rng) for (_, _, n), k in zip(sides[0], blocks[0])]),
            rate(sides[1], [circular_block_indices(n, k, rng) for (_, _, n), k in zip(sides[1], blocks[1])]),
        ),
    )
    counts = {
        "rate_real_per_min": lam_r,
        "rate_synthetic_per_min": lam_s,
        "false_tracks_real": float(sum(b.sum() for b, _, _ in sides[0])),
        "false_tracks_synthetic": float(sum(b.sum() for b, _, _ in sides[1])),
        "minutes_real": float(sum(m for _, m, _ in sides[0])),
        "minutes_synthetic": float(sum(m for _, m, _ in sides[1])),
    }
    return _with_ci(poisson_hellinger(lam_r, lam_s), reps, o.level, **counts)
