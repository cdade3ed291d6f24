"""seatwin simulate: recording contents, reproducibility, faults."""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.recording import open_bag
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sim import simulate_scenario
from seatwin.sim.loop import schedule
from seatwin.sim.sensors import Periodic


def _payloads(run_dir: Path) -> dict[str, list[bytes]]:
    out: dict[str, list[bytes]] = {}
    with open_bag(run_dir) as bag:
        for topic, _type, ts, data in bag.raw_messages():
            out.setdefault(topic, []).append(bytes(data) + ts.to_bytes(8, "little"))
    return out


@pytest.fixture(scope="module")
def scenario():
    return builtin_scenario("ferry_crossing")


def test_schedule_orders_sensors_by_time_and_phase():
    class S(Periodic):
        def __init__(self, name, rate, phase):
            self.name, self.rate_hz, self.phase_s = name, rate, phase

    ev = schedule([S("gt", 10, 0.0), S("cam", 5, 0.03)], 0.0, 0.5)
    assert [(round(t, 3), i) for t, i, _ in ev] == [
        (0.0, 0),
        (0.03, 1),
        (0.1, 0),
        (0.2, 0),
        (0.23, 1),
        (0.3, 0),
        (0.4, 0),
        (0.43, 1),
    ]
    assert [k for t, i, k in ev if i == 1] == [0, 1, 2]


def test_frame_times_are_relative_to_the_start():
    """POSIX-sized starts lose no frame to rounding (issue: the last sweep of Scenario6 fell outside)."""
    from seatwin.sim.timing import periodic_times, time_window

    t0 = 1600173270.0999441
    times = periodic_times(t0, t0 + 81.9, 10.0)
    assert len(times) == 819 and times[-1] - t0 == pytest.approx(81.8, abs=1e-6)
    assert time_window(t0, t0 + 81.9, None, None) == (t0, t0 + 81.9)
    assert time_window(t0, t0 + 81.9, t0 + 1.0, 80.9 + 2e-7)[1] == t0 + 81.9


def test_recording_contents(tmp_path, scenario):
    res = simulate_scenario(scenario, tmp_path / "r", duration=1.0, progress=False, sensors=("lidar",))
    assert res.completed and res.frames == {"ground_truth": 10, "lidar": 10}
    manifest = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert manifest["completed"] is True and manifest["seed"] == scenario.seed
    assert manifest["sensors"]["lidar"]["config"]["drop_probability"] == 0.8
    assert manifest["topics"]["/lidar/points"]["count"] == 10
    assert (tmp_path / "r" / "scenario.yaml").is_file()
    with open_bag(tmp_path / "r") as bag:
        clouds = list(bag.point_clouds("/lidar/points"))
        assert len(clouds) == 10
        c = clouds[0]
        assert c.stamp == pytest.approx(scenario.start, abs=1e-6)
        assert c.frame_id == "milliAmpere/lidar"  # per-vessel namespace (REP-105 multi-robot)
        assert c.points.dtype.names == ("x", "y", "z", "intensity", "ring", "time")
        assert c.points.dtype.itemsize == 24 and len(c.points) > 100
        assert c.points["time"].min() >= 0.0 and c.points["time"].max() < 0.1
        truth = bag.ground_truth()
        assert set(truth) == {v.name for v in scenario.vessels}
        tf = bag.static_transforms()
        parents = {t.child: t.parent for t in tf}  # upside down: rolled below an upright mount on base_link
        assert parents["milliAmpere/lidar"] == "milliAmpere/lidar_upright"
        assert parents["milliAmpere/lidar_upright"] == "milliAmpere/base_link"


def test_same_seed_bit_identical_other_seed_changes_only_random_parts(tmp_path, scenario):
    for name, seed in (("a", 7), ("b", 7), ("c", 8)):
        simulate_scenario(scenario, tmp_path / name, duration=0.5, seed=seed, progress=False, sensors=("lidar",))
    a, b, c = (_payloads(tmp_path / n) for n in "abc")
    assert a == b
    assert a["/lidar/points"] != c["/lidar/points"]
    for topic in a:
        if topic != "/lidar/points":
            assert a[topic] == c[topic], topic


