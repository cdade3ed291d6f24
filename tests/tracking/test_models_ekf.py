"""EKF (Algorithm 2) and models: Jacobians, agreement with the linear Kalman filter (Algorithm 1)."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.perception import MeasurementKind, Scan
from seatwin.tracking import JIPDATracker, TrackerConfig, ekf
from seatwin.tracking.models import (
    BearingModel,
    CartesianModel,
    RangeBearingModel,
    cv_process_noise,
    cv_transition,
)

X = np.array([[120.0, 2.0, -40.0, -1.0], [-30.0, 0.5, 80.0, 3.0], [5.0, 0.0, 0.5, 0.0]])


def test_cv_model_hand_values() -> None:
    F = cv_transition(0.5)
    assert np.allclose(F @ [1, 2, 3, 4], [2, 2, 5, 4])
    Q = cv_process_noise(2.0, 0.3, 0.2)
    assert np.allclose(Q[:2, :2], 0.3 * np.array([[8 / 3, 2], [2, 2]]))
    assert np.allclose(Q[2:, 2:], 0.2 * np.array([[8 / 3, 2], [2, 2]]))
    assert np.all(Q[:2, 2:] == 0)


@pytest.mark.parametrize(
    "model",
    [
        RangeBearingModel(np.eye(2), 3.0, -7.0),
        BearingModel(np.eye(1), -2.0, 4.0),
        CartesianModel(np.eye(2)),
    ],
)
def test_jacobian_matches_finite_differences(model) -> None:
    zhat, H = model.predict(X)
    eps = 1e-6
    for i in range(4):
        dx = np.zeros(4)
        dx[i] = eps
        zp, _ = model.predict(X + dx)
        zm, _ = model.predict(X - dx)
        num = (zp - zm) / (2 * eps)
        if model.angle_index is not None:
            num[:, model.angle_index] = (np.angle(np.exp(1j * (zp - zm)[:, model.angle_index]))) / (2 * eps)
        assert np.allclose(H[:, :, i], num, atol=1e-7)


def test_range_bearing_hand_values() -> None:
    m = RangeBearingModel(np.eye(2), 0.0, 0.0)
    zhat, _ = m.predict(np.array([[3.0, 0, 4.0, 0], [-1.0, 0, 0.0, 0]]))
    assert np.allclose(zhat, [[5.0, np.arctan2(4, 3)], [1.0, np.pi]])
    # bearing innovations wrap across ±π
    v = m.residual(np.array([[1.0, -np.pi + 0.01]]), np.array([[1.0, np.pi - 0.01]]))
    assert np.isclose(v[0, 0, 1], 0.02)


def test_ekf_equals_linear_kalman_filter_for_linear_models() -> None:
    rng = np.random.default_rng(0)
    F, Q = cv_transition(0.7), cv_process_noise(0.7, 0.3, 0.5)
    R = np.array([[4.0, 0.5], [0.5, 2.0]])
    model = CartesianModel(R)
    x = np.array([[1.0, 2.0, 3.0, -1.0]])
    P = np.diag([10.0, 4.0, 10.0, 4.0])[None]
    xr, Pr = x[0].copy(), P[0].copy()
    for _ in range(20):
        z = rng.normal(size=2) * 3
        x, P = ekf.predict(x, P, F, Q)
        zhat, H = model.predict(x)
        x, P, _ = ekf.update(x, P, model.residual(z[None], zhat)[:, 0], H, R)
        xr, Pr = ekf.kalman_step(xr, Pr, z, F, Q, H[0], R)
        assert np.allclose(x[0], xr, rtol=1e-12, atol=1e-10)
        assert np.allclose(P[0], Pr, rtol=1e-12, atol=1e-10)


def test_tracker_with_certain_detection_is_the_kalman_filter() -> None:
    """P_D → 1, no clutter, one target: the JIPDA mixture collapses to Algorithm 1."""
    cfg = TrackerConfig(
        q_north=0.3,
        q_east=0.3,
        gate_g=None,
        gate_probability=1 - 1e-12,
        initial_existence=0.999999,
        sensors={"radar": dict(r_range=1, r_bearing=1, r_cartesian=4.0, p_detect=1 - 1e-12, clutter_density=1e-30)},
    )
    rng = np.random.default_rng(3)
    truth = np.array([0.0, 2.0, 0.0, 1.0])
    zs = [truth[[0, 2]] + np.array([2.0, 1.0]) * k + rng.normal(size=2) for k in range(12)]
    tr = JIPDATracker(cfg)
    out = [tr.step(Scan(float(k), "radar", MeasurementKind.CARTESIAN, z[None])) for k, z in enumerate(zs)]
    # reference: the two-point initialisation, then Algorithm 1
    R = 4.0 * np.eye(2)
    x = np.array([zs[1][0], zs[1][0] - zs[0][0], zs[1][1], zs[1][1] - zs[0][1]])
    P = np.zeros((4, 4))
    P[np.ix_([0, 2], [0, 2])] = R
    P[np.ix_([1, 3], [1, 3])] = 2 * R
    P[np.ix_([0, 2], [1, 3])] = P[np.ix_([1, 3], [0, 2])] = R
    H = np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0]])
    for k in range(2, 12):
        x, P = ekf.kalman_step(x, P, zs[k], cv_transition(1.0), cv_process_noise(1.0, 0.3, 0.3), H, R)
        assert len(out[k]) == 1
        assert np.allclose(out[k].x[0], x, atol=1e-6)
        assert np.allclose(out[k].P[0], P, atol=1e-6)


def test_camera_bearings_update_but_never_start_tracks() -> None:
    """Fusion: range-bearing scans start a track, bearing-only (camera) scans refine it (Table 5.2 tuning)."""
    from seatwin.tracking import load_tuning

    cfg = load_tuning("synthetic").model_copy(update={"gate_g": None, "gate_probability": 0.999})
    tr = JIPDATracker(cfg)
    target = np.array([50.0, 0.0])
    for k in range(4):
        tr.step(Scan(float(k), "lidar", MeasurementKind.RANGE_BEARING, [[np.hypot(*target), np.arctan2(target[1], target[0])]]))
    assert len(tr.r) == 1
    F = cv_transition(1.05)
    P_before = F @ tr.P[0] @ F.T + cv_process_noise(1.05, cfg.q_north, cfg.q_east)  # predicted to t = 4.05
    out = tr.step(Scan(4.05, "camera", MeasurementKind.BEARING, [[0.0], [1.5]]))  # the target and a false bearing
    assert len(out) == 1  # the camera started nothing
    assert out.P[0][2, 2] < P_before[2, 2]  # cross-range (east) variance shrank with the bearing
    assert abs(out.x[0, 2]) < 1.0
    assert len(tr.step(Scan(4.1, "camera", MeasurementKind.BEARING, [[1.2]]))) == 1
