"""Simulated linear-Gaussian tracking problems: CV targets, noisy detections, uniform clutter.

Used by the tests (filter consistency) and by ``benchmarks/tracking.py``. Randomness only
through :func:`seatwin.rng.frame_rng` (one frame per scan).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.perception.measurements import MeasurementKind, Scan, cartesian_to_polar
from seatwin.rng import frame_rng
from seatwin.tracking.models import cv_process_noise, cv_transition

Array = NDArray[np.float64]


@dataclass(frozen=True)
class SimulatedRun:
    scans: list[Scan]
    truth: Array
    """(K, N_targets, 4) true states at each scan."""


def simulate(
    *,
    n_scans: int = 200,
    dt: float = 0.1,
    n_targets: int = 3,
    q: float = 0.3,
    r_cartesian: float = 4.0,
    r_range: float = 4.0,
    r_bearing: float = 1e-4,
    kind: MeasurementKind = MeasurementKind.CARTESIAN,
    p_detect: float = 0.9,
    clutter_mean: float = 10.0,
    area: tuple[float, float, float, float] = (-250.0, 250.0, -250.0, 250.0),
    sensor: str = "radar",
    sensor_position: tuple[float, float] = (0.0, 0.0),
    seed: int = 1,
) -> SimulatedRun:
    """Targets start spread over ``area`` at 2–6 m/s and move with CV process noise ``q``.

    Each scan detects each target with ``p_detect`` (noise per ``kind``) and adds
    Poisson(``clutter_mean``) clutter uniform over ``area``; the sensor sits at ``sensor_position``.
    """
    n0, n1, e0, e1 = area
    rng = frame_rng(seed, "tracking/sim/init", 0)
    x = np.column_stack(
        (
            rng.uniform(n0 * 0.6, n1 * 0.6, n_targets),
            rng.uniform(-4, 4, n_targets),
            rng.uniform(e0 * 0.6, e1 * 0.6, n_targets),
            rng.uniform(-4, 4, n_targets),
        )
    )
    F = cv_transition(dt)
    L = np.linalg.cholesky(cv_process_noise(dt, q, q) + 1e-15 * np.eye(4))
    scans, truth = [], []
    for k in range(n_scans):
        rng = frame_rng(seed, "tracking/sim/scan", k)
        if k:
            x = x @ F.T + rng.standard_normal((n_targets, 4)) @ L.T
        truth.append(x.copy())
        det = rng.random(n_targets) < p_detect
        pos = x[det][:, (0, 2)]
        n_c = rng.poisson(clutter_mean)
        clutter = np.column_stack((rng.uniform(n0, n1, n_c), rng.uniform(e0, e1, n_c)))
        if kind is MeasurementKind.CARTESIAN:
            zt = pos + rng.standard_normal(pos.shape) * np.sqrt(r_cartesian)
            z = np.concatenate((zt, clutter))
        else:
            zt = cartesian_to_polar(pos, sensor_position)
            zt = zt + rng.standard_normal(zt.shape) * np.sqrt([r_range, r_bearing])
            z = np.concatenate((zt, cartesian_to_polar(clutter, sensor_position)))
        z = z[rng.permutation(z.shape[0])]
        scans.append(
            Scan(
                time=1.0e9 + k * dt,
                sensor=sensor,
                kind=kind,
                z=z,
                sensor_north=sensor_position[0],
                sensor_east=sensor_position[1],
            )
        )
    return SimulatedRun(scans, np.array(truth))
