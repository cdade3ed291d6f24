"""The radar model: one rotation → plots (and optionally raw spokes).

Per scan (frame ``k`` at time ``t``):

1. :func:`~seatwin.sensors.radar.geometry.illuminate` casts the fan through the engine and
   groups the hits per object (visible cells, width, height, range).
2. A vessel is detected with ``Pd(range, visible area)`` (:mod:`.detection`); a detected
   vessel lights all its cells. Land/quay cells cross the threshold independently with
   ``land.cell_pd``.
3. Every lit cell is smeared over the beam width in azimuth; :func:`.plots.extract_plots`
   merges touching cells into plots and splits large blobs.
4. Range and bearing noise (bias + Gaussian) is added to each plot; Poisson clutter
   (:mod:`.clutter`) adds false plots.

Random draws use ``frame_rng(seed, "radar/<name>/<what>", k)``: reruns are bit-identical
and frames independent of each other. The world is posed once per scan (at its stamp):
the motion of targets during one rotation is not modelled.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from seatwin.geo.angles import wrap_to_2pi
from seatwin.rng import frame_rng
from seatwin.sensors.radar.clutter import clutter_points
from seatwin.sensors.radar.config import RadarConfig
from seatwin.sensors.radar.detection import cell_intensity, detection_probability, snr_linear
from seatwin.sensors.radar.geometry import AntennaPose, ObjectReturns, illuminate
from seatwin.sensors.radar.plots import KIND_CLUTTER, KIND_LAND, KIND_VESSEL, Cells, extract_plots
from seatwin.sensors.radar.spokes import RadarSpokes, render_spokes

LAND = "land"
VESSEL = "vessel"


@dataclass
class RadarScan:
    """The plots of one rotation. Azimuth is radians clockwise from the bow; bearing from north."""

    time: float
    frame: int
    antenna: AntennaPose
    range_m: NDArray[np.float64]
    azimuth: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    n_cells: NDArray[np.int64]
    extent_m: NDArray[np.float64]
    object_id: NDArray[np.int64]
    """Object most of the plot's cells came from (−1 for clutter): ground truth, not a measurement."""
    kind: NDArray[np.int64]
    """0 vessel, 1 land, 2 clutter (``seatwin.sensors.radar.plots.KIND_NAMES``)."""
    intensity: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    """Peak echo intensity of the plot (0–255 scale of the spokes)."""
    spokes: RadarSpokes | None = None
    illuminated: list[ObjectReturns] = field(default_factory=list)

    def __len__(self) -> int:
        return int(self.range_m.shape[0])

    @property
    def bearing(self) -> NDArray[np.float64]:
        return wrap_to_2pi(self.antenna.heading + self.azimuth)

    @property
    def positions(self) -> NDArray[np.float64]:
        """(n, 2) world ``[north, east]`` of the plots."""
        return np.column_stack([self.north, self.east])


