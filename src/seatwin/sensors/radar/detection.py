"""Probability of detecting a target in one scan, from its range and visible size.

The model is the textbook one for a non-coherent marine radar (not a thesis equation: the
thesis names a radar-cross-section model as future work): the signal-to-noise ratio falls
with the fourth power of range (radar equation) and grows with the target's visible area
(a stand-in for its radar cross section, which depends on size and aspect); a Swerling I
(slowly fluctuating) target in a square-law detector with false-alarm probability ``pfa``
is then detected with ``Pd = pfa^(1/(1+SNR))``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.sensors.radar.config import DetectionConfig


def snr_linear(range_m: ArrayLike, area_m2: ArrayLike, cfg: DetectionConfig) -> NDArray[np.float64]:
    """SNR (linear) = snr_ref · (A / area_ref) · (range_ref / R)^4."""
    r = np.maximum(np.asarray(range_m, float), 1e-3)
    a = np.maximum(np.asarray(area_m2, float), 0.0)
    return 10.0 ** (cfg.snr_ref_db / 10.0) * (a / cfg.area_ref_m2) * (cfg.range_ref_m / r) ** 4


def swerling1_pd(snr: ArrayLike, pfa: float) -> NDArray[np.float64]:
    """Swerling I detection probability ``pfa^(1/(1+SNR))`` (square-law detector, one pulse)."""
    return np.power(pfa, 1.0 / (1.0 + np.asarray(snr, float)))


def detection_probability(range_m: ArrayLike, area_m2: ArrayLike, cfg: DetectionConfig) -> NDArray[np.float64]:
    """Pd of a target at ``range_m`` whose visible area is ``area_m2``, capped at ``pd_max``."""
    return cfg.pd_max * swerling1_pd(snr_linear(range_m, area_m2, cfg), cfg.pfa)


def cell_intensity(snr: ArrayLike, noise_floor: float = 8.0) -> NDArray[np.uint8]:
    """An 8-bit echo intensity for a cell: the noise floor plus 10·log10(1+SNR) dB, 3 counts per dB."""
    db = 10.0 * np.log10(1.0 + np.maximum(np.asarray(snr, float), 0.0))
    return np.clip(np.round(noise_floor + 3.0 * db), 0, 255).astype(np.uint8)
