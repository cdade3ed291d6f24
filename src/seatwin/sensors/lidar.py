"""The spinning lidar: beams posed per firing column, ranged, dropped, noised and packed.

Pipeline of one sweep (shared by every range model):

1. column times ``start + k/(rate·C)``; the carrier's pose at each (it moves during a sweep);
2. ray drop (thesis 4.2.2) drawn per beam from ``frame_rng(seed, stream + "/drop", frame)``
   *before* ranging — a dropped beam is never ranged, which gives the same points as
   dropping afterwards at a fraction of the cost;
3. world-frame beams, cut at the calm water (no water returns), ranged by the selected
   :mod:`range model <seatwin.sensors.rangemodel>` (``raycast`` or ``depthbuffer``);
4. the carrier's own hull/rig (fixed in the sensor frame: cast once, cached);
5. optional range dissipation, Gaussian range noise (σ = accuracy/2), intensity from
   reflectivity, incidence and range;
6. points in the sensor frame (REP-103), azimuth-major, with ring and time since the start.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError
from seatwin.geo.angles import circular_mean, wrap_to_pi
from seatwin.geo.frames import yaw_rotate
from seatwin.rng import frame_rng
from seatwin.scenario.model import Scenario
from seatwin.sensors.lidar_config import MILLIAMPERE_LIDAR_MOUNT, VLP16, LidarConfig, LidarMount
from seatwin.sensors.lidar_physics import cos_incidence, intensity, return_probability, water_limit
from seatwin.sensors.rangemodel import BeamBatch, BeamRanges, get_range_model
from seatwin.world.scene import Scene


@dataclass(frozen=True)
class LidarSweep:
    """One revolution's points, in the sensor frame (REP-103: x forward, y left, z up)."""

    stamp: float
    """POSIX time of the sweep's start (its first column)."""
    frame: int
    x: NDArray[np.float32]
    y: NDArray[np.float32]
    z: NDArray[np.float32]
    intensity: NDArray[np.float32]
    ring: NDArray[np.uint16]
    time: NDArray[np.float32]
    """Seconds since ``stamp`` of each point's firing."""
    object_id: NDArray[np.int32]
    """Ground-truth object hit (an id of the scene's ``objects``)."""
    sensor: str = "lidar"

    def __len__(self) -> int:
        return int(self.x.shape[0])

    @property
    def xyz(self) -> NDArray[np.float32]:
        return np.stack([self.x, self.y, self.z], axis=1)

    @property
    def range(self) -> NDArray[np.float32]:
        return np.sqrt(self.x * self.x + self.y * self.y + self.z * self.z)


@dataclass(frozen=True)
class RangedBeams:
    """The valid returns of some sweeps' every beam (no ray drop), before dissipation and noise
    (:meth:`Lidar.ranged`, :meth:`Lidar.redraw`): per return its beam, world direction, range, object and normal."""

    starts: tuple[float, ...]
    frames: tuple[int, ...]
    bounds: NDArray[np.intp]
    """Sweep j's returns are rows ``bounds[j]:bounds[j + 1]``."""
    beam: NDArray[np.intp]
    directions: NDArray[np.float32]
    range: NDArray[np.float32]
    object_id: NDArray[np.int32]
    normal: NDArray[np.float32]
    dirs: NDArray[np.float32] | None
    """Sensor-frame directions of the points where the range model samples other rays than the beams."""
    geometry: tuple
    """The lidar's beam pattern and mount they were ranged with."""


