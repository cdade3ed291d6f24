"""ROS 1's own ``rosbag`` (Debian's python3-rosbag, ros_comm 1.15) reads seatwin's ROS 1 bags: every chunk
compression, raw and JPEG images, a bag converted from MCAP. Every message is decoded with classes that genpy
generates from the definitions stored in the bag (their MD5 must be the one in the bag), and its bytes and log
time must be the ones seatwin's reader returns. Until this test, ROS refused seatwin's lz4 chunks."""

from __future__ import annotations

import hashlib
import json
import shutil
import subprocess
from pathlib import Path

import pytest

from seatwin.recording import open_bag
from seatwin.recording.convert import convert_bag
from seatwin.scenario import builtin_scenario
from seatwin.sim.run import simulate_scenario

SYSTEM_PYTHON = shutil.which("python3", path="/usr/bin")

ROSBAG_READ = """
import hashlib, json, sys
import genpy.dynamic, rosbag
out = {"md5_ok": {}, "messages": []}
with rosbag.Bag(sys.argv[1]) as bag:
    for c in bag._connections.values():
        cls = genpy.dynamic.generate_dynamic(c.datatype, c.msg_def)[c.datatype]
        out["md5_ok"][c.topic] = cls._md5sum == c.md5sum
    for topic, msg, t in bag.read_messages():
        assert msg._type, topic
    for topic, (datatype, data, md5, pos, pytype), t in bag.read_messages(raw=True):
        out["messages"].append([topic, datatype, t.to_nsec(), hashlib.sha256(data).hexdigest()])
print(json.dumps(out))
"""


def _ros_rosbag_available() -> bool:
    if SYSTEM_PYTHON is None:
        return False
    return subprocess.run([SYSTEM_PYTHON, "-c", "import rosbag, genpy"], capture_output=True).returncode == 0


pytestmark = pytest.mark.skipif(
    not _ros_rosbag_available(),
    reason="ROS 1's rosbag is not installed for /usr/bin/python3 (apt-get install python3-rosbag; `make test` as root does)",
)


def _read_with_ros(bag: Path) -> dict:
    res = subprocess.run([SYSTEM_PYTHON, "-c", ROSBAG_READ, str(bag)], capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr[-2000:]
    return json.loads(res.stdout)


def _read_with_seatwin(bag: Path) -> list[list]:
    with open_bag(bag) as rec:
        # seatwin names types the ROS 2 way (sensor_msgs/msg/Image), ROS 1 without /msg/
        return [[t, mt.replace("/msg/", "/"), ts, hashlib.sha256(bytes(d)).hexdigest()] for t, mt, ts, d in rec.raw_messages()]


def _same_messages(ros: dict, ours: list[list]) -> None:
    assert ros["md5_ok"] and all(ros["md5_ok"].values()), ros["md5_ok"]
    key = lambda m: (m[2], m[0], m[3])  # noqa: E731 - ties in log time: rosbag orders by connection
    assert sorted(map(tuple, ros["messages"]), key=key) == sorted(map(tuple, ours), key=key)


@pytest.fixture(scope="module")
def scenario():
    return builtin_scenario("ferry_crossing")


@pytest.mark.parametrize(("compression", "image_format"), [("lz4", "jpeg"), ("bz2", "raw"), ("none", "raw")])
def test_ros_rosbag_reads_every_message_of_a_run(tmp_path: Path, scenario, compression: str, image_format: str) -> None:
    run = tmp_path / "run"
    sensors = ("lidar", "radar", "camera")
    simulate_scenario(
        scenario,
        run,
        duration=0.6,
        fmt="ros1",
        progress=False,
        sensors=sensors,
        compression=compression,
        image_format=image_format,
    )
    bag = run / "recording.bag"
    ros = _read_with_ros(bag)
    ours = _read_with_seatwin(bag)
    topics = {m[0] for m in ours}
    assert {"/lidar/points", "/radar/detections", "/tf_static"} <= topics
    assert any(t.endswith("/compressed") for t in topics) == (image_format == "jpeg")
    _same_messages(ros, ours)


def test_ros_rosbag_reads_a_bag_converted_from_mcap(tmp_path: Path, scenario) -> None:
    simulate_scenario(scenario, tmp_path / "run", duration=0.4, progress=False, sensors=("lidar", "radar"))
    res = convert_bag(tmp_path / "run", tmp_path / "converted.bag", fmt="ros1")
    ros = _read_with_ros(res.bag)
    _same_messages(ros, _read_with_seatwin(res.bag))
    assert len(ros["messages"]) > 20
