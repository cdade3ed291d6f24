"""Small pure functions of the lidar's return model: intensity, return probability, noise."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from seatwin.sensors.lidar_config import IntensityModel, RangeDissipation


def intensity(
    reflectivity: NDArray[np.float32], cos_incidence: NDArray[np.float32], rng: NDArray[np.float32], model: IntensityModel
) -> NDArray[np.float32]:
    """``scale · ρ · |cos θ| · (r_ref / max(r, r_ref))^k`` clipped to [0, 255] (float32)."""
    ref = np.float32(model.reference_range)
    out = np.float32(model.scale) * reflectivity * np.abs(cos_incidence)
    if model.exponent:
        fall = ref / np.maximum(rng, ref)
        out *= fall if model.exponent == 1 else (fall * fall if model.exponent == 2 else fall ** np.float32(model.exponent))
    return np.clip(out, 0, 255, out=out).astype(np.float32, copy=False)


def return_probability(rng: NDArray[np.float32], model: RangeDissipation) -> NDArray[np.float32]:
    """Probability that a return at range ``rng`` reaches the receiver: a logistic fall-off."""
    z = (np.asarray(rng, np.float32) - np.float32(model.half_range)) / np.float32(model.width)
    return (1.0 / (1.0 + np.exp(np.minimum(z, np.float32(80.0))))).astype(np.float32)


def water_limit(origins_z: NDArray[np.float32], dir_z: NDArray[np.float32], max_range: float) -> NDArray[np.float32]:
    """Distance along each ray to the calm water plane z = 0 (NED, z down), capped at ``max_range``.

    Rays pointing down (dz > 0) from above the water meet it at −z₀/dz; the water gives no
    return, so nothing beyond that distance can be seen.
    """
    cap = np.float32(max_range)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(dir_z > 0, -origins_z / dir_z, cap)
    return np.minimum(t, cap).astype(np.float32, copy=False)


def cos_incidence(normals: NDArray[np.float32], directions: NDArray[np.float32]) -> NDArray[np.float32]:
    """|cos| of the angle between each ray and the surface normal (normals of any length)."""
    n = np.asarray(normals, np.float32)
    d = np.asarray(directions, np.float32)
    dot = n[:, 0] * d[:, 0] + n[:, 1] * d[:, 1] + n[:, 2] * d[:, 2]
    norm = np.sqrt(n[:, 0] * n[:, 0] + n[:, 1] * n[:, 1] + n[:, 2] * n[:, 2])
    norm[norm == 0] = 1.0
    return np.minimum(np.abs(dot) / norm, np.float32(1.0)).astype(np.float32, copy=False)