def _column_bearings(d_body: NDArray[np.float32], rings: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per column: the middle bearing of its beams (body frame) and half their spread."""
    d = d_body.reshape(-1, rings, 3).astype(np.float64)
    az = np.arctan2(d[..., 1], d[..., 0])
    mid = circular_mean(az, axis=1)
    spread = np.abs(wrap_to_pi(az - mid[:, None])).max(1)
    vertical = np.hypot(d[..., 0], d[..., 1]).min(1) < 1e-6
    spread[vertical] = np.pi
    return mid, spread


class Lidar:
    """A spinning lidar in a :class:`Scene`, carried by vessel ``platform`` (or fixed when None).

    Carriers move in 3 DOF (north, east, heading), so the sensor's height and each beam's
    angle to the water are fixed: the water cut-off per beam is computed once.
    """

    def __init__(
        self,
        scene: Scene,
        config: LidarConfig = VLP16,
        mount: LidarMount = MILLIAMPERE_LIDAR_MOUNT,
        platform: str | None = None,
        range_model: str = "raycast",
        seed: int = 0,
        stream: str = "lidar",
        self_returns: bool = True,
    ):
        self.scene, self.config, self.mount, self.platform = scene, config, mount, platform
        self.seed, self.stream = int(seed), stream
        self.range_model_name = range_model
        self._model = get_range_model(range_model)
        if platform is not None and platform not in scene.vessel_models:
            raise InputError(
                None, f"lidar carrier {platform!r} is not a vessel of the scene {scene.vessel_names}", where="platform"
            )
        if mount.z >= 0:
            raise InputError(None, f"the lidar must be above the water (mount z < 0 in NED), got z = {mount.z}", where="mount.z")
        cfg = config
        n, rings = cfg.beams, cfg.rings
        self.d_sensor = cfg.sensor_directions()
        rot = mount.rotation()
        self.d_body = (self.d_sensor.astype(np.float64) @ rot.T).astype(np.float32)
        self._bxy = (self.d_body[:, 0] + 1j * self.d_body[:, 1]).astype(np.complex64)
        self._bz = np.ascontiguousarray(self.d_body[:, 2])
        self._template = np.zeros_like(self.d_body)
        self._template[:, 2] = self._bz
        self._water = water_limit(np.full(n, mount.z, np.float32), self._bz, cfg.max_range)
        self.beam_column = np.repeat(np.arange(cfg.columns), rings)
        self._all_beams = np.arange(n)
        self._ring16 = np.tile(np.arange(rings, dtype=np.uint16), cfg.columns)
        self.column_offsets = cfg.column_offsets()
        self._offsets32 = self.column_offsets.astype(np.float32)
        self.column_bearing_body, self.column_halfwidth = _column_bearings(self.d_body, rings)
        self._self: tuple[NDArray[np.intp], NDArray[np.float32], NDArray[np.int32], NDArray[np.float32]] | None = None
        if platform is not None and self_returns:
            # The carrier is rigid with the sensor: its returns are the same every sweep.
            origins = np.broadcast_to(mount.translation.astype(np.float32), (n, 3))
            h = scene.vessel_caster(platform).cast(origins, self.d_body, self._water)
            # Hits inside the blind zone (the sensor touching its own rig in the model) do not block.
            beams = np.flatnonzero(h.hit & (h.range >= np.float32(cfg.min_range)))
            if beams.size:  # sparse: the few beams that meet the carrier itself
                self._self = (beams, h.range[beams], h.object_id[beams], h.geometric_normal[beams])
        self._geometry = (cfg.beams, cfg.columns, rings, mount)

    def _check_config(self) -> None:
        cfg = self.config
        if self._geometry != (cfg.beams, cfg.columns, cfg.rings, self.mount):
            raise InputError(None, "the lidar's beam pattern or mount changed; build a new Lidar", where="config")

    # ------------------------------------------------------------------ posing
    def column_times(self, start: float) -> NDArray[np.float64]:
        """POSIX firing time of every column of the sweep starting at ``start``."""
        return float(start) + self.column_offsets

    def _column_frames(
        self, times: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128]]:
        """Sensor origin (C, 3), carrier heading (C,) and exp(i·heading) at the column times."""
        m = self.mount
        if self.platform is None:
            return np.broadcast_to(m.translation, (len(times), 3)), np.zeros(len(times)), np.ones(len(times), complex)
        p = self.scene.pose(self.platform, times)
        ch, sh = np.cos(p.heading), np.sin(p.heading)
        o = np.empty((len(times), 3))
        o[:, 0] = p.north + ch * m.x - sh * m.y
        o[:, 1] = p.east + sh * m.x + ch * m.y
        o[:, 2] = m.z
        return o, p.heading, ch + 1j * sh

    def kept_beams(self, frame: int) -> NDArray[np.intp] | None:
        """Indices of the beams that survive the ray drop in ``frame`` (None: all of them).

        Thesis 4.2.2: each beam is dropped with probability p, drawn from uniform 32-bit
        integers u of ``frame_rng(seed, stream + "/drop", frame)``: dropped when u < p·2³².
        """
        cfg = self.config
        p = cfg.drop_probability
        if p <= 0:
            return None
        thr = int(round(p * 2.0**32))
        if thr >= 2**32:
            return np.zeros(0, np.intp)
        raw = frame_rng(self.seed, f"{self.stream}/drop", frame).bit_generator.random_raw((cfg.beams + 1) // 2)
        return np.flatnonzero(raw.view(np.uint32)[: cfg.beams] >= np.uint32(thr))

    def beams(self, start: float, frame: int = 0) -> BeamBatch:
        """The sweep's beams that survive the ray drop, posed in the world."""
        return self._batch([start], [frame])[0]

    def _batch(self, starts: Sequence[float], frames: Sequence[int], drop: bool = True) -> tuple[BeamBatch, NDArray[np.intp]]:
        """One batch of the beams of several sweeps (columns numbered across them; without ``drop``, every beam,
        as with no ray drop) and each beam's global index ``sweep · beams + beam``."""
        self._check_config()
        cfg = self.config
        k, c, n, rings = len(starts), cfg.columns, cfg.beams, cfg.rings
        times = (np.asarray(starts, dtype=np.float64)[:, None] + self.column_offsets[None, :]).reshape(-1)
        col_o, heading, turn128 = self._column_frames(times)
        # Horizontal parts as complex numbers: turning by the heading is one complex product,
        # written straight into the (M, 3) float32 directions through a complex64 view.
        turn = turn128.astype(np.complex64)
        kept = [self.kept_beams(f) if drop else None for f in frames]
        o32 = col_o.astype(np.float32)
        if all(i is None for i in kept):  # every beam: broadcast per column instead of gathering
            g = np.arange(k * n) if k > 1 else self._all_beams
            beam = np.tile(self._all_beams, k) if k > 1 else self._all_beams
            col = np.repeat(np.arange(k * c), rings) if k > 1 else self.beam_column
            d = np.empty((k * n, 3), np.float32)
            d[:, 2].reshape(k, n)[:] = self._bz
            np.multiply(
                self._bxy.reshape(1, c, rings), turn.reshape(k, c, 1), out=d[:, :2].view(np.complex64).reshape(k, c, rings)
            )
            o = np.repeat(o32, rings, axis=0)
            limit = np.tile(self._water, k) if k > 1 else self._water
        else:
            parts = [self._all_beams if i is None else i for i in kept]
            beam = np.concatenate(parts) if k > 1 else parts[0]
            g = np.concatenate([p + j * n for j, p in enumerate(parts)]) if k > 1 else beam
            col = g // rings
            d = np.empty((len(g), 3), np.float32)
            np.multiply(self._bxy[beam], turn[col], out=d[:, :2].view(np.complex64)[:, 0])
            d[:, 2] = self._bz[beam]
            o = np.take(o32, col, axis=0)
            limit = self._water[beam]
        batch = BeamBatch(
            origins=o,
            directions=d,
            max_range=limit,
            beam=beam,
            column=col,
            column_times=times,
            column_origins=col_o,
            column_bearing=np.tile(self.column_bearing_body, k) + heading,
            column_halfwidth=np.tile(self.column_halfwidth, k) if k > 1 else self.column_halfwidth,
            rings=rings,
            lidar_directions=self.d_sensor,
            exclude=(self.platform,) if self.platform is not None else (),
        )
        return batch, g

    # ------------------------------------------------------------------ sweeps
    def sweep(self, start: float, frame: int = 0) -> LidarSweep:
        """The points of the sweep that starts at POSIX time ``start``; ``frame`` keys its random draws."""
        return self.sweeps([start], [frame])[0]

    def sweeps(self, starts: Sequence[float], frames: Sequence[int] | None = None) -> list[LidarSweep]:
        """Several sweeps (``frames`` default 0, 1, …) ranged in one batch: the same points as one
        :meth:`sweep` call each, with the per-call overhead shared. Give consecutive sweeps
        (vessel culling covers the whole time span of the batch)."""
        frames = list(range(len(starts))) if frames is None else [int(f) for f in frames]
        if len(frames) != len(starts):
            raise InputError(None, f"{len(starts)} sweep starts but {len(frames)} frame numbers", where="frames")
        if not len(starts):
            return []
        cfg = self.config
        n = cfg.beams
        batch, g = self._batch(starts, frames)
        res: BeamRanges = self._model(self.scene, batch)
        rng, oid, nrm = res.range, res.object_id, res.normal
        if self._self is not None:
            rng, oid, nrm = self._merge_self_returns(batch, g, rng, oid, nrm)
        keep = np.flatnonzero((oid >= 0) & (rng >= np.float32(cfg.min_range)))
        bounds = np.searchsorted(g[keep], np.arange(len(starts) + 1) * n)
        dirs = self._sampled_directions(res, batch)
        out = []
        for j, (start, frame) in enumerate(zip(starts, frames)):
            mine = keep[bounds[j] : bounds[j + 1]]
            out.append(self._pack(float(start), frame, mine, batch.beam, batch.directions, rng, oid, nrm, dirs))
        return out

    def ranged(self, starts: Sequence[float], frames: Sequence[int]) -> RangedBeams:
        """Every beam of the sweeps at ``starts`` (random draws keyed by ``frames``) ranged as with no ray drop, kept for
        :meth:`redraw`: the ranging does not depend on the drop probability, the dissipation or the noise."""
        frames = [int(f) for f in frames]
        if len(frames) != len(starts):
            raise InputError(None, f"{len(starts)} sweep starts but {len(frames)} frame numbers", where="frames")
        n = self.config.beams
        batch, g = self._batch(starts, frames, drop=False)
        res: BeamRanges = self._model(self.scene, batch)
        rng, oid, nrm = res.range, res.object_id, res.normal
        if self._self is not None:
            rng, oid, nrm = self._merge_self_returns(batch, g, rng, oid, nrm)
        keep = np.flatnonzero((oid >= 0) & (rng >= np.float32(self.config.min_range)))
        dirs = self._sampled_directions(res, batch)
        return RangedBeams(
            tuple(float(t) for t in starts),
            tuple(frames),
            np.searchsorted(g[keep], np.arange(len(starts) + 1) * n),
            batch.beam[keep],
            batch.directions[keep],
            rng[keep],
            oid[keep],
            nrm[keep],
            None if dirs is None else dirs[keep],
            self._geometry,
        )

    def redraw(self, ranged: RangedBeams) -> list[LidarSweep]:
        """The sweeps of :meth:`ranged` with this lidar's ray drop, dissipation and noise: the same points as
        :meth:`sweeps` of the same starts and frames (with the raycast range model: bit-identical, tested), for any
        of those parameters at the cost of the drawing only. ``ranged`` must come from a lidar of the same scene,
        beam pattern and mount."""
        if ranged.geometry != self._geometry:
            raise InputError(None, "the ranged beams come from a lidar of another beam pattern or mount", where="ranged")
        out = []
        for j, (start, frame) in enumerate(zip(ranged.starts, ranged.frames)):
            a, b = ranged.bounds[j], ranged.bounds[j + 1]
            beam = ranged.beam[a:b]
            kept = self.kept_beams(frame)
            if kept is None:
                keep = np.arange(b - a)
            else:
                alive = np.zeros(self.config.beams, bool)
                alive[kept] = True
                keep = np.flatnonzero(alive[beam])
            dirs = None if ranged.dirs is None else ranged.dirs[a:b]
            out.append(
                self._pack(
                    start,
                    frame,
                    keep,
                    beam,
                    ranged.directions[a:b],
                    ranged.range[a:b],
                    ranged.object_id[a:b],
                    ranged.normal[a:b],
                    dirs,
                )
            )
        return out

    @staticmethod
    def _sampled_directions(res: BeamRanges, batch: BeamBatch) -> NDArray[np.float32] | None:
        """Per-beam sensor-frame directions of the points when the range model samples other
        rays than the beams (the depth buffer's pixel rays: their direction error is part of
        its error); None when points lie along the beams."""
        pts = getattr(res, "sensor_points", None)
        if pts is None or not len(pts):
            return None
        norm = np.linalg.norm(pts, axis=1, keepdims=True)
        ok = np.isfinite(norm[:, 0]) & (norm[:, 0] > 0)
        dirs = batch.sensor_directions.copy()
        dirs[ok] = (pts[ok] / norm[ok]).astype(np.float32)
        return dirs

    def _pack(
        self,
        start: float,
        frame: int,
        keep: NDArray[np.intp],
        beam: NDArray[np.intp],
        directions: NDArray[np.float32],
        rng: NDArray[np.float32],
        oid: NDArray[np.int32],
        nrm: NDArray[np.float32],
        dirs: NDArray[np.float32] | None = None,
    ) -> LidarSweep:
        """Dissipation, noise, intensity and the points of one sweep (``keep``: its valid returns; ``beam``,
        ``directions`` (world) and the rest per ranged beam)."""
        cfg = self.config
        if cfg.dissipation is not None:
            u = frame_rng(self.seed, f"{self.stream}/dissipation", frame).random(keep.size, dtype=np.float32)
            keep = keep[u < return_probability(rng[keep], cfg.dissipation)]
        sel = beam[keep]
        r = rng[keep]
        if self._noise_std > 0:
            r = r + self._noise_std * frame_rng(self.seed, f"{self.stream}/noise", frame).standard_normal(
                r.size, dtype=np.float32
            )
        ids = oid[keep]
        cos = cos_incidence(nrm[keep], directions[keep])
        inten = intensity(self.scene.reflectivity[ids], cos, r, cfg.intensity)
        ds = self.d_sensor[sel] if dirs is None else dirs[keep]
        return LidarSweep(
            stamp=start,
            frame=int(frame),
            x=r * ds[:, 0],
            y=r * ds[:, 1],
            z=r * ds[:, 2],
            intensity=inten,
            ring=self._ring16[sel],
            time=self._offsets32[self.beam_column[sel]],
            object_id=ids,
            sensor=cfg.name,
        )

    def _merge_self_returns(
        self, batch: BeamBatch, g: NDArray[np.intp], rng: NDArray[np.float32], oid: NDArray[np.int32], nrm: NDArray[np.float32]
    ) -> tuple[NDArray[np.float32], NDArray[np.int32], NDArray[np.float32]]:
        """Where the carrier's own hull/rig is nearer, take it (normals turned into the world)."""
        beams, s_rng, s_id, s_nrm = self._self  # type: ignore[misc]
        if not len(g):
            return rng, oid, nrm
        sweeps = len(batch.column_times) // self.config.columns
        want = (beams[None, :] + self.config.beams * np.arange(sweeps)[:, None]).reshape(-1)
        which = np.tile(np.arange(len(beams)), sweeps)
        pos = np.minimum(np.searchsorted(g, want), len(g) - 1)
        present = np.flatnonzero(g[pos] == want)
        at, which = pos[present], which[present]
        nearer = s_rng[which] < rng[at]
        at, which = at[nearer], which[nearer]
        if not at.size:
            return rng, oid, nrm
        rng, oid, nrm = rng.copy(), oid.copy(), nrm.copy()
        rng[at], oid[at] = s_rng[which], s_id[which]
        heading = self.scene.pose(self.platform, batch.column_times[batch.column[at]]).heading  # type: ignore[arg-type]
        c, s, nb = np.cos(heading), np.sin(heading), s_nrm[which]
        nrm[at] = np.stack([c * nb[:, 0] - s * nb[:, 1], s * nb[:, 0] + c * nb[:, 1], nb[:, 2]], axis=1)
        return rng, oid, nrm

    @property
    def _noise_std(self) -> np.float32:
        return np.float32(self.config.range_noise_std)

    def sensor_pose(self, t: float) -> tuple[NDArray[np.float64], float]:
        """Sensor origin (world NED) and carrier heading [rad] at time ``t``."""
        o, h, _ = self._column_frames(np.array([float(t)]))
        return o[0], float(h[0])


def sweep_starts(scenario: Scenario, config: LidarConfig = VLP16) -> NDArray[np.float64]:
    """Start times of every whole sweep within the scenario (frame k starts at ``start + k/rate``)."""
    n = int(np.floor(scenario.duration * config.rate_hz + 1e-9))
    return scenario.start + np.arange(n) / config.rate_hz


def lidar_for_scenario(
    scenario: Scenario,
    scene: Scene | None = None,
    config: LidarConfig = VLP16,
    mount: LidarMount | None = None,
    range_model: str = "raycast",
) -> Lidar:
    """The scenario's lidar: on its ownship's rig (milliAmpere's mount), seeded by the scenario."""
    if scenario.rig not in (None, "milliampere"):
        raise InputError(scenario.source, f"unknown sensor rig {scenario.rig!r}; known: 'milliampere'", where="rig")
    scene = scene or Scene.from_scenario(scenario)
    own = scenario.ownship
    return Lidar(
        scene,
        config,
        mount or MILLIAMPERE_LIDAR_MOUNT,
        platform=own.name if own is not None else None,
        range_model=range_model,
        seed=scenario.seed,
    )


def sweep_to_world(lidar: Lidar, sweep: LidarSweep) -> NDArray[np.float64]:
    """The sweep's points in the world frame (NED), each posed with the sensor at its own firing time."""
    p_s = np.stack([sweep.x, sweep.y, sweep.z], axis=1).astype(np.float64)
    p_b = p_s @ lidar.mount.rotation().T + lidar.mount.translation
    if lidar.platform is None:
        return p_b
    pose = lidar.scene.pose(lidar.platform, sweep.stamp + sweep.time.astype(np.float64))
    dn, de = yaw_rotate(pose.heading, p_b[:, 0], p_b[:, 1])
    out = np.empty_like(p_b)
    out[:, 0] = pose.north + dn
    out[:, 1] = pose.east + de
    out[:, 2] = p_b[:, 2]
    return out
