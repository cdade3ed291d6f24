"""``seatwin bag info``."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from recording_helpers import write_run

from seatwin.cli.main import run


def test_bag_info_table(tmp_path: Path, fmt: str, capsys: pytest.CaptureFixture[str]) -> None:
    write_run(tmp_path / "run", fmt, n_sweeps=6)
    assert run(["bag", "info", str(tmp_path / "run")]) == 0
    out = capsys.readouterr().out
    assert f"format:    {fmt}" in out
    assert "duration:  0.500 s" in out and "complete:  yes" in out
    assert "2020-09-13T12:26:40.250+00:00" in out
    line = next(x for x in out.splitlines() if x.strip().startswith("/lidar/points"))
    assert line.split()[1:] == ["sensor_msgs/msg/PointCloud2", "6", "10.00", "Hz"]


def test_bag_info_json_and_fast(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    write_run(tmp_path / "run", "mcap", n_sweeps=6)
    assert run(["bag", "info", "--json", "--fast", str(tmp_path / "run" / "recording" / "recording.mcap")]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["format"] == "mcap" and d["complete"] is True and d["seed"] == 7
    assert d["topics"]["/ground_truth/milliAmpere/odom"] == {"type": "nav_msgs/msg/Odometry", "count": 6, "rate_hz": 10.0}
    assert d["topics"]["/tf_static"]["rate_hz"] is None


def test_bag_info_bad_path(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert run(["bag", "info", str(tmp_path / "missing")]) == 2
    assert "no such file or directory" in capsys.readouterr().err
    (tmp_path / "junk.mcap").write_bytes(b"not an mcap file at all")
    assert run(["bag", "info", str(tmp_path / "junk.mcap")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("seatwin: error:") and len(err.strip().splitlines()) == 1
