"""The joyride dataset and its synthetic replica.

``joyride.mat`` (MATLAB v5): ``time`` (n×1 POSIX s), ``measurements`` (n×1 cell of m×2
``[north, east]`` plots; rows with inf are invalid), ``target`` and ``telemetron`` (n×4
``[north, v_north, east, v_east]``). The replica: the ownship (Telemetron, carrying the
radar) and the target boat posed from that ground truth in open water (no harbour), the
radar model scanned at the recorded scan times.

**No heading in the data.** Both vessels' headings are taken from their velocity
(``atan2(v_east, v_north)``), held at the last value while slower than ``MIN_SPEED`` — a
planing boat points roughly where it goes, but drift and crabbing are not modelled. The
ownship heading only rotates the radar's spokes (plots land in the same place), the
target's heading sets its aspect and so its visible width and detection probability.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError

if TYPE_CHECKING:
    from seatwin.evaluation import Tracks, TruthSet
    from seatwin.scenario.model import Scenario
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.sensors.radar.fit import RadarObservations
    from seatwin.sensors.radar.model import RadarModel, RadarScan
    from seatwin.world.scene import Scene

MIN_SPEED = 0.5
"""m/s: below it a vessel keeps its previous heading."""
TARGET_SIZE = (8.0, 2.8, 2.0)
"""Length, beam, height [m] of the target box: the dataset does not say; a typical small
leisure motor boat / RIB of the kind used in the joyride experiments (assumption)."""
OWNSHIP = "telemetron"
TARGET = "target"


@dataclass
class JoyrideData:
    """The dataset: scan times, real plots, ground truth of target and ownship."""

    time: NDArray[np.float64]
    plots: list[NDArray[np.float64]]
    target: NDArray[np.float64]
    """(n, 4) ``[north, v_north, east, v_east]``."""
    ownship: NDArray[np.float64]
    source: str = "<memory>"
    n_invalid: int = 0
    """Plot rows dropped because they held inf/NaN."""

    def __len__(self) -> int:
        return int(self.time.shape[0])


RADAR_CLUTTER_GATE_M = 60.0
"""Plots and confirmed tracks farther than this from the target are clutter and off-target tracks: the
radar's plots scatter tens of metres about the target, and a model's own scattered target plots must
not count as clutter (plot statistics, off-target tracks and the score's plot terms alike)."""


def load_joyride(path: str | Path) -> JoyrideData:
    """Read ``joyride.mat`` with :func:`seatwin.perception.datasets.read_joyride` (invalid rows dropped, counted)."""
    from seatwin.perception.datasets import read_joyride

    ds = read_joyride(path)
    for key, arr in (("target", ds.targets["target"]), ("telemetron", ds.sensor)):
        if not np.isfinite(arr).all():
            raise InputError(path, f"non-finite value in row {int(np.flatnonzero(~np.isfinite(arr).all(1))[0])}", where=key)
    return JoyrideData(ds.time, ds.plots, ds.targets["target"], ds.sensor, str(path), _count_invalid(path, ds.plots))


def _count_invalid(path: str | Path, kept: list[NDArray[np.float64]]) -> int:
    """Plot rows the reader dropped as invalid (inf/NaN)."""
    import scipy.io

    cells = np.asarray(scipy.io.loadmat(Path(path), variable_names=["measurements"])["measurements"], dtype=object).reshape(-1)
    return int(sum(np.asarray(c).reshape(-1, 2).shape[0] if np.asarray(c).size else 0 for c in cells) - sum(len(k) for k in kept))


def heading_from_velocity(
    v_north: NDArray[np.float64], v_east: NDArray[np.float64], min_speed: float = MIN_SPEED
) -> NDArray[np.float64]:
    """Course over ground [rad], held while slower than ``min_speed`` (0 until the first fast sample)."""
    h = np.arctan2(v_east, v_north)
    fast = np.hypot(v_north, v_east) >= min_speed
    if not fast.any():
        return np.zeros_like(h)
    idx = np.where(fast, np.arange(len(h)), -1)
    idx = np.maximum.accumulate(idx)
    idx[idx < 0] = int(np.flatnonzero(fast)[0])
    return h[idx]


AWAY_M = 1.0e6
"""Where an un-truthed vessel waits outside the span it was tracked over: far beyond any radar's range."""


VESSEL_MIN_DISPLACEMENT_M = 200.0
"""How far a track must get from where it was first confirmed by motion (:func:`sustained_motion`) to be a
vessel. Measured on the eight Ravnkloa radar-2023 recordings (quays, moored boats, buildings; issue 21,
docs/validation.md): of the tracks confirmed over ≥ 20 scans, none gets 200 m — at most 186 m with the
joyride tuning (111 tracks, 22 of them with a single-scan step > 50 m), 161 m with the ravnkloa tuning (138)."""

VESSEL_MAX_SPEED_MPS = 15.0
"""A step between consecutive confirmed estimates longer than this × Δt + :data:`VESSEL_STEP_SLACK_M` is a
jump (the track re-attached to other clutter), not motion: 1.5 × the v_max of the radar tunings (10 m/s)."""

VESSEL_STEP_SLACK_M = 10.0
"""Position noise allowed in one step on top of :data:`VESSEL_MAX_SPEED_MPS` × Δt. On the Ravnkloa
recordings (Δt = 1 s) the ravnkloa tuning's steps stay ≤ 28 m (99 %: 23 m); the joyride tuning's (σ_r 10 m)
99th percentile is 96 m — its jumps of 50–98 m are what the bound removes."""


def sustained_motion(
    time: NDArray[np.float64],
    north: NDArray[np.float64],
    east: NDArray[np.float64],
    max_speed: float = VESSEL_MAX_SPEED_MPS,
    step_slack: float = VESSEL_STEP_SLACK_M,
) -> float:
    """How far a track gets from its first position by motion [m]: at each scan the smaller of its distance
    from the start and the length of its bounded-step path's resultant (steps longer than ``max_speed`` × Δt +
    ``step_slack`` — single-scan jumps — left out, the rest summed as vectors), the largest over the track.
    A jump outwards is not motion (the bounded path stays home); drifting out and jumping back again and again
    is not either (the track itself stays near); jitter in place cancels in the sum."""
    if len(time) < 2:
        return 0.0
    step = np.column_stack([np.diff(north), np.diff(east)])
    bounded = np.hypot(step[:, 0], step[:, 1]) <= max_speed * np.diff(time) + step_slack
    path = np.cumsum(step * bounded[:, None], axis=0)
    actual = np.hypot(north[1:] - north[0], east[1:] - east[0])
    return float(np.minimum(np.hypot(path[:, 0], path[:, 1]), actual).max())


def untruthed_vessels(
    tracks: Tracks,
    data: JoyrideData,
    gate_m: float,
    min_scans: int = 20,
    share: float = 0.9,
    min_displacement_m: float = VESSEL_MIN_DISPLACEMENT_M,
) -> dict[str, NDArray[np.float64]]:
    """Vessels without ground truth that the real tracker followed: confirmed tracks farther than ``gate_m``
    from the target in at least ``share`` of their confirmed instants, over at least ``min_scans`` scans, that
    move: at least ``min_displacement_m`` from where they were first confirmed by bounded steps
    (:func:`sustained_motion`; a track that stays put, e.g. on a quay, or gets there only by jumping between
    clutter, stays counted as a false track).
    Per vessel (``untruthed1`` …), its ``[time, north, v_north, east, v_east]`` rows (the track's estimates).

    The dataset has GNSS truth for the target only; a boat it does not list is still part of the real
    scene, and a replica without it cannot produce the plots and tracks it causes."""
    out: dict[str, NDArray[np.float64]] = {}
    conf = tracks.confirmed
    for k in np.unique(tracks.track_id[conf]):
        m = conf & (tracks.track_id == k)
        t = tracks.time[m]
        tn, te = np.interp(t, data.time, data.target[:, 0]), np.interp(t, data.time, data.target[:, 2])
        north, east = tracks.state[m, 0], tracks.state[m, 2]
        off = np.hypot(north - tn, east - te) > gate_m
        if len(t) >= min_scans and off.mean() >= share and sustained_motion(t, north, east) >= min_displacement_m:
            out[f"untruthed{len(out) + 1}"] = np.column_stack([t, tracks.state[m]])
    return out


def truth_of(data: JoyrideData) -> TruthSet:
    """The target's GNSS ground truth as a :class:`seatwin.evaluation.TruthSet`."""
    from seatwin.evaluation import TruthSet, TruthTrack

    tr = TruthTrack(TARGET, data.time, data.target[:, 0], data.target[:, 2], data.target[:, 1], data.target[:, 3], data.source)
    return TruthSet({TARGET: tr}, data.source)


def vessels_truth(vessels: dict[str, NDArray[np.float64]], source: str = "<memory>") -> TruthSet:
    """Un-truthed vessels (:func:`untruthed_vessels`) as a :class:`seatwin.evaluation.TruthSet` of their
    track estimates: the score's "don't care" regions (defined only over the span each was tracked)."""
    from seatwin.evaluation import TruthSet, TruthTrack

    return TruthSet(
        {name: TruthTrack(name, r[:, 0], r[:, 1], r[:, 3], r[:, 2], r[:, 4], source) for name, r in vessels.items()}, source
    )


def replica_scenario(
    data: JoyrideData,
    target_size: tuple[float, float, float] = TARGET_SIZE,
    extra: dict[str, NDArray[np.float64]] | None = None,
) -> Scenario:
    """A :class:`seatwin.scenario.Scenario` of the two boats (headings from velocity), plus ``extra`` vessels
    (:func:`untruthed_vessels`, the target's size; far away outside the span they were tracked over)."""
    from seatwin.scenario.model import Dimensions, Role, Scenario, Trajectory, Vessel

    def traj(time: NDArray[np.float64], x: NDArray[np.float64]) -> Trajectory:
        return Trajectory(time, x[:, 0], x[:, 2], heading_from_velocity(x[:, 1], x[:, 3]), source=data.source)

    own = Vessel(OWNSHIP, Role.OWNSHIP, traj(data.time, data.ownship), model="generic", dimensions=Dimensions(10.0, 3.0, 2.5))
    vessels = [
        own,
        Vessel(TARGET, Role.TARGET, traj(data.time, data.target), model="generic", dimensions=Dimensions(*target_size)),
    ]
    for name, rows in (extra or {}).items():
        outside = data.time[(data.time < rows[0, 0]) | (data.time > rows[-1, 0])]
        time = np.concatenate([outside, rows[:, 0]])
        states = np.vstack([np.tile([AWAY_M, 0.0, AWAY_M, 0.0], (len(outside), 1)), rows[:, 1:]])
        order = np.argsort(time, kind="stable")
        time, states = time[order], states[order]
        vessels.append(Vessel(name, Role.TARGET, traj(time, states), model="generic", dimensions=Dimensions(*target_size)))
    return Scenario("joyride-replica", vessels, environment={"harbour": "none", "water": "flat"}, rig=None, source=data.source)


def replica_scene(
    data: JoyrideData, target_size: tuple[float, float, float] = TARGET_SIZE, extra: dict[str, NDArray[np.float64]] | None = None
) -> Scene:
    """The scene: no static world, the vessels with generic hulls of their sizes."""
    from seatwin.world.scene import Scene
    from seatwin.world.vessels import vessel_model

    sc = replica_scenario(data, target_size, extra)
    vessels = {v.name: (vessel_model(v.model, v.dimensions, sc.source, v.mesh), v.trajectory) for v in sc.vessels}
    return Scene([], vessels)


def simulate_replica(
    data: JoyrideData, model: RadarModel, scene: Scene | None = None, indices: Sequence[int] | None = None
) -> list[RadarScan]:
    """The radar model's scans at the dataset's scan times (all, or the increasing scan ``indices``).

    Through the one simulation loop (:func:`seatwin.sim.loop.frames`) with a
    :class:`seatwin.sim.radar.RadarSensor` replaying the scan times; the frame index (and so
    every random draw) is the scan index, whichever scans are simulated.
    """
    from seatwin.sim.loop import frames
    from seatwin.sim.radar import RadarSensor

    scene = scene or replica_scene(data)
    if indices is None:
        sensor = RadarSensor(model, scene, OWNSHIP, times=data.time)
    else:
        idx = np.asarray(indices, dtype=np.int64).reshape(-1)
        if len(idx) and ((np.diff(idx) <= 0).any() or idx[0] < 0 or idx[-1] >= len(data)):
            raise ParameterError("indices", f"expected increasing scan indices in [0, {len(data)})")
        sensor = RadarSensor(model, scene, OWNSHIP, times=data.time[idx], frame_ids=idx)
    if not len(sensor.times):
        return []
    t0 = float(sensor.times[0])
    return [scan for _, _, _, scan in frames([sensor], t0, float(sensor.times[-1]) + 1.0)]


def target_visible_area(data: JoyrideData, config: RadarConfig, scene: Scene | None = None) -> NDArray[np.float64]:
    """The target's visible area [m²] seen by the radar at each scan (from the replica's geometry; NaN if unseen)."""
    from seatwin.sensors.radar.geometry import illuminate
    from seatwin.sensors.radar.model import RadarModel
    from seatwin.sensors.radar.world import SceneCaster, antenna_pose

    scene = scene or replica_scene(data)
    model = RadarModel(config)
    tid = scene.vessel_ids[TARGET]
    out = np.full(len(data), np.nan)
    for k, t in enumerate(data.time):
        objs = illuminate(config, antenna_pose(model, scene, OWNSHIP, float(t)), SceneCaster(scene, float(t), (OWNSHIP,)))
        for o in objs:
            if o.object_id == tid:
                out[k] = o.area_m2
    return out


def observations(data: JoyrideData, config: RadarConfig | None = None, scene: Scene | None = None) -> RadarObservations:
    """The dataset as :class:`seatwin.sensors.radar.fit.RadarObservations` (target area from the replica)."""
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.sensors.radar.fit import RadarObservations

    config = config or RadarConfig()
    area = target_visible_area(data, config, scene)
    area = np.where(np.isfinite(area), area, np.nanmedian(area) if np.isfinite(area).any() else TARGET_SIZE[0] * TARGET_SIZE[2])
    return RadarObservations(data.time, data.plots, antenna_positions(data, config), data.target[:, [0, 2]], area, data.source)


def antenna_positions(data: JoyrideData, config: RadarConfig) -> NDArray[np.float64]:
    """North/east of the radar antenna at each scan: the ownship's position plus ``config``'s mount,
    turned by the heading from velocity."""
    h = heading_from_velocity(data.ownship[:, 1], data.ownship[:, 3])
    return data.ownship[:, [0, 2]] + np.column_stack(
        [
            config.mount_x_m * np.cos(h) - config.mount_y_m * np.sin(h),
            config.mount_x_m * np.sin(h) + config.mount_y_m * np.cos(h),
        ]
    )
