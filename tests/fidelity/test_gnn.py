"""The GNN agent: hard assignment, then the same EKF as JIPDA."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.tracking import TrackerConfig
from seatwin.tracking.gnn import GNNTracker, gnn_assign


def test_gnn_assign_hand_example():
    # Two tracks, two measurements: each prefers measurement 0, the joint optimum splits them.
    log_ratio = np.array([[5.0, 4.0], [4.5, 1.0]])
    gated = np.ones((2, 2), bool)
    out = gnn_assign(log_ratio, gated, np.log(np.array([0.5, 0.5])))
    assert out.tolist() == [1, 0]  # 4.0 + 4.5 > 5.0 + 1.0
    # Outside the gate a track takes nothing; a miss beats a poor pair.
    out = gnn_assign(log_ratio, np.array([[True, False], [False, False]]), np.log(np.array([0.5, 0.5])))
    assert out.tolist() == [0, -1]
    out = gnn_assign(np.array([[-3.0]]), np.ones((1, 1), bool), np.log(np.array([0.5])))
    assert out.tolist() == [-1]


def _config() -> TrackerConfig:
    return TrackerConfig.model_validate(
        {
            "q_north": 0.3,
            "q_east": 0.3,
            "gate_g": None,
            "gate_probability": 0.99,
            "v_max": 10.0,
            "init_margin": 5.0,
            "sensors": {
                "radar": {"r_range": 4.0, "r_bearing": 1e-4, "r_cartesian": 4.0, "p_detect": 0.9, "clutter_density": 1e-5}
            },
        }
    )


def test_gnn_tracks_simulated_targets_like_jipda():
    from seatwin.tracking import JIPDATracker
    from seatwin.tracking.simulate import simulate

    run = simulate(n_scans=150, dt=1.0, n_targets=2, q=0.05, r_cartesian=4.0, p_detect=0.9, clutter_mean=3.0, seed=3)
    errs = {}
    for name, cls in (("gnn", GNNTracker), ("jipda", JIPDATracker)):
        table = cls(_config()).run(run.scans)
        conf = table.confirmed
        assert conf.any(), name
        # Error of each confirmed estimate to its nearest true target.
        k = np.searchsorted(np.array([s.time for s in run.scans]), table.time[conf])
        truth = run.truth[k][:, :, [0, 2]]
        est = table.x[conf][:, [0, 2]]
        d = np.linalg.norm(truth - est[:, None, :], axis=2).min(axis=1)
        errs[name] = float(np.sqrt(np.mean(d**2)))
    assert errs["gnn"] < 5.0
    assert errs["gnn"] == pytest.approx(errs["jipda"], abs=2.0)
