"""On simulated linear-Gaussian data the tracker is consistent: ANEES inside its χ² bounds (5.28).

NEES samples of one run are correlated in time, which the χ² bounds do not allow for; the
test therefore pools independent Monte Carlo runs and takes every 10th scan.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import chi2

from seatwin.perception import MeasurementKind
from seatwin.tracking import JIPDATracker, TrackerConfig
from seatwin.tracking.simulate import simulate

SENSOR = (-1500.0, 0.0)  # far enough that the range-bearing model is nearly linear over a gate


def _nees(kind: MeasurementKind, clutter_mean: float, seed: int) -> tuple[list[float], int]:
    run = simulate(
        n_scans=150,
        dt=1.0,
        n_targets=3,
        q=0.3,
        r_cartesian=9.0,
        r_range=9.0,
        r_bearing=2.5e-5,
        kind=kind,
        p_detect=0.95,
        clutter_mean=clutter_mean,
        area=(-600, 600, -600, 600),
        sensor_position=SENSOR,
        seed=seed,
    )
    cfg = TrackerConfig(
        q_north=0.3,
        q_east=0.3,
        gate_g=None,
        gate_probability=0.999,
        # The random-walk targets reach 10–20 m/s, beyond the default v_max: no speed gate here
        # (tests/tracking/test_speed_gate.py tests it).
        speed_gate_sigma=None,
        speed_gate_scans=None,
        sensors={
            "radar": dict(
                r_range=9.0, r_bearing=2.5e-5, r_cartesian=9.0, p_detect=0.95, clutter_density=max(clutter_mean, 1e-3) / 1200**2
            )
        },
    )
    tr = JIPDATracker(cfg)
    nees, ids = [], set()
    for k, scan in enumerate(run.scans):
        out = tr.step(scan)
        if k % 10 or k == 0:
            continue
        c = np.flatnonzero(out.confirmed)
        for x_true in run.truth[k]:
            d = np.hypot(out.x[c, 0] - x_true[0], out.x[c, 2] - x_true[2])
            if c.size and d.min() < 20.0:
                i = c[np.argmin(d)]
                e = out.x[i] - x_true
                nees.append(float(e @ np.linalg.solve(out.P[i], e)))
                ids.add(int(out.track_id[i]))
    return nees, len(ids)


@pytest.mark.parametrize(
    "kind,clutter", [(MeasurementKind.CARTESIAN, 0.0), (MeasurementKind.RANGE_BEARING, 0.0), (MeasurementKind.CARTESIAN, 10.0)]
)
def test_anees_inside_chi2_bounds(kind, clutter) -> None:
    nees: list[float] = []
    for seed in range(10):
        values, n_tracks = _nees(kind, clutter, seed)
        assert n_tracks == 3  # each target keeps one track: no switches, no losses
        nees += values
    n = len(nees)
    assert n >= 0.98 * 10 * 14 * 3  # every target tracked at (nearly) every sampled scan
    anees = float(np.mean(nees))
    lo, hi = chi2.ppf(0.025, 4 * n) / n, chi2.ppf(0.975, 4 * n) / n
    assert lo <= anees <= hi, (anees, lo, hi)
