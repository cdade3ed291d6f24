"""``seatwin serve --live``: the lock-step run served to Foxglove while a co-simulation steps it."""

from __future__ import annotations

import asyncio
import json
import struct
import threading
import time

import pytest

from seatwin.recording import open_bag

pytest.importorskip("foxglove", reason="foxglove-sdk is not installed")
websockets = pytest.importorskip("websockets", reason="websockets (the test extra) is not installed")


async def _receive(port: int, topic: str, done: threading.Event) -> list[tuple[int, bytes]]:
    async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=["foxglove.sdk.v1"]) as ws:
        got: list[tuple[int, bytes]] = []
        while True:
            try:
                data = await asyncio.wait_for(ws.recv(), 2)
            except TimeoutError:
                if done.is_set():
                    return got
                continue
            if isinstance(data, str):
                msg = json.loads(data)
                chans = [c for c in msg.get("channels", []) if c["topic"] == topic] if msg["op"] == "advertise" else []
                if chans:
                    await asyncio.sleep(0.25)  # see tests/recording/test_live.py
                    await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": chans[0]["id"]}]}))
            elif data[0] == 0x01:
                _, log_time = struct.unpack_from("<IQ", data, 1)
                got.append((log_time, bytes(data[13:])))


def test_served_steps_are_watched_live(tmp_path) -> None:
    from seatwin.api.client import SimulationClient, scenario_steps
    from seatwin.api.lockstep import DEFAULT_VESSELS
    from seatwin.api.server import serve
    from seatwin.recording.live import LiveServer
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario("ferry_crossing")
    start = sc.start + 5.0
    with LiveServer(port=0, speed=0.0) as live:
        port = live.start()
        handle = serve(tmp_path / "served", port=0, sensors=())
        live.attach(handle.sim.writer)

        def drive() -> None:
            with SimulationClient(handle.address) as client:
                assert client.set_start_time(start)
                for rel, poses in scenario_steps(sc, DEFAULT_VESSELS, start, 3.0):
                    assert client.step(poses, rel, 0.1)
                    time.sleep(0.05)  # a co-simulation's own pace

        stepping, done = threading.Thread(target=drive), threading.Event()
        got: list = []
        watcher = threading.Thread(target=lambda: got.extend(asyncio.run(_receive(port, "/tf", done))))
        watcher.start()
        time.sleep(0.3)
        stepping.start()
        stepping.join()
        assert handle.stop().completed  # the frames still due are recorded (and served) at the stop
        done.set()
        watcher.join()
    with open_bag(tmp_path / "served") as rec:
        bag = [(ts, bytes(d)) for _, _, ts, d in rec.raw_messages({"/tf"})]
    assert got and got == bag[-len(got) :]  # every /tf since the subscription, as recorded


def test_serve_live_refuses_a_bad_port_before_serving(tmp_path, capsys) -> None:
    from seatwin.cli.main import run as cli

    assert cli(["serve", "--out", str(tmp_path / "r"), "--sensors", "none", "--live", "--live-port", "70000"]) == 2
    assert "--live-port" in capsys.readouterr().err
    assert not (tmp_path / "r" / "manifest.json").exists()