class RadarModel:
    """A rotating marine radar with parameters ``config`` and random streams keyed by ``seed``."""

    def __init__(self, config: RadarConfig, seed: int = 0, name: str = "radar"):
        self.config = config
        self.seed = int(seed)
        self.name = name

    def _rng(self, what: str, frame: int) -> np.random.Generator:
        return frame_rng(self.seed, f"radar/{self.name}/{what}", frame)

    def lit_cells(self, frame: int, objects: list[ObjectReturns], kinds: Mapping[int, str]) -> Cells:
        """Cells above threshold (before beam smearing): detected vessels and land cells."""
        cfg = self.config
        det = self._rng("detect", frame)
        land = self._rng("land", frame)
        parts = []
        # Draw in object-id order so the draws do not depend on the caster's output order.
        for obj in sorted(objects, key=lambda o: o.object_id):
            kind = kinds.get(obj.object_id, VESSEL)
            n = len(obj.spoke)
            if kind == LAND:
                if not cfg.land.enabled:
                    continue
                u = land.random(n)
                m = u < cfg.land.cell_pd
                r = cfg.range_start_m + (obj.sample[m] + 0.5) * cfg.range_increment_m
                cell_area = cfg.spoke_step * r * max(obj.height_m, 0.5)
                parts.append(
                    Cells(
                        obj.spoke[m], obj.sample[m], np.full(int(m.sum()), obj.object_id), snr_linear(r, cell_area, cfg.detection)
                    )
                )
            else:
                pd = float(detection_probability(obj.range_m, obj.area_m2, cfg.detection))
                if det.random() < pd:
                    snr = float(snr_linear(obj.range_m, obj.area_m2, cfg.detection))
                    parts.append(Cells(obj.spoke, obj.sample, np.full(n, obj.object_id), np.full(n, snr)))
        return Cells.concat(parts)

    def smear(self, cells: Cells) -> Cells:
        """Each cell seen by every spoke whose beam covers it (± half the beam width)."""
        k = self.config.beam_half_spokes
        if k == 0 or not len(cells):
            return cells.unique()
        off = np.arange(-k, k + 1)
        m = len(off)
        return Cells(
            ((cells.spoke[:, None] + off[None, :]) % self.config.n_spokes).ravel(),
            np.repeat(cells.sample, m),
            np.repeat(cells.object_id, m),
            np.repeat(cells.snr, m),
        ).unique()

    def scan(
        self,
        frame: int,
        time: float,
        antenna: AntennaPose,
        caster: object,
        kinds: Mapping[int, str] | None = None,
        exclude: frozenset[int] = frozenset(),
        with_spokes: bool | None = None,
    ) -> RadarScan:
        """Simulate one rotation starting at ``time`` from ``antenna`` against ``caster``'s world.

        ``kinds`` maps object ids to ``"vessel"`` (default) or ``"land"``; ``exclude`` are ids
        the antenna does not see (its own hull).
        """
        cfg = self.config
        kinds = kinds or {}
        objects = illuminate(cfg, antenna, caster, exclude)
        cells = self.smear(self.lit_cells(frame, objects, kinds))
        blobs = extract_plots(cells, cfg)
        noise = self._rng("noise", frame)
        n = len(blobs)
        nc = cfg.noise
        rng_m = blobs.range_m + nc.range_bias_m + nc.range_sigma_m * noise.standard_normal(n)
        az = wrap_to_2pi(blobs.azimuth + nc.bearing_bias + nc.bearing_sigma * noise.standard_normal(n))
        kind = np.array([KIND_LAND if kinds.get(int(o), VESSEL) == LAND else KIND_VESSEL for o in blobs.object_id], np.int64)
        keep = (rng_m >= cfg.min_range_m) & (rng_m <= cfg.max_range_m)
        bearing = antenna.heading + az
        north = antenna.north + rng_m * np.cos(bearing)
        east = antenna.east + rng_m * np.sin(bearing)
        # Clutter.
        cl = clutter_points(
            self._rng("clutter", frame), cfg.clutter, (antenna.north, antenna.east), cfg.min_range_m, cfg.max_range_m
        )
        c_rng = np.hypot(cl[:, 0] - antenna.north, cl[:, 1] - antenna.east)
        c_az = wrap_to_2pi(np.arctan2(cl[:, 1] - antenna.east, cl[:, 0] - antenna.north) - antenna.heading)
        nclut = len(cl)
        spokes = None
        if cfg.spokes.enabled if with_spokes is None else with_spokes:
            c_cells = Cells(
                np.floor(c_az / cfg.spoke_step).astype(np.int64),
                np.floor((c_rng - cfg.range_start_m) / cfg.range_increment_m).astype(np.int64),
                np.full(nclut, -1, np.int64),
                np.full(nclut, 3.0),
            )
            spokes = render_spokes(cfg, Cells.concat([cells, c_cells]), time, self._rng("spokes", frame))
        return RadarScan(
            time=float(time),
            frame=int(frame),
            antenna=antenna,
            range_m=np.concatenate([rng_m[keep], c_rng]),
            azimuth=np.concatenate([az[keep], c_az]),
            north=np.concatenate([north[keep], cl[:, 0]]),
            east=np.concatenate([east[keep], cl[:, 1]]),
            n_cells=np.concatenate([blobs.n_cells[keep], np.ones(nclut, np.int64)]),
            extent_m=np.concatenate([blobs.extent_m[keep], np.full(nclut, cfg.range_increment_m)]),
            object_id=np.concatenate([blobs.object_id[keep], np.full(nclut, -1, np.int64)]),
            kind=np.concatenate([kind[keep], np.full(nclut, KIND_CLUTTER, np.int64)]),
            intensity=np.concatenate(
                [
                    cell_intensity(blobs.snr[keep], cfg.spokes.noise_floor).astype(float),
                    cell_intensity(np.full(nclut, 3.0), cfg.spokes.noise_floor).astype(float),
                ]
            ),
            spokes=spokes,
            illuminated=objects,
        )
