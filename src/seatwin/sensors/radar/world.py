"""The radar in a :class:`seatwin.world.scene.Scene`: pose the antenna on the ownship, cast at any time.

Vessels are cast in their own body frames (the scene's per-vessel casters: no geometry is
rebuilt per scan) and the static harbour in the world frame; the nearest hit of each ray
wins, so vessels occlude land and each other. Objects labelled ``quay``, ``pier`` or
``building`` (and any static object other than a moored boat) are land for the radar.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from seatwin.engine import RayHits
from seatwin.errors import InputError
from seatwin.geo import TWO_PI, wrap_to_2pi, yaw_matrix
from seatwin.sensors.radar.geometry import AntennaPose
from seatwin.sensors.radar.model import LAND, VESSEL, RadarModel, RadarScan

VESSEL_LABELS = frozenset({"vessel", "moored_boat"})


class SceneCaster:
    """A ray caster over a scene posed at one time (static world + vessels in body frames)."""

    def __init__(
        self, scene: object, time: float, exclude: Sequence[str] = (), sweep: tuple[float, float, float, float] | None = None
    ):
        """``sweep = (antenna_north, antenna_east, heading, rotation_period)``: pose each vessel when the
        beam (spoke 0 at the bow at ``time``, turning clockwise) passes it, not at ``time``."""
        self.scene = scene
        self.time = float(time)
        self.sweep = sweep
        self.vessels = [n for n in scene.vessel_names if n not in exclude]  # type: ignore[attr-defined]

    def pose_time(self, name: str) -> float:
        """When vessel ``name`` is seen: the scan time, or the time the beam passes it."""
        if self.sweep is None:
            return self.time
        n0, e0, heading, period = self.sweep
        p = self.scene.pose(name, self.time)  # type: ignore[attr-defined]
        frac = wrap_to_2pi(np.arctan2(float(p.east) - e0, float(p.north) - n0) - heading) / TWO_PI
        t = self.time + frac * period
        try:
            self.scene.pose(name, t)  # type: ignore[attr-defined]
        except InputError:  # past the end of the trajectory: the last pose we have is the scan time's
            return self.time
        return t

    def _radius(self, name: str) -> float:
        """Radius of a sphere about the body origin holding the whole vessel mesh (+1 m)."""
        v = np.asarray(self.scene.vessel_models[name].mesh.vertices)  # type: ignore[attr-defined]
        return float(np.sqrt((v**2).sum(axis=1)).max()) + 1.0

    def cast(self, origins: ArrayLike, directions: ArrayLike, max_range: float = np.inf) -> RayHits:
        o = np.asarray(origins, np.float64).reshape(-1, 3)
        d = np.asarray(directions, np.float64).reshape(-1, 3)
        n = len(d)
        if self.scene.static_meshes:  # type: ignore[attr-defined]
            best = self.scene.static_caster.cast(o, d, max_range)  # type: ignore[attr-defined]
            rng, oid, nrm = np.array(best.range), np.array(best.object_id), np.array(best.normal)
        else:
            rng, oid, nrm = np.full(n, np.inf, np.float32), np.full(n, -1, np.int32), np.zeros((n, 3), np.float32)
        one_origin = n > 0 and bool((o == o[0]).all())
        for name in self.vessels:
            p = self.scene.pose(name, self.pose_time(name))  # type: ignore[attr-defined]
            rot = yaw_matrix(float(p.heading))  # body → world
            t = np.array([float(p.north), float(p.east), 0.0])
            # Cull: only rays passing within the vessel's bounding sphere can hit it.
            radius = self._radius(name)
            if one_origin:
                rel0 = t - o[0]
                along = np.maximum(d @ rel0, 0.0)
                perp2 = rel0 @ rel0 - 2.0 * along * (d @ rel0) + along * along
            else:
                rel = t - o
                along = np.maximum(np.einsum("ij,ij->i", rel, d), 0.0)
                diff = rel - along[:, None] * d
                perp2 = np.einsum("ij,ij->i", diff, diff)
            near = (perp2 <= radius * radius) & (along <= max_range + radius)
            if not near.any():
                continue
            idx = np.flatnonzero(near)
            hits = self.scene.vessel_caster(name).cast((o[idx] - t) @ rot, d[idx] @ rot, max_range)  # type: ignore[attr-defined]
            closer = hits.range < rng[idx]
            j = idx[closer]
            rng[j] = hits.range[closer]
            oid[j] = hits.object_id[closer]
            nrm[j] = (hits.normal[closer].astype(np.float64) @ rot.T).astype(np.float32)
        return RayHits(rng, oid, nrm)


def object_kinds(scene: object) -> dict[int, str]:
    """Object id → ``"vessel"`` or ``"land"`` for the radar."""
    return {o.id: (VESSEL if o.label in VESSEL_LABELS else LAND) for o in scene.objects}  # type: ignore[attr-defined]


def antenna_pose(model: RadarModel, scene: object, ownship: str, time: float) -> AntennaPose:
    """The antenna on ``ownship`` at ``time`` (mount offset rotated by the heading)."""
    p = scene.pose(ownship, time)  # type: ignore[attr-defined]
    h = float(p.heading)
    cfg = model.config
    north = float(p.north) + cfg.mount_x_m * np.cos(h) - cfg.mount_y_m * np.sin(h)
    east = float(p.east) + cfg.mount_x_m * np.sin(h) + cfg.mount_y_m * np.cos(h)
    return AntennaPose(north, east, h, cfg.antenna_height_m)


def scan_scene(
    model: RadarModel, scene: object, ownship: str, frame: int, time: float, with_spokes: bool | None = None
) -> RadarScan:
    """One rotation of ``model`` on ``ownship`` in ``scene`` at ``time`` (frame index ``frame``)."""
    ant = antenna_pose(model, scene, ownship, time)
    sweep = (ant.north, ant.east, ant.heading, model.config.rotation_period_s) if model.config.pose_at == "beam" else None
    caster = SceneCaster(scene, time, exclude=(ownship,), sweep=sweep)
    return model.scan(frame, time, ant, caster, object_kinds(scene), with_spokes=with_spokes)


def scan_times(start: float, end: float, rotation_period: float) -> np.ndarray:
    """Scan stamps every rotation from ``start`` up to ``end``."""
    n = int(np.floor((end - start) / rotation_period + 1e-9)) + 1
    return start + np.arange(n) * rotation_period
