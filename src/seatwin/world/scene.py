"""The world of a scenario: static harbour geometry built once, vessels posed at any time(s).

Static objects are committed once into one ray caster in the world frame (NED). Each
vessel keeps its own caster in its *body* frame: a sensor moving through a sweep
transforms each ray into a vessel's frame at that ray's own time instead of rebuilding
geometry per pose (see ``docs/architecture/lidar.md``). Rasterising back ends get
world-frame triangles of the scene posed at one time from :meth:`Scene.posed_meshes`.

Object ids: static objects first (0 … S−1), then the vessels in scenario order.

The world does not import :mod:`seatwin.scenario`: it takes anything shaped like a
scenario (:class:`ScenarioLike`, :class:`Track`), so the two packages stay independent.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.engine import MeshData, RayCaster, make_caster
from seatwin.errors import InputError, ParameterError
from seatwin.geo import unwrap, wrap_to_pi, yaw_matrix
from seatwin.world.harbour import build_harbour
from seatwin.world.objects import WorldObject
from seatwin.world.vessels import VesselModel, vessel_model


class Track(Protocol):
    """What a scene needs of a vessel's trajectory (:class:`seatwin.scenario.Trajectory` is one):
    samples of time [s], north, east [m], heading [rad], and ``state_at`` raising an
    :class:`~seatwin.errors.InputError` for times outside ``[start, end]``."""

    @property
    def time(self) -> NDArray[np.float64]: ...
    @property
    def north(self) -> NDArray[np.float64]: ...
    @property
    def east(self) -> NDArray[np.float64]: ...
    @property
    def heading(self) -> NDArray[np.float64]: ...
    @property
    def start(self) -> float: ...
    @property
    def end(self) -> float: ...
    def state_at(self, t: ArrayLike) -> Any: ...


class VesselLike(Protocol):
    """A scenario's vessel as a scene reads it (:class:`seatwin.scenario.Vessel`)."""

    @property
    def name(self) -> str: ...
    @property
    def model(self) -> str: ...
    @property
    def dimensions(self) -> Any: ...
    @property
    def trajectory(self) -> Track: ...


class ScenarioLike(Protocol):
    """A scenario as a scene reads it (:class:`seatwin.scenario.Scenario`)."""

    @property
    def source(self) -> str: ...
    @property
    def environment(self) -> Mapping[str, Any]: ...
    @property
    def vessels(self) -> Sequence[VesselLike]: ...


@dataclass(frozen=True)
class ObjectInfo:
    """One object id of a scene."""

    id: int
    name: str
    label: str
    reflectivity: float
    dynamic: bool


@dataclass(frozen=True)
class Poses:
    """Vessel poses at one or more times: north, east [m], heading [rad] (arrays like the times)."""

    north: NDArray[np.float64]
    east: NDArray[np.float64]
    heading: NDArray[np.float64]


class _PoseTrack:
    """Fast pose interpolation of one trajectory (linear, heading unwrapped) — as ``state_at``."""

    def __init__(self, traj: Track):
        self.traj = traj
        self.time = traj.time
        self.north = traj.north
        self.east = traj.east
        self.heading = unwrap(traj.heading)

    def at(self, t: ArrayLike) -> Poses:
        tt = np.asarray(t, dtype=np.float64)
        if tt.size and (float(tt.min()) < self.traj.start - 1e-6 or float(tt.max()) > self.traj.end + 1e-6 or np.isnan(tt).any()):
            self.traj.state_at(tt)  # raises the scenario's own InputError naming the span
        return Poses(
            np.interp(tt, self.time, self.north), np.interp(tt, self.time, self.east), np.interp(tt, self.time, self.heading)
        )


