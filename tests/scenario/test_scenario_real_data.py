"""The thesis's real trajectories (../shared/data/gemini-scenarios): every file loads as a scenario."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from seatwin.scenario import load_scenario, save_scenario, scenario_summary

pytestmark = pytest.mark.shared_data


def _files(shared_data: Path) -> list[Path]:
    files = sorted((shared_data / "gemini-scenarios").glob("*.csv"))
    if not files:
        pytest.skip(f"no Gemini scenario CSVs under {shared_data / 'gemini-scenarios'}")
    return files


def test_every_real_scenario_loads(shared_data: Path):
    for path in _files(shared_data):
        sc = load_scenario(path)
        assert [v.name for v in sc.vessels] == ["Havfruen", "Finn", "milliAmpere"], path.name
        assert sc.ownship.name == "milliAmpere"
        for v in sc.vessels:
            tr = v.trajectory
            assert tr.rate_hz == pytest.approx(10.0, rel=1e-3), (path.name, v.name)
            assert np.diff(tr.time).max() < 0.11
            speed = tr.state_at(tr.time).speed
            assert speed.max() < 10.0, (path.name, v.name, speed.max())
        s = scenario_summary(sc)
        assert s["duration_s"] > 60.0 and len(s["closest_approach"]) == 3


def test_real_scenario_round_trips_through_yaml(shared_data: Path, tmp_path: Path):
    path = _files(shared_data)[-1]
    sc = load_scenario(path)
    yaml_path, _ = save_scenario(sc, tmp_path / f"{sc.name}.yaml", time_format="time_of_day")
    back = load_scenario(yaml_path)
    for a, b in zip(sc.vessels, back.vessels):
        assert a.name == b.name
        np.testing.assert_allclose(a.trajectory.time, b.trajectory.time, rtol=0, atol=1e-6)
        np.testing.assert_allclose(a.trajectory.north, b.trajectory.north, rtol=0, atol=1e-9)
