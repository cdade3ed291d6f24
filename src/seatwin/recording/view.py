"""``seatwin view RUN``: a recorded run served to Foxglove over its WebSocket protocol (the official
``foxglove-sdk``), played at its own pace.

Every topic of the bag becomes one channel: schema = the message type with its ROS 2 ``.msg``
definition (``ros2msg``, generated from the bag's own definitions), messages the bag's CDR bytes
(a ROS 1 bag's converted as ``seatwin bag convert`` does), logged with their recorded log time.
:meth:`RecordingViewer.play` sends the run once, paced by the log times divided by ``speed``
(``0``: as fast as the clients take them); the CLI loops it until Ctrl-C, so a Foxglove window
opened at any moment (Open connection → Foxglove WebSocket, ``ws://127.0.0.1:8765``) sees the run.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from seatwin.errors import ParameterError
from seatwin.recording.foxglove_ws import DEFAULT_PORT, check_port, foxglove_sdk, ros2_channel, start_server


@dataclass
class _Topic:
    channel: Any
    msgtype: str


@dataclass
class RecordingViewer:
    """A Foxglove WebSocket server for one recording (see the module docstring). Use as a context manager."""

    run: Path
    host: str = "127.0.0.1"
    port: int = DEFAULT_PORT
    server: Any = None
    messages: list[tuple[str, int, bytes]] = field(default_factory=list)
    """(topic, log time ns, CDR bytes) of the whole run, in bag order."""
    topics: dict[str, _Topic] = field(default_factory=dict)

    def start(self) -> int:
        """Read the run, open a channel per topic and start the server; return the port it listens on."""
        from seatwin.recording.convert import cdr_converter
        from seatwin.recording.reader import open_bag

        foxglove_sdk()
        check_port(self.port)
        with open_bag(self.run) as rec:
            store, convert = cdr_converter(rec)
            for topic, info in rec.topics.items():
                self.topics[topic] = _Topic(ros2_channel(store, topic, info.msgtype), info.msgtype)
            self.messages = [(topic, ts, bytes(convert(data, msgtype))) for topic, msgtype, ts, data in rec.raw_messages()]
        try:
            self.server = start_server(f"seatwin view {self.run.name}", self.host, self.port)
        except ParameterError:
            self.close()
            raise
        return int(self.server.port)

    def play(self, speed: float = 1.0, stop: threading.Event | None = None) -> int:
        """Send every message once, ``speed`` × real time (0: no pauses); return how many were sent."""
        if speed < 0:
            raise ParameterError("speed", f"expected ≥ 0 (0: as fast as possible), got {speed}")
        if not self.messages:
            return 0
        t0, wall0 = self.messages[0][1], time.perf_counter()
        sent = 0
        for topic, ts, data in self.messages:
            if stop is not None and stop.is_set():
                break
            if speed > 0:
                wait = (ts - t0) * 1e-9 / speed - (time.perf_counter() - wall0)
                if wait > 0 and (stop.wait(wait) if stop is not None else time.sleep(wait)):
                    break
            self.topics[topic].channel.log(data, log_time=ts)
            sent += 1
        return sent

    def play_loop(self, speed: float, stop: threading.Event) -> int:
        """:meth:`play` again and again until ``stop`` is set; return the messages sent."""
        sent = 0
        while not stop.is_set():
            sent += self.play(speed, stop)
            if speed == 0:
                stop.wait(0.1)  # at full speed a short run would only spin
        return sent

    def close(self) -> None:
        """Stop the server and close the channels."""
        if self.server is not None:
            self.server.stop()
            self.server = None
        for t in self.topics.values():
            t.channel.close()
        self.topics.clear()

    def __enter__(self) -> RecordingViewer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
