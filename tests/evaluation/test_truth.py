"""Ground truth adapters: scenario (ownship excluded), recording, real Gemini CSV; numerical velocities."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.evaluation.truth import TruthTrack, load_truth, truth_from_scenario
from seatwin.scenario import Role, Scenario, Trajectory, Vessel


def _scenario() -> Scenario:
    t = 1.6e9 + np.arange(0.0, 10.01, 0.1)
    z = np.zeros_like(t)
    return Scenario(
        "s",
        [
            Vessel("own", Role.OWNSHIP, Trajectory(t, z, z - 30.0, z)),
            Vessel("A", Role.TARGET, Trajectory(t, 2.0 * (t - t[0]), z + 5.0, z)),
        ],
    )


def test_numerical_velocity_and_span() -> None:
    t = np.arange(0.0, 5.0, 0.5)
    tr = TruthTrack("x", t, 3.0 * t, t**2)
    s = tr.state_at([1.0, 2.25, 99.0])
    assert s[0] == pytest.approx([3.0, 3.0, 1.0, 2.0])  # central difference of t² at 1 is exact
    assert s[1, 0] == pytest.approx(6.75)
    assert np.isnan(s[2]).all()
    with pytest.raises(InputError, match="increase strictly"):
        TruthTrack("x", [0.0, 0.0, 1.0], [0, 1, 2], [0, 0, 0])


def test_scenario_excludes_ownship() -> None:
    truth = truth_from_scenario(_scenario())
    assert truth.names == ["A"]
    s = truth["A"].state_at(1.6e9 + 5.0)
    assert s == pytest.approx([10.0, 2.0, 5.0, 0.0])


def test_recording_truth(tmp_path: Path) -> None:
    from seatwin.recording import open_recording
    from seatwin.sim.poses import poses_from_scenario

    scen = _scenario()
    with open_recording(tmp_path / "run") as rec:
        for t in scen.vessels[0].trajectory.time[::5]:
            rec.write_ground_truth(float(t), poses_from_scenario(scen, float(t)))
    truth = load_truth(tmp_path / "run")
    assert truth.names == ["A"]
    assert truth["A"].state_at(1.6e9 + 5.0) == pytest.approx([10.0, 2.0, 5.0, 0.0], abs=1e-6)


def test_real_gemini_scenario(shared_data: Path) -> None:
    truth = load_truth(shared_data / "gemini-scenarios" / "Scenario3.csv")
    assert len(truth) == 2  # V3 (milliAmpere, the ownship) excluded
    for tr in truth.targets.values():
        speed = np.hypot(tr.v_north, tr.v_east)
        assert np.isfinite(speed).all() and np.median(speed) < 10.0  # small harbour boats


def test_unknown_truth() -> None:
    with pytest.raises(InputError):
        load_truth("no-such-scenario")
