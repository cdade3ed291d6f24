"""``--live``: a run served to Foxglove while it is recorded, checked headless with a WebSocket client."""

from __future__ import annotations

import asyncio
import json
import struct
import threading
import time
from pathlib import Path

import pytest

from seatwin.recording import open_bag

pytest.importorskip("foxglove", reason="foxglove-sdk is not installed")
websockets = pytest.importorskip("websockets", reason="websockets (the test extra) is not installed")

SUBPROTOCOLS = ["foxglove.sdk.v1", "foxglove.websocket.v1"]


async def _watch(port: int, topics: dict[str, int], running: threading.Thread) -> tuple[dict, dict[int, list], list[bool]]:
    """Subscribe to ``topics`` (topic → subscription id) as soon as they are advertised and collect messages
    until the run ends and the stream goes quiet; also note, per message, whether the run was still going."""
    async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=SUBPROTOCOLS) as ws:
        channels: dict[str, dict] = {}
        got: dict[int, list] = {sid: [] for sid in topics.values()}
        during: list[bool] = []
        subscribed: set[str] = set()
        while True:
            try:
                data = await asyncio.wait_for(ws.recv(), 2)
            except TimeoutError:
                if running.ident is not None and not running.is_alive():
                    break
                continue
            if isinstance(data, str):
                msg = json.loads(data)
                if msg["op"] == "advertise":
                    channels.update({c["topic"]: c for c in msg["channels"]})
                    new = [t for t in topics if t in channels and t not in subscribed]
                    if new:
                        # as a person clicking would: the SDK can see a subscription that arrives within a few
                        # ms of the advertisement before it has registered the channel ("unknown channel")
                        await asyncio.sleep(0.25)
                        subs = [{"id": topics[t], "channelId": channels[t]["id"]} for t in new]
                        await ws.send(json.dumps({"op": "subscribe", "subscriptions": subs}))
                        subscribed |= set(new)
            elif data[0] == 0x01:  # MESSAGE_DATA: opcode, subscription id, log time, payload
                sid, log_time = struct.unpack_from("<IQ", data, 1)
                got[sid].append((log_time, bytes(data[13:])))
                during.append(running.is_alive())
        return channels, got, during


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
def test_a_client_watches_a_run_while_it_is_made(tmp_path: Path, fmt: str) -> None:
    from seatwin.pipeline.simulate import simulate_run
    from seatwin.recording.convert import cdr_converter
    from seatwin.recording.live import LiveServer

    run = tmp_path / "run"
    topics = {"/lidar/points": 1, "/ground_truth/Finn/odom": 2, "/tf_static": 3, "/tf": 4}
    with LiveServer(port=0, speed=1.0, fmt=fmt) as live:
        port = live.start()
        result: list = []
        sim = threading.Thread(
            target=lambda: result.append(
                simulate_run(
                    "ferry_crossing",
                    run,
                    duration=1.5,
                    start_offset=30.0,
                    sensors=("lidar",),
                    fmt=fmt,
                    progress=False,
                    on_write=live.publish,
                )  # fmt: skip
            )
        )
        client: list = []
        watcher = threading.Thread(target=lambda: client.append(asyncio.run(_watch(port, topics, sim))))
        watcher.start()
        time.sleep(0.3)  # the client is connected before the run starts
        sim.start()
        sim.join()
        watcher.join()
    assert result and result[0].completed
    channels, got, during = client[0]
    lidar = channels["/lidar/points"]
    assert (lidar["encoding"], lidar["schemaName"]) == ("cdr", "sensor_msgs/msg/PointCloud2")
    assert any(during), "no message arrived while the run was being made"
    with open_bag(run) as rec:
        _, convert = cdr_converter(rec)
        bag = {t: [(ts, bytes(convert(d, m))) for _, m, ts, d in rec.raw_messages({t})] for t in topics}
    for topic, sid in topics.items():
        received = got[sid]
        assert received, topic
        if topic == "/tf_static":  # latched: sent again to a client subscribing after it was written
            assert set(received) == set(bag[topic])
        else:  # from the moment of subscription on (on a loaded machine, late), every message as the bag has it
            n = len(received)
            assert received == bag[topic][-n:], (topic, n, len(bag[topic]))  # none lost, none changed


def test_simulate_live_on_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from seatwin.cli.main import run as cli

    args = ["simulate", "ferry_crossing", "--offset", "30", "--duration", "0.3", "--sensors", "lidar", "--no-progress"]
    assert cli([*args, "--out", str(tmp_path / "a"), "--live", "--live-port", "0", "--live-speed", "0"]) == 0
    err = capsys.readouterr().err
    assert "ws://127.0.0.1:" in err and "ws://127.0.0.1:0" not in err  # the port it bound
    with open_bag(tmp_path / "a") as rec:
        assert rec.complete and rec.topics["/lidar/points"].count == 3
    assert cli([*args, "--out", str(tmp_path / "b"), "--live", "--live-speed", "-1"]) == 2
    assert "--live-speed" in capsys.readouterr().err
    assert not (tmp_path / "b").exists()


def test_live_server_refuses_bad_use() -> None:
    from seatwin.errors import ParameterError
    from seatwin.recording.live import LiveServer

    with pytest.raises(ParameterError) as exc:
        LiveServer(speed=float("nan"))
    assert exc.value.param == "speed"
    with pytest.raises(ParameterError) as exc:
        LiveServer(port=70000).start()
    assert exc.value.param == "port"
    with LiveServer(port=0) as live, pytest.raises(ParameterError, match="not started"):
        live.publish("/a", "std_msgs/msg/String", 0, b"")
