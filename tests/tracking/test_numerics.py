"""Tracker numerics: time order enforced by ``JIPDATracker.step``; random scans keep the state valid.

The full 10^5-scan run is ``benchmarks/tracking_numerics.py``; here a bounded budget of the
same generator (:func:`seatwin.tracking.simulate.stress_scans`: clutter 0–200, duplicate
detections, zero and 1 ms time steps, long gaps, three sensors of three measurement kinds).
"""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.perception import MeasurementKind, Scan
from seatwin.tracking import JIPDATracker
from seatwin.tracking.simulate import state_violations, stress_scans, stress_tuning


def _scan(t: float, z) -> Scan:
    return Scan(time=t, sensor="radar", kind=MeasurementKind.CARTESIAN, z=np.asarray(z, float))


def test_step_rejects_a_scan_earlier_than_the_last() -> None:
    tr = JIPDATracker(stress_tuning())
    for k in range(4):
        tr.step(_scan(10.0 + k, [[0.0, 1.0 * k], [50.0, 0.0]]))
    assert tr.r.size
    before = (tr.x.copy(), tr.P.copy(), tr.r.copy(), tr.time)
    with pytest.raises(InputError, match=r"scans out of time order: a radar scan at 12\.5 after 13\.0"):
        tr.step(_scan(12.5, [[0.0, 3.0]]))
    assert np.array_equal(tr.x, before[0]) and np.array_equal(tr.P, before[1]) and np.array_equal(tr.r, before[2])
    assert tr.time == before[3]
    tr.step(_scan(13.0, [[0.0, 3.0]]))  # the same instant again (zero time step) is fine


@pytest.mark.parametrize(
    "scan,msg",
    [(_scan(float("nan"), [[0.0, 0.0]]), "time must be finite"), (_scan(1.0, [[np.inf, 0.0]]), "non-finite measurements")],
)
def test_step_rejects_non_finite_input(scan, msg) -> None:
    with pytest.raises(InputError, match=msg):
        JIPDATracker(stress_tuning()).step(scan)


def test_state_violations_detects_each_fault() -> None:
    P = np.eye(4)[None].repeat(2, axis=0)
    x, r = np.zeros((2, 4)), np.array([0.5, 1.0])
    assert state_violations(P, r, x) == []
    bad = P.copy()
    bad[1, 0, 1] = 0.5
    assert state_violations(bad, r, x) == ["asymmetric covariance"]
    bad = P.copy()
    bad[0, 0, 0] = -1.0
    assert any("not PSD" in v for v in state_violations(bad, r, x))
    assert any("existence" in v for v in state_violations(P, np.array([0.5, 1.0 + 1e-12]), x))
    bad = P.copy()
    bad[0, 2, 2] = np.nan
    assert state_violations(bad, r, x) == ["non-finite covariance"]


@pytest.mark.parametrize("matched,n_scans", [(True, 600), (False, 300)], ids=["matched", "preset"])
def test_random_scans_keep_covariances_psd_and_existence_in_unit_interval(matched, n_scans) -> None:
    tr = JIPDATracker(stress_tuning(200, matched=matched))
    most = 0
    for k, scan in enumerate(stress_scans(n_scans, seed=3 + matched)):
        tr.step(scan)
        most = max(most, tr.r.size)
        assert state_violations(tr.P, tr.r, tr.x) == [], f"scan {k}"
    assert most >= 10  # the generator does make crowded, ambiguous scans
