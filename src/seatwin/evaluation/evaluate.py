"""Evaluate one tracker run against ground truth: per target, the metrics of thesis 5.1.4 over time and summarised."""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.evaluation.association import DEFAULT_GATE_M, Association, associate, track_losses, track_switches
from seatwin.evaluation.metrics import anees, anees_bounds, nees, rms, rmse
from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet

N_G = 4  # states per estimate (5.32)


@dataclass
class TargetSeries:
    """One target over the tracker's instants; NaN / −1 where the metrics are undefined (track loss)."""

    target: str
    time: NDArray[np.float64]
    track_id: NDArray[np.int64]
    state: NDArray[np.float64]
    """(n, 4) the associated estimate ``[north, v_north, east, v_east]``."""
    covariance: NDArray[np.float64]
    """(n, 4, 4)."""
    truth: NDArray[np.float64]
    """(n, 4) ground truth, NaN outside its span."""
    rmse: NDArray[np.float64]
    """(5.25) over the whole state, per instant."""
    rmse_position: NDArray[np.float64]
    nees: NDArray[np.float64]
    """(5.26) per instant."""

    @property
    def valid(self) -> NDArray[np.bool_]:
        return self.track_id >= 0


@dataclass
class TargetSummary:
    """The per-target line of ``seatwin evaluate``."""

    target: str
    n_instants: int
    """Tracker instants inside the ground truth's span."""
    n_valid: int
    """Instants with an associated track (the thesis's N_k)."""
    coverage: float | None
    first_time: float | None
    last_time: float | None
    track_switches: int
    track_losses: int
    track_ids: list[int]
    rmse: float | None
    """RMS over the valid instants of the per-instant RMSE (5.25) (whole state, m and m/s mixed as printed)."""
    rmse_position: float | None
    rmse_velocity: float | None
    anees: float | None
    anees_lower: float | None
    anees_upper: float | None
    anees_verdict: str

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class FalseTracks:
    """Tracks never associated with any target: un-truthed vessels, persistent clutter, quay returns."""

    n_tracks: int
    """Distinct false tracks."""
    n_instants: int
    """Track-instants they occupy."""
    n_on_land: int | None
    """False tracks whose mean position lies on land (None without a water mask)."""
    max_speed_mps: float | None
    """Largest estimated speed of any false track (impossible speeds show quay-sliding tracks)."""
    n_dont_care: int = 0
    """Tracks never associated with a target that follow a don't-care object (a moored boat: real, without ground
    truth); not counted in ``n_tracks``."""

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class Evaluation:
    association: Association
    series: dict[str, TargetSeries]
    summaries: list[TargetSummary]
    false_tracks: FalseTracks | None = None

    def to_dict(self) -> dict:
        return {
            "gate_m": self.association.gate,
            "n_instants": int(len(self.association.times)),
            "targets": [s.to_dict() for s in self.summaries],
            "false_tracks": None if self.false_tracks is None else self.false_tracks.to_dict(),
        }