class Scene:
    """Static objects plus vessels (model + trajectory), with ray casters for both."""

    def __init__(
        self,
        static_objects: Sequence[WorldObject],
        vessels: Mapping[str, tuple[VesselModel, Track]] | None = None,
        backend: str = "embree",
        threads: int | None = None,
    ):
        self.backend = backend
        self.threads = threads
        self.static_objects = list(static_objects)
        self.vessel_models: dict[str, VesselModel] = {}
        self._tracks: dict[str, _PoseTrack] = {}
        objects = [ObjectInfo(i, o.name, o.label, float(o.reflectivity), False) for i, o in enumerate(self.static_objects)]
        self.vessel_ids: dict[str, int] = {}
        for name, (model, traj) in (vessels or {}).items():
            self.vessel_ids[name] = len(objects)
            objects.append(ObjectInfo(len(objects), name, "vessel", float(model.reflectivity), True))
            self.vessel_models[name] = model
            self._tracks[name] = _PoseTrack(traj)
        self.objects = objects
        self.vessel_radius = {n: m.radius for n, m in self.vessel_models.items()}
        """Horizontal bounding radius of each vessel about its body origin [m]."""
        self.reflectivity = np.asarray([o.reflectivity for o in objects] + [0.0], dtype=np.float32)
        """Reflectivity by object id; index −1 (a miss) gives 0."""
        self.static_meshes = [MeshData.from_trimesh(o.mesh, i) for i, o in enumerate(self.static_objects)]
        self.static_caster: RayCaster = make_caster(self.static_meshes, backend, threads)
        self._vessel_casters: dict[str, RayCaster] = {}

    @classmethod
    def from_scenario(
        cls,
        scenario: ScenarioLike,
        harbour: object | None = None,
        backend: str = "embree",
        threads: int | None = None,
    ) -> Scene:
        """The scene of ``scenario``: its harbour (``environment['harbour']`` unless ``harbour`` is
        given) and every vessel with the 3-D model its ``model`` names."""
        spec = harbour if harbour is not None else scenario.environment.get("harbour", "default")
        if harbour is None and isinstance(spec, str) and Path(spec).suffix.lower() in (".bin", ".yaml", ".yml"):
            # A raster named in a scenario file is found relative to that file.
            beside = Path(scenario.source).parent / spec
            if not Path(spec).is_absolute() and beside.is_file():
                spec = str(beside)
        water = scenario.environment.get("water", "flat")
        if water not in (None, "flat", "calm"):
            raise InputError(scenario.source, f"water {water!r} is not supported; only 'flat'", where="environment.water")
        try:
            static = build_harbour(spec)
        except InputError as exc:
            if harbour is not None:  # the caller's override is at fault, not the scenario
                raise ParameterError("harbour", exc.detail if exc.source is None else f"{exc.source}: {exc.detail}") from exc
            raise InputError(scenario.source, exc.detail, where=exc.where) from exc
        vessels = {v.name: (vessel_model(v.model, v.dimensions, scenario.source, v.mesh), v.trajectory) for v in scenario.vessels}
        return cls(static, vessels, backend, threads)

    @property
    def vessel_names(self) -> list[str]:
        return list(self.vessel_models)

    @property
    def moored_boats(self) -> dict[str, int]:
        """The harbour's moored boats (static objects labelled ``moored_boat``): name → object id."""
        return {o.name: i for i, o in enumerate(self.static_objects) if o.label == "moored_boat"}

    def pose(self, name: str, t: ArrayLike) -> Poses:
        """Pose of vessel ``name`` at time(s) ``t`` (heading unwrapped, not wrapped to ±π)."""
        if name not in self._tracks:
            raise InputError(None, f"no vessel named {name!r}; vessels are {self.vessel_names}")
        return self._tracks[name].at(t)

    def update_trajectory(self, name: str, traj: Track) -> None:
        """Pose vessel ``name`` along ``traj`` from now on (a trajectory that grows, as in ``seatwin serve``)."""
        if name not in self._tracks:
            raise InputError(None, f"no vessel named {name!r}; vessels are {self.vessel_names}")
        self._tracks[name] = _PoseTrack(traj)

    def motion_circle(self, name: str, t0: float, t1: float) -> tuple[float, float, float]:
        """A circle (north, east, radius) holding vessel ``name``'s whole footprint during [t0, t1].

        The track is piecewise linear, so it stays inside the hull of its positions at t0,
        t1 and the samples between: the circle about the middle of the two ends reaching the
        farthest of them, grown by the vessel's own radius.
        """
        track = self._tracks[name]
        ends = track.at(np.array([t0, t1]))
        i0, i1 = np.searchsorted(track.time, [t0, t1], side="right")
        n = np.concatenate((ends.north, track.north[i0:i1]))
        e = np.concatenate((ends.east, track.east[i0:i1]))
        cn, ce = 0.5 * (n[0] + n[1]), 0.5 * (e[0] + e[1])
        spread = float(np.sqrt(((n - cn) ** 2 + (e - ce) ** 2).max()))
        return float(cn), float(ce), spread + self.vessel_radius[name]

    def vessel_caster(self, name: str) -> RayCaster:
        """The caster of vessel ``name``'s mesh in its body frame (built on first use)."""
        if name not in self._vessel_casters:
            mesh = MeshData.from_trimesh(self.vessel_models[name].mesh, self.vessel_ids[name])
            self._vessel_casters[name] = make_caster([mesh], self.backend, self.threads)
        return self._vessel_casters[name]

    def vessel_mesh_at(self, name: str, t: float) -> MeshData:
        """Vessel ``name``'s mesh posed in the world frame at time ``t``."""
        p = self.pose(name, t)
        rot = yaw_matrix(float(p.heading))
        mesh = MeshData.from_trimesh(self.vessel_models[name].mesh, self.vessel_ids[name])
        return mesh.transformed(rot, [float(p.north), float(p.east), 0.0])

    def posed_meshes(self, t: float, exclude: Sequence[str] = ()) -> list[MeshData]:
        """Every mesh of the scene in the world frame at time ``t`` (vessels in ``exclude`` left out)."""
        return self.static_meshes + [self.vessel_mesh_at(n, t) for n in self.vessel_names if n not in exclude]

    def label_of(self, object_id: ArrayLike) -> NDArray[np.str_]:
        """Labels of object ids (``""`` for −1)."""
        labels = np.asarray([o.label for o in self.objects] + [""])
        return labels[np.asarray(object_id)]

    def heading_wrapped(self, name: str, t: ArrayLike) -> NDArray[np.float64]:
        return np.asarray(wrap_to_pi(self.pose(name, t).heading), float)
