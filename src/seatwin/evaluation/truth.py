"""Ground truth for evaluation: per target, sampled positions and velocities in local NED.

The thesis (5.2.1) anchors the tracker's state ``[north, v_north, east, v_east]`` (5.32) to
GNSS positions, with velocities "using numerical differentiation estimates based on
position". :class:`TruthTrack` does the same (central differences, ``numpy.gradient``) unless
velocities are given; a scenario's trajectories already carry those derivatives, so
:func:`truth_from_scenario` takes them from the scenario model.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError

if TYPE_CHECKING:
    from seatwin.recording import Recording, VesselTruth

RECORDING_SUFFIXES = (".mcap", ".bag", ".db3")


def numerical_velocity(time: NDArray[np.float64], position: NDArray[np.float64]) -> NDArray[np.float64]:
    """Velocity from sampled positions by central differences (one-sided at the ends)."""
    return np.gradient(position, time)


@dataclass
class TruthTrack:
    """One target's ground truth: strictly increasing POSIX ``time``, ``north``/``east`` [m], velocities [m/s]."""

    name: str
    time: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    v_north: NDArray[np.float64] | None = None
    v_east: NDArray[np.float64] | None = None
    source: str = "<memory>"

    def __post_init__(self) -> None:
        self.time = np.asarray(self.time, dtype=float).reshape(-1)
        n = len(self.time)
        self.north = np.asarray(self.north, dtype=float).reshape(n)
        self.east = np.asarray(self.east, dtype=float).reshape(n)
        if n < 2:
            raise InputError(self.source, f"ground truth of {self.name!r} needs at least 2 samples, got {n}")
        if (np.diff(self.time) <= 0).any():
            raise InputError(self.source, f"ground truth times of {self.name!r} must increase strictly")
        for arr_name in ("time", "north", "east"):
            if not np.isfinite(getattr(self, arr_name)).all():
                raise InputError(self.source, f"ground truth {arr_name} of {self.name!r} is not finite")
        self.v_north = (
            numerical_velocity(self.time, self.north) if self.v_north is None else np.asarray(self.v_north, float).reshape(n)
        )
        self.v_east = (
            numerical_velocity(self.time, self.east) if self.v_east is None else np.asarray(self.v_east, float).reshape(n)
        )

    @property
    def start(self) -> float:
        return float(self.time[0])

    @property
    def end(self) -> float:
        return float(self.time[-1])

    def state_at(self, t: ArrayLike, tolerance: float = 1e-6) -> NDArray[np.float64]:
        """State ``[north, v_north, east, v_east]`` at times ``t`` (shape (…, 4)); NaN outside the span."""
        tt = np.asarray(t, dtype=float)
        out = np.stack([np.interp(tt, self.time, y) for y in (self.north, self.v_north, self.east, self.v_east)], axis=-1)
        outside = (tt < self.start - tolerance) | (tt > self.end + tolerance)
        out[outside] = np.nan
        return out


@dataclass
class TruthSet:
    """Ground truth of every target (never the ownship), by name."""

    targets: dict[str, TruthTrack] = field(default_factory=dict)
    source: str = "<memory>"

    @property
    def names(self) -> list[str]:
        return list(self.targets)

    def __getitem__(self, name: str) -> TruthTrack:
        return self.targets[name]

    def __len__(self) -> int:
        return len(self.targets)

    def states_at(self, t: ArrayLike) -> NDArray[np.float64]:
        """States of all targets at times ``t``: shape (n_targets, len(t), 4), NaN where undefined."""
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        if not self.targets:
            return np.empty((0, len(tt), 4))
        return np.stack([tr.state_at(tt) for tr in self.targets.values()])


def stationary_truth(points: ArrayLike, start: float, end: float, names: list[str] | None = None) -> TruthSet:
    """Vessels that do not move (a harbour's moored boats): each of ``points`` ((n, 2) north/east [m]) held still
    from ``start`` to ``end`` (POSIX s); named ``names`` or ``moored1``, ``moored2``, …"""
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    names = names or [f"moored{i + 1}" for i in range(len(p))]
    if len(names) != len(p):
        raise ValueError(f"{len(names)} names for {len(p)} points")
    t = np.array([start, max(end, start + 1.0)])
    return TruthSet({n: TruthTrack(n, t, np.full(2, q[0]), np.full(2, q[1]), np.zeros(2), np.zeros(2)) for n, q in zip(names, p)})