def _num(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def target_series(tracks: Tracks, truth: TruthSet, assoc: Association, target: str) -> TargetSeries:
    """The per-instant estimate, truth, RMSE and NEES of ``target`` under ``assoc``."""
    i = assoc.index(target)
    rows = assoc.row[i]
    valid = rows >= 0
    n = len(assoc.times)
    state = np.full((n, 4), np.nan)
    cov = np.full((n, 4, 4), np.nan)
    state[valid] = tracks.state[rows[valid]]
    cov[valid] = tracks.covariance[rows[valid]]
    ref = truth[target].state_at(assoc.times)
    e_rmse = np.full(n, np.nan)
    e_pos = np.full(n, np.nan)
    e_nees = np.full(n, np.nan)
    if valid.any():
        e_rmse[valid] = rmse(state[valid], ref[valid])
        e_pos[valid] = rmse(state[valid][:, [0, 2]], ref[valid][:, [0, 2]])
        e_nees[valid] = nees(state[valid], ref[valid], cov[valid])
    return TargetSeries(target, assoc.times, assoc.track_id[i].copy(), state, cov, ref, e_rmse, e_pos, e_nees)


def summarise(series: TargetSeries, truth_defined: NDArray[np.bool_], confidence: float = 0.95) -> TargetSummary:
    """Coverage, association statistics, RMSE, ANEES (5.27) and its bounds (5.28) of one target."""
    valid = series.valid
    n_inst = int(np.count_nonzero(truth_defined))
    n_k = int(np.count_nonzero(valid))
    value = anees(series.nees)
    bounds = anees_bounds(n_k, N_G, confidence)
    vel = np.full(len(valid), np.nan)
    if n_k:
        d = series.state[valid][:, [1, 3]] - series.truth[valid][:, [1, 3]]
        vel[valid] = np.hypot(d[:, 0], d[:, 1])
    times = series.time[valid]
    return TargetSummary(
        target=series.target,
        n_instants=n_inst,
        n_valid=n_k,
        coverage=(n_k / n_inst) if n_inst else None,
        first_time=float(times[0]) if n_k else None,
        last_time=float(times[-1]) if n_k else None,
        track_switches=track_switches(series.track_id),
        track_losses=track_losses(series.track_id, truth_defined),
        track_ids=sorted({int(k) for k in series.track_id[valid]}),
        rmse=_num(rms(series.rmse)),
        rmse_position=_num(rms(series.rmse_position)),
        rmse_velocity=_num(rms(vel)),
        anees=_num(value),
        anees_lower=_num(bounds.lower),
        anees_upper=_num(bounds.upper),
        anees_verdict=bounds.verdict(value),
    )


def false_tracks(
    tracks: Tracks,
    assoc: Association,
    mask: object | None = None,
    dont_care: TruthSet | None = None,
    gate: float = DEFAULT_GATE_M,
) -> FalseTracks:
    """The tracks of ``tracks`` that ``assoc`` never gave to a target; on land per ``mask`` (``is_water(n, e)``).

    ``dont_care``: vessels that are real but have no (reliable) ground truth — a harbour's moored boats
    (:func:`stationary_truth` of :func:`seatwin.layout.moored_boat_positions`), AIS-only vessels. A never-associated
    track with at least half of its rows within ``gate`` of one of them (at the row's time) is a track of that vessel,
    counted in ``n_dont_care`` instead of as a false track."""
    used = {int(k) for k in assoc.track_id.ravel() if k >= 0}
    false = ~np.isin(tracks.track_id, list(used)) if used else np.ones(len(tracks.track_id), bool)
    false &= tracks.track_id >= 0
    n_dont_care = 0
    if dont_care is not None and len(dont_care) and false.any():
        rows = np.flatnonzero(false)
        where = dont_care.states_at(tracks.time[rows])[:, :, [0, 2]]  # (vessels, rows, 2)
        d = np.hypot(where[:, :, 0] - tracks.state[rows, 0], where[:, :, 1] - tracks.state[rows, 2])
        near = np.zeros(len(tracks.time), bool)
        near[rows] = (np.where(np.isfinite(d), d, np.inf) <= gate).any(axis=0)
        for k in np.unique(tracks.track_id[rows]):
            m = false & (tracks.track_id == k)
            if near[m].mean() >= 0.5:
                false &= ~m
                n_dont_care += 1
    ids = np.unique(tracks.track_id[false])
    on_land = None
    if mask is not None:
        on_land = 0
        for k in ids:
            m = false & (tracks.track_id == k)
            n, e = tracks.state[m][:, 0].mean(), tracks.state[m][:, 2].mean()
            on_land += int(not mask.is_water(float(n), float(e)))  # type: ignore[attr-defined]
    speeds = np.hypot(tracks.state[false, 1], tracks.state[false, 3])
    return FalseTracks(int(len(ids)), int(false.sum()), on_land, float(speeds.max()) if len(speeds) else None, n_dont_care)


def evaluate(
    tracks: Tracks,
    truth: TruthSet,
    gate: float = DEFAULT_GATE_M,
    confirmed_only: bool = True,
    confidence: float = 0.95,
    mask: object | None = None,
    dont_care: TruthSet | None = None,
) -> Evaluation:
    """Associate ``tracks`` with ``truth`` and compute every target's metrics (thesis 5.1.4), and the false
    tracks (on land per the water ``mask``, when given; tracks of the ``dont_care`` objects, e.g. moored boats,
    are not false: :func:`false_tracks`)."""
    used = tracks.confirmed_only() if confirmed_only else tracks
    assoc = associate(used, truth, gate)
    series = {name: target_series(used, truth, assoc, name) for name in assoc.targets}
    summaries = [summarise(series[name], assoc.truth_defined[assoc.index(name)], confidence) for name in assoc.targets]
    return Evaluation(assoc, series, summaries, false_tracks(used, assoc, mask, dont_care, gate))
