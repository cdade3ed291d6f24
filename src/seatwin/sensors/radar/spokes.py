"""Raw spokes in the layout of Gemini's ``RadarStreamingRequest``.

Fields (Autoferry Gemini ``sensor_streaming.proto``): ``range_start``, ``range_increment``
[m], ``num_spokes``, ``num_samples``, ``min_intensity``, ``max_intensity``,
``time_in_seconds`` and ``azimuth`` [rad] per spoke, and ``radar_spokes``: ``num_spokes ×
num_samples`` uint8 intensities, spoke-major. For users who run their own plot extraction.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.sensors.radar.config import RadarConfig
from seatwin.sensors.radar.detection import cell_intensity
from seatwin.sensors.radar.plots import Cells


@dataclass
class RadarSpokes:
    """One rotation of spokes (Gemini ``RadarStreamingRequest`` layout)."""

    range_start: float
    range_increment: float
    min_intensity: int
    max_intensity: int
    time_in_seconds: NDArray[np.float64]
    azimuth: NDArray[np.float64]
    """Per spoke, radians clockwise from the bow."""
    intensities: NDArray[np.uint8]
    """(num_spokes, num_samples)."""

    @property
    def num_spokes(self) -> int:
        return int(self.intensities.shape[0])

    @property
    def num_samples(self) -> int:
        return int(self.intensities.shape[1])

    def to_request_dict(self) -> dict[str, Any]:
        """The fields by their Gemini names (``radar_spokes`` as bytes)."""
        return {
            "range_start": float(self.range_start),
            "range_increment": float(self.range_increment),
            "num_spokes": self.num_spokes,
            "num_samples": self.num_samples,
            "min_intensity": int(self.min_intensity),
            "max_intensity": int(self.max_intensity),
            "time_in_seconds": self.time_in_seconds.tolist(),
            "azimuth": self.azimuth.tolist(),
            "radar_spokes": np.ascontiguousarray(self.intensities, np.uint8).tobytes(),
        }


def render_spokes(cfg: RadarConfig, cells: Cells, scan_start: float, rng: np.random.Generator) -> RadarSpokes:
    """Spokes of one rotation: Rayleigh background noise plus every cell's echo (strongest wins)."""
    ns, nr = cfg.n_spokes, cfg.n_samples
    sigma = cfg.spokes.noise_floor / np.sqrt(np.pi / 2.0)  # Rayleigh mean = σ·sqrt(π/2)
    img = np.clip(np.round(rng.rayleigh(sigma, (ns, nr))), 0, 255).astype(np.uint8)
    if len(cells):
        ok = (cells.sample >= 0) & (cells.sample < nr)
        val = cell_intensity(cells.snr[ok], cfg.spokes.noise_floor)
        np.maximum.at(img, (cells.spoke[ok] % ns, cells.sample[ok]), val)
    k = np.arange(ns)
    return RadarSpokes(
        range_start=cfg.range_start_m,
        range_increment=cfg.range_increment_m,
        min_intensity=0,
        max_intensity=255,
        time_in_seconds=scan_start + k * (cfg.rotation_period_s / ns),
        azimuth=(k + 0.5) * cfg.spoke_step,
        intensities=img,
    )