def truth_from_scenario(scenario) -> TruthSet:  # noqa: ANN001 - seatwin.scenario.Scenario
    """The targets of a :class:`seatwin.scenario.Scenario` (the ownship excluded), at their sample times."""
    out: dict[str, TruthTrack] = {}
    for vessel in scenario.targets:
        traj = vessel.trajectory
        s = traj.state_at(traj.time)
        out[vessel.name] = TruthTrack(vessel.name, s.time, s.north, s.east, s.v_north, s.v_east, source=scenario.source)
    if not out:
        raise InputError(scenario.source, "the scenario has no target vessel to evaluate against")
    return TruthSet(out, source=scenario.source)


def _is_recording(path: Path) -> bool:
    """A bag file, or a folder (our run directory or a rosbag2 directory); scenarios are files or names."""
    return path.suffix.lower() in RECORDING_SUFFIXES or path.name.lower().endswith(".db3.zstd") or path.is_dir()


def truth_from_scenario_file(path: Path) -> dict[str, VesselTruth]:
    """Every vessel's ground truth from a scenario file: a Gemini CSV (vessels ``V1``, ``V2``, …; the last
    is taken as the ownship, as in the Gemini data) or any format ``seatwin.scenario`` can load."""
    from seatwin.recording import VesselTruth

    if not path.is_file():
        raise InputError(path, "scenario file not found")
    if path.suffix.lower() == ".csv":
        from seatwin.scenario.gemini_csv import read_gemini_csv

        trajs = read_gemini_csv(path)
        last = max(trajs) if trajs else None
        vessels = [(f"V{n}", tr, n == last) for n, tr in trajs.items()]
    else:
        from seatwin.scenario.load import load_scenario

        sc = load_scenario(path)
        vessels = [(v.name, v.trajectory, getattr(v.role, "value", v.role) == "ownship") for v in sc.vessels]
    out = {}
    for name, tr, own in vessels:
        s = tr.state_at(tr.time)
        out[name] = VesselTruth(
            name,
            tr.time.copy(),
            s.north,
            s.east,
            np.zeros_like(s.north),
            s.heading,
            s.v_north,
            s.v_east,
            s.yaw_rate,
            ownship=own,
            source=str(path),
        )
    return out


def recording_truth(rec: Recording, scenario: str | os.PathLike[str] | None = None) -> dict[str, VesselTruth]:
    """Every vessel's ground truth for an open recording: from ``scenario`` if given, else the bag's
    odometry/pose topics, else the scenario file beside the bag (:meth:`Recording.scenario_file`)."""
    if scenario is not None:
        return truth_from_scenario_file(Path(scenario))
    truth = rec.ground_truth()
    if truth:
        return truth
    beside = rec.scenario_file()
    if beside is None:
        raise InputError(rec.bag, "no ground truth: no odometry/pose topics and no scenario file beside the bag")
    return truth_from_scenario_file(beside)


def truth_from_recording(path: str | os.PathLike[str]) -> TruthSet:
    """The targets' ground truth in a recording (:func:`recording_truth`).

    Velocities are re-derived from the positions by numerical differentiation, as in the thesis
    (5.2.1), whatever velocities the recording carries.
    """
    from seatwin.recording import open_bag

    with open_bag(path) as rec:
        vessels = recording_truth(rec)
    truth = targets_truth(vessels, str(path))
    if not len(truth):
        raise InputError(path, f"the recording has no target ground truth (vessels: {sorted(vessels)})")
    return truth


def targets_truth(vessels: dict[str, VesselTruth], source: str) -> TruthSet:
    """The targets (not the ownship) of a recording's vessel truth (:func:`recording_truth`) as a :class:`TruthSet`;
    velocities re-derived from the positions."""
    out = {name: TruthTrack(name, v.time, v.north, v.east, source=source) for name, v in vessels.items() if not v.ownship}
    return TruthSet(out, source=source)


def load_truth(spec: str | os.PathLike[str]) -> TruthSet:
    """Ground truth from a scenario (file or built-in name) or a recording (``.mcap``, ``.bag``, ``.db3``, ``.db3.zstd``
    or a folder)."""
    from seatwin.scenario.load import load_scenario

    path = Path(spec)
    if _is_recording(path):
        return truth_from_recording(path)
    return truth_from_scenario(load_scenario(str(spec)))
