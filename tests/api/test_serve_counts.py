"""``serve`` records the frames ``simulate`` records for the same window, whatever sensors run (issue 23: with the
camera on, its last lidar sweep, ground-truth frame and radar rotation were lost)."""

from __future__ import annotations

import pytest

from seatwin.api.client import SimulationClient, scenario_steps
from seatwin.api.lockstep import DEFAULT_VESSELS
from seatwin.api.server import serve
from seatwin.errors import InputError
from seatwin.scenario.builtin import builtin_scenario


def test_serve_with_the_camera_records_simulates_frames(tmp_path):
    from seatwin.pipeline.simulate import simulate_run

    sc = builtin_scenario("ferry_crossing")
    start, duration = sc.start + 5.0, 2.5  # one radar rotation (2.5 s)
    sensors = ("lidar", "radar", "camera")
    try:
        ref = simulate_run(sc, tmp_path / "ref", start=start, duration=duration, progress=False, seed=3, sensors=sensors)
    except InputError as exc:  # no EGL here
        pytest.skip(str(exc))
    handle = serve(tmp_path / "served", port=0, seed=3, sensors=sensors)
    try:
        with SimulationClient(handle.address) as client:
            client.set_start_time(start)
            for rel, poses in scenario_steps(sc, DEFAULT_VESSELS, start, duration):
                client.step(poses, rel, 0.1)
    finally:
        res = handle.stop()
    assert res.completed
    assert ref.frames == {"ground_truth": 25, "lidar": 25, "radar": 1, "camera": 13}
    assert res.frames == ref.frames
