"""``seatwin bag convert``: every format to every other and for every ROS 2 distribution, messages kept."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from seatwin.errors import InputError, ParameterError
from seatwin.recording import open_bag
from seatwin.recording.convert import convert_bag


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A short run with every message type seatwin records (lidar, radar, cameras with labels, ground truth, tf)."""
    from seatwin.pipeline.simulate import simulate_run

    out = tmp_path_factory.mktemp("conv") / "src"
    simulate_run("ferry_crossing", out, duration=0.3, start_offset=30.0, sensors=("lidar", "radar", "camera"), progress=False)
    return out


def _counts(path: Path) -> dict[str, int]:
    from rosbags.highlevel import AnyReader

    counts: dict[str, int] = {}
    with AnyReader([path]) as r:
        for c, _t, raw in r.messages():
            r.deserialize(raw, c.msgtype)  # every message decodes with the bag's own definitions
            counts[c.topic] = counts.get(c.topic, 0) + 1
    return counts


def test_every_format_and_back_keeps_every_message(run: Path, tmp_path: Path) -> None:
    with open_bag(run) as rec:
        want = list(rec.raw_messages())
        bag = rec.bag
        types = {t: i.msgtype for t, i in rec.topics.items()}
    assert {"sensor_msgs/msg/Image", "vision_msgs/msg/Detection2DArray", "sensor_msgs/msg/PointCloud2"} <= set(types.values())
    ref = _counts(bag)
    info = yaml.safe_load((bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    assert (info["version"], info["ros_distro"]) == (5, "humble")  # simulate's default: the oldest supported LTS
    assert json.loads((run / "manifest.json").read_text())["ros_distro"] == "humble"
    src = run
    for k, (fmt, distro) in enumerate([("ros1", "humble"), ("sqlite3", "iron"), ("mcap", "jazzy"), ("sqlite3", "kilted")]):
        res = convert_bag(src, tmp_path / str(k), fmt=fmt, ros_distro=distro)
        assert res.path == tmp_path / str(k) and res.counts == ref
        assert _counts(res.bag) == ref  # rosbags' AnyReader opens every result
        manifest = json.loads((res.path / "manifest.json").read_text())
        assert manifest["format"] == fmt and manifest["bag"] == res.bag.name
        assert manifest.get("ros_distro") == (None if fmt == "ros1" else distro)
        assert (res.path / "scenario.yaml").is_file()
        if fmt != "ros1":
            info = yaml.safe_load((res.bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
            assert info["ros_distro"] == distro and info["version"] == {"iron": 7, "jazzy": 9, "kilted": 9}[distro]
        src = res.path
    back = convert_bag(src, tmp_path / "back", fmt="mcap")  # the default: Humble's version 5
    with open_bag(back.path) as rec:
        got = list(rec.raw_messages())
        assert rec.complete is True
        truth = rec.ground_truth()
    assert [m[:3] for m in got] == [m[:3] for m in want]
    assert [m[3] for m in got] == [m[3] for m in want]  # through ROS 1 and back: the very same CDR bytes
    with open_bag(run) as rec:
        for name, t in rec.ground_truth().items():
            np.testing.assert_array_equal(truth[name].north, t.north)


def test_a_bare_bag_converts_into_a_bare_bag(run: Path, tmp_path: Path) -> None:
    first = convert_bag(run, tmp_path / "r", fmt="sqlite3")
    bare = tmp_path / "bare"
    bare.mkdir()
    import shutil

    shutil.copytree(first.bag, bare / "in")  # a rosbag2 directory with no run around it
    res = convert_bag(bare / "in", tmp_path / "out", fmt="ros1")
    assert res.path == res.bag == tmp_path / "out.bag" and not (tmp_path / "out").exists()
    assert _counts(res.bag) == first.counts


def test_bad_requests_are_refused_before_writing(run: Path, tmp_path: Path) -> None:
    (tmp_path / "taken").mkdir()
    with pytest.raises(InputError, match="exists already"):
        convert_bag(run, tmp_path / "taken")
    with pytest.raises(ParameterError) as exc:
        convert_bag(run, tmp_path / "x", fmt="bag")
    assert exc.value.param == "fmt"
    with pytest.raises(ParameterError) as exc:
        convert_bag(run, tmp_path / "x", ros_distro="foxy")
    assert exc.value.param == "ros_distro"
    with pytest.raises(InputError):
        convert_bag(tmp_path / "nothing", tmp_path / "x")
    assert not (tmp_path / "x").exists()


def test_a_message_that_does_not_convert_names_its_topic_and_leaves_nothing(run: Path, tmp_path: Path) -> None:
    from seatwin.recording.messages import typestore
    from seatwin.recording.storage import open_storage

    src = tmp_path / "bad"
    st = open_storage("mcap", src, typestore("mcap"))
    conn = st.add_connection("/broken", "std_msgs/msg/String")
    st.write(conn, 1, b"\x00\x01\x00\x00\xff\xff\xff\x7f")  # a string longer than the message
    st.close()
    with pytest.raises(InputError) as exc:
        convert_bag(src, tmp_path / "out", fmt="ros1")
    assert exc.value.where == "/broken"
    assert not (tmp_path / "out.bag").exists()


def test_cli(run: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from seatwin.cli.main import run as cli

    assert cli(["bag", "convert", str(run), "--out", str(tmp_path / "c"), "--format", "sqlite3", "--ros-distro", "jazzy"]) == 0
    assert "as sqlite3 for ROS 2 jazzy" in capsys.readouterr().out
    assert cli(["bag", "convert", str(run), "--out", str(tmp_path / "c")]) == 2
    assert "exists already" in capsys.readouterr().err
