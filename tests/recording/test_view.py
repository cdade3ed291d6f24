"""``seatwin view``: a run served over Foxglove's WebSocket protocol, checked headless with a WebSocket client."""

from __future__ import annotations

import asyncio
import json
import struct
import threading
from pathlib import Path

import pytest

from seatwin.recording import open_bag

pytest.importorskip("foxglove", reason="foxglove-sdk is not installed")
websockets = pytest.importorskip("websockets", reason="websockets (the test extra) is not installed")


@pytest.fixture(scope="module", params=["mcap", "ros1"])
def run(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Path:
    from seatwin.pipeline.simulate import simulate_run

    out = tmp_path_factory.mktemp("view") / request.param
    simulate_run("ferry_crossing", out, duration=0.3, start_offset=30.0, sensors=("lidar",), fmt=request.param, progress=False)
    return out


async def _subscribe_and_receive(port: int, topic: str, play: threading.Thread) -> tuple[dict, list[tuple[int, bytes]]]:
    """Connect as Foxglove does, subscribe to ``topic``, start ``play``, and collect its messages until it ends."""
    async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=["foxglove.sdk.v1", "foxglove.websocket.v1"]) as ws:
        channels: dict[str, dict] = {}
        while topic not in channels:
            msg = json.loads(await asyncio.wait_for(ws.recv(), 10))
            if msg["op"] == "advertise":
                channels.update({c["topic"]: c for c in msg["channels"]})
        await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 7, "channelId": channels[topic]["id"]}]}))
        await asyncio.sleep(0.5)  # the server registers the subscription before the run is played
        play.start()
        got = []
        while True:
            try:
                data = await asyncio.wait_for(ws.recv(), 3)
            except TimeoutError:
                break
            if isinstance(data, bytes) and data[0] == 0x01:  # MESSAGE_DATA: opcode, subscription id, log time, payload
                sub, log_time = struct.unpack_from("<IQ", data, 1)
                assert sub == 7
                got.append((log_time, data[13:]))
        return channels[topic], got


def test_a_subscribed_client_receives_the_runs_messages(run: Path) -> None:
    from seatwin.recording.convert import cdr_converter
    from seatwin.recording.view import RecordingViewer

    topic = "/ground_truth/Finn/odom"
    with open_bag(run) as rec:
        _, convert = cdr_converter(rec)
        want = [(ts, bytes(convert(d, t))) for _, t, ts, d in rec.raw_messages({topic})]
        n_topics = len(rec.topics)
    with RecordingViewer(run, port=0) as viewer:
        port = viewer.start()
        assert port > 0 and len(viewer.topics) == n_topics
        sent: list[int] = []
        play = threading.Thread(target=lambda: sent.append(viewer.play(speed=0)))
        channel, got = asyncio.run(_subscribe_and_receive(port, topic, play))
        play.join()
    assert channel["encoding"] == "cdr" and channel["schemaName"] == "nav_msgs/msg/Odometry"
    assert channel["schemaEncoding"] == "ros2msg" and "geometry_msgs/TwistWithCovariance twist" in channel["schema"]
    assert sent == [len(viewer.messages)]
    assert got == want and len(got) == 3  # every message of the topic, as CDR, with its recorded log time


def test_bad_requests(run: Path, tmp_path: Path) -> None:
    from seatwin.cli.main import run as cli
    from seatwin.errors import InputError, ParameterError
    from seatwin.recording.view import RecordingViewer

    with pytest.raises(InputError):
        RecordingViewer(tmp_path / "nothing", port=0).start()
    with pytest.raises(ParameterError) as exc, RecordingViewer(run, port=70000) as v:
        v.start()
    assert exc.value.param == "port"
    assert cli(["view", str(run), "--speed", "-1"]) == 2
