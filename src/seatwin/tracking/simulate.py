"""Simulated linear-Gaussian tracking problems: CV targets, noisy detections, uniform clutter.

Used by the tests (filter consistency, numerics) and by ``benchmarks/tracking.py`` and
``benchmarks/tracking_numerics.py``. Randomness only through :func:`seatwin.rng.frame_rng`
(one frame per scan).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.perception.measurements import MeasurementKind, Scan, cartesian_to_polar
from seatwin.rng import frame_rng
from seatwin.tracking.config import TrackerConfig
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


STRESS_SENSORS = {"lidar": MeasurementKind.RANGE_BEARING, "radar": MeasurementKind.CARTESIAN, "camera": MeasurementKind.BEARING}
"""Sensors of :func:`stress_scans` and the kind of measurement each gives (tuning: preset ``synthetic``)."""


def stress_scans(n_scans: int, seed: int, max_clutter: int = 200) -> list[Scan]:
    """Random scans for numerical stress: the tracker must stay finite, symmetric PSD, r ∈ [0, 1].

    Five targets (CV, some crossing) seen by three sensors (:data:`STRESS_SENSORS`) in random
    order; per scan: a time step of 0 (same instant: another sensor or a repeated scan), 1 ms,
    0.1–2 s, or 30–300 s (a gap), chosen at random; clutter 0–``max_clutter`` plots (uniform
    count) uniform over 400 m × 400 m; each detection (P_D 0.9) repeated 1–3 times with
    probability 0.2 (duplicates), sometimes exactly, sometimes 1 mm apart; some targets 2 m apart.
    """
    rng = frame_rng(seed, "tracking/sim/stress", 0)
    x = np.column_stack((rng.uniform(-100, 100, 5), rng.uniform(-5, 5, 5), rng.uniform(-100, 100, 5), rng.uniform(-5, 5, 5)))
    x[1] = x[0] + [0.0, 0.0, 2.0, 0.0]  # two targets 2 m apart, same velocity
    names = list(STRESS_SENSORS)
    t = 1.0e9
    scans = []
    for k in range(n_scans):
        rng = frame_rng(seed, "tracking/sim/stress", k + 1)
        u = rng.random()
        dt = 0.0 if u < 0.2 else 1e-3 if u < 0.3 else float(rng.uniform(0.1, 2.0)) if u < 0.97 else float(rng.uniform(30, 300))
        t += dt
        x = x @ cv_transition(dt).T + rng.normal(0.0, 0.05, x.shape) * min(dt, 1.0)
        sensor = names[int(rng.integers(0, 3))]
        kind = STRESS_SENSORS[sensor]
        pos = x[rng.random(5) < 0.9][:, (0, 2)]
        pos = pos + rng.normal(0.0, 1.0, pos.shape)
        rep = np.where(rng.random(pos.shape[0]) < 0.2, rng.integers(2, 4, pos.shape[0]), 1)
        pos = np.repeat(pos, rep, axis=0)
        pos = pos + (rng.random(pos.shape[0]) < 0.5)[:, None] * rng.normal(0.0, 1e-3, pos.shape)
        n_c = int(rng.integers(0, max_clutter + 1))
        pos = np.concatenate((pos, rng.uniform(-200, 200, (n_c, 2))))
        sp = (float(rng.uniform(-300, 300)), float(rng.uniform(-300, 300)))
        if kind is MeasurementKind.CARTESIAN:
            z = pos
        else:
            z = cartesian_to_polar(pos, sp)
            if kind is MeasurementKind.BEARING:
                z = z[:, 1:]
        scans.append(Scan(time=t, sensor=sensor, kind=kind, z=z, sensor_north=sp[0], sensor_east=sp[1]))
    return scans


def state_violations(P: Array, r: Array, x: Array) -> list[str]:
    """What is wrong with a tracker state: non-finite, asymmetric or non-PSD covariances, r ∉ [0, 1]."""
    out = []
    if not np.isfinite(x).all():
        out.append("non-finite state")
    if not np.isfinite(P).all():
        return [*out, "non-finite covariance"]
    if not ((r >= 0.0) & (r <= 1.0)).all():
        out.append(f"existence outside [0, 1]: {r[(r < 0) | (r > 1)][:3]}")
    if P.shape[0]:
        scale = np.abs(P).max(axis=(1, 2))
        if (np.abs(P - np.swapaxes(P, 1, 2)).max(axis=(1, 2)) > 1e-12 * scale).any():
            out.append("asymmetric covariance")
        lo = np.linalg.eigvalsh(0.5 * (P + np.swapaxes(P, 1, 2)))[:, 0]
        if (lo < -1e-9 * scale).any():
            out.append(f"covariance not PSD: min eigenvalue {lo.min():.3g}")
    return out


def stress_tuning(max_clutter: int = 200, matched: bool = True) -> TrackerConfig:
    """The tuning for :func:`stress_scans`: preset ``synthetic``; if ``matched``, its clutter densities
    set to the scans' mean clutter and a χ² gate P_G = 0.99 (else the preset as it is, g = 1 and
    clutter densities far below the scans': many false tracks, a harder case)."""
    from seatwin.tracking.config import load_tuning

    cfg = load_tuning("synthetic")
    if not matched:
        return cfg
    data = cfg.model_dump()
    mean = max(max_clutter, 1) / 2.0
    for name, tuning in data["sensors"].items():
        tuning["clutter_density"] = mean / (2.0 * np.pi) if name == "camera" else mean / 400.0**2
    data.update(name="stress", gate_g=None, gate_probability=0.99)
    return TrackerConfig.model_validate(data)