def test_formats(tmp_path, scenario):
    for fmt in ("sqlite3", "ros1"):
        simulate_scenario(scenario, tmp_path / fmt, duration=0.3, fmt=fmt, progress=False, sensors=("lidar",))
        with open_bag(tmp_path / fmt) as bag:
            assert len(list(bag.point_clouds())) == 3


def test_bad_input_fails_before_any_work(tmp_path, capsys):
    assert run(["simulate", "no_such_scenario", "--out", str(tmp_path / "x")]) == 2
    assert "no_such_scenario" in capsys.readouterr().err
    assert not (tmp_path / "x").exists()
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: [unclosed\n")
    assert run(["simulate", str(bad), "--out", str(tmp_path / "y")]) == 2
    assert not (tmp_path / "y").exists()
    assert run(["simulate", "ferry_crossing", "--out", str(tmp_path / "z"), "--duration", "1e6"]) == 2
    assert not (tmp_path / "z").exists()


def _start_run(tmp_path: Path) -> subprocess.Popen:
    cmd = [
        sys.executable,
        "-m",
        "seatwin.cli.main",
        "simulate",
        "ferry_crossing",
        "--out",
        str(tmp_path / "run"),
        "--ray-drop",
        "0",
        "--quiet",
    ]
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)


def _wait_for_flushes(run_dir: Path, proc: subprocess.Popen, counts: int = 25) -> None:
    """Wait until the manifest reports at least ``counts`` lidar sweeps flushed."""
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        assert proc.poll() is None, proc.communicate()
        try:
            m = json.loads((run_dir / "manifest.json").read_text())
            if m.get("topics", {}).get("/lidar/points", {}).get("count", 0) >= counts:
                return
        except (OSError, ValueError):
            pass
        time.sleep(0.1)
    pytest.fail("the run did not flush in time")


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGINT, signal.SIGTERM])
def test_killed_run_leaves_a_readable_bag(tmp_path, sig):
    proc = _start_run(tmp_path)
    run_dir = tmp_path / "run"
    _wait_for_flushes(run_dir, proc)
    proc.send_signal(sig)
    proc.communicate(timeout=60)
    m = json.loads((run_dir / "manifest.json").read_text())
    assert m["completed"] is False
    with open_bag(run_dir) as bag:
        assert bag.complete is False
        clouds = list(bag.point_clouds("/lidar/points"))
        assert len(clouds) >= 10
        stamps = np.array([c.stamp for c in clouds])
        assert (np.diff(stamps) > 0).all()
        assert all(len(c.points) > 1000 for c in clouds)
    if sig != signal.SIGKILL:  # Ctrl-C and SIGTERM: the bag finished, the manifest says why it stopped
        assert m["error"] == f"interrupted ({'Ctrl-C' if sig == signal.SIGINT else 'SIGTERM'})"
        assert not bag.recovered


@pytest.mark.slow
@pytest.mark.parametrize("name", ["Scenario3", "Scenario4", "Scenario5", "Scenario6"])
def test_every_published_scenario_runs_to_its_end(tmp_path, shared_data, name):
    """The Gemini CSVs (POSIX times ~1.6e9 s) simulate to their very last frame and complete."""
    from seatwin.scenario.load import load_scenario

    sc = load_scenario(shared_data / "gemini-scenarios" / f"{name}.csv")
    res = simulate_scenario(sc, tmp_path / name, progress=False, lidar_preset="vlp16-thesis", sensors=("lidar",))
    assert res.completed
    expected = math.ceil((sc.end - sc.start) * 10.0 - 1e-5)  # frames at 0, 0.1, … < span
    assert res.frames["lidar"] == res.frames["ground_truth"] == expected
    with open_bag(tmp_path / name) as bag:
        assert bag.manifest["completed"] is True
