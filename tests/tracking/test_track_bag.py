"""``seatwin track --out-bag``: the tracks written into a copy of the run, as ROS messages and Foxglove entities."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np
import pytest

from seatwin.recording import open_bag


@pytest.fixture(scope="module", params=["mcap", "ros1"])
def run(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Path:
    from seatwin.pipeline.simulate import simulate_run

    out = tmp_path_factory.mktemp("trk") / request.param
    sensors = ("lidar", "radar")
    simulate_run("ferry_crossing", out, duration=4.0, start_offset=30.0, sensors=sensors, fmt=request.param, progress=False)
    return out


def _digest(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.rglob("*")) if p.is_file()
    }


def test_tracks_go_into_a_copy_of_the_run(run: Path, tmp_path: Path) -> None:
    from rosbags.highlevel import AnyReader

    from seatwin.pipeline.track import track_into_run
    from seatwin.recording.tracks import TRACK_TOPICS, UNKNOWN_VARIANCE

    before = _digest(run)
    result, copy = track_into_run(run, tmp_path / "tracked")
    assert _digest(run) == before  # the input is not touched
    tracks = result.tracks
    assert result.n_tracks > 0 and len(tracks.time) > 0
    with open_bag(run) as a, open_bag(copy.path) as b:
        assert b.format == a.format and b.complete
        original = list(a.raw_messages())
        copied = [m for m in b.raw_messages() if m[0] not in TRACK_TOPICS.values()]
        assert [(t, ts, bytes(d)) for t, _, ts, d in copied] == [(t, ts, bytes(d)) for t, _, ts, d in original]
        assert b.manifest["added"][0]["what"] == "tracks" and b.manifest["added"][0]["tracks"] == result.n_tracks
        assert b.manifest["topics"]["/tracks/odom"]["count"] == len(tracks.time)
        odoms = list(b.messages("/tracks/odom"))
        markers = list(b.messages("/tracks/markers"))
        scenes = list(b.messages("/tracks/scene"))
        bag = b.bag
    assert len(markers) == len(scenes) == len(tracks.scan_times)
    assert [m.log_time_ns for m in markers] == sorted(m.log_time_ns for m in markers)
    for k, m in enumerate(odoms):  # rows in (time, track_id) order, as the tracker wrote them
        o = m.msg
        assert o.header.frame_id == "world_ned" and o.child_frame_id == f"track/{tracks.track_id[k]}"
        n, vn, e, ve = tracks.state[k]
        assert (o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z) == (n, e, 0.0)
        assert (o.twist.twist.linear.x, o.twist.twist.linear.y) == (vn, ve)
        pc, tc = np.reshape(o.pose.covariance, (6, 6)), np.reshape(o.twist.covariance, (6, 6))
        P = tracks.covariance[k]
        np.testing.assert_array_equal(pc[:2, :2], P[np.ix_([0, 2], [0, 2])])
        np.testing.assert_array_equal(tc[:2, :2], P[np.ix_([1, 3], [1, 3])])
        assert pc[2, 2] == tc[5, 5] == UNKNOWN_VARIANCE
    by_time: dict[int, list[int]] = {}
    for m in odoms:
        by_time.setdefault(m.log_time_ns, []).append(int(m.msg.child_frame_id.split("/")[1]))
    for mk, sc in zip(markers, scenes):
        arr = mk.msg.markers
        assert arr[0].action == 3  # DELETEALL: ended tracks vanish
        ids = by_time.get(mk.log_time_ns, [])
        assert [x.id for x in arr[1:]] == [3 * i + j for i in ids for j in range(3)]
        assert all(x.header.frame_id == "world_ned" for x in arr)
        assert [d.type for d in sc.msg.deletions] == [1]  # ALL (earlier than this update)
        metas = [{kv.key: kv.value for kv in ent.metadata} for ent in sc.msg.entities]
        assert [int(md["track_id"]) for md in metas] == ids
        assert all(ent.frame_id == "world_ned" and ent.id == f"track {md['track_id']}" for ent, md in zip(sc.msg.entities, metas))
    confirmed = [md for sc in scenes for md in ({kv.key: kv.value for kv in ent.metadata} for ent in sc.msg.entities)]
    assert {md["confirmed"] for md in confirmed} <= {"true", "false"}
    with AnyReader([bag]) as r:  # the copy carries every definition: a standard reader decodes the new topics
        conns = [c for c in r.connections if c.topic in TRACK_TOPICS.values()]
        types = {"nav_msgs/msg/Odometry", "visualization_msgs/msg/MarkerArray", "foxglove_msgs/msg/SceneUpdate"}
        assert {c.msgtype for c in conns} == types
        for c, _t, raw in r.messages(connections=conns):
            r.deserialize(raw, c.msgtype)


def test_the_copy_tracks_as_the_original(run: Path, tmp_path: Path) -> None:
    """The added topics do not disturb readers: tracking the copy gives the same tracks; tracking it into a
    further copy replaces its tracks instead of doubling them."""
    from seatwin.pipeline.track import track_into_run, track_recording

    first, copy = track_into_run(run, tmp_path / "a")
    again = track_recording(copy.path)
    np.testing.assert_array_equal(again.tracks.state, first.tracks.state)
    _, twice = track_into_run(copy.path, tmp_path / "b")
    assert twice.counts["/tracks/odom"] == copy.counts["/tracks/odom"]


def test_outputs_follow_the_rules(run: Path, tmp_path: Path) -> None:
    from seatwin.cli.main import run as cli
    from seatwin.errors import InputError
    from seatwin.outputs import OutputExistsError
    from seatwin.pipeline.track import track_into_run

    out = tmp_path / "t"
    assert cli(["track", str(run), "--out-bag", str(out), "--no-progress"]) == 0
    with pytest.raises(OutputExistsError) as exc:
        track_into_run(run, out)
    assert exc.value.param == "out_bag"
    assert cli(["track", str(run), "--out-bag", str(out), "--out", str(tmp_path / "t.csv"), "--overwrite", "--no-progress"]) == 0
    assert (tmp_path / "t.csv").is_file() and (out / "manifest.json").is_file()
    with pytest.raises(InputError):
        track_into_run(run, run / "inside")  # never into the input
    assert cli(["track", str(run)]) == 2  # nowhere to write
