"""A run served to Foxglove while it is recorded (``seatwin simulate --live``, ``seatwin serve --live``).

:class:`LiveServer` is a :class:`~seatwin.recording.writer.RecordingWriter`'s ``on_write`` listener:
every message the writer puts into the bag is also logged on a ``foxglove-sdk`` WebSocket channel
(the same server and channels as ``seatwin view``: schema = the type's ROS 2 ``.msg``, messages CDR
— a ROS 1 bag's converted), with its log time. A topic's channel opens with its first message.

* **Pace**: with ``speed`` > 0 the listener holds the writer back until the wall clock reaches the
  message's simulated time ÷ ``speed`` (the run is watched as it is made; a run slower than that is
  not slowed further); ``0`` leaves the run at full speed.
* **Late clients**: messages of latched topics (``/tf_static``) and the latest message of
  ``resend`` topics (the vessel markers) are kept and logged again when a client subscribes to
  them, so a Foxglove window opened mid-run still has the tf tree.
* **Clock**: the server has Foxglove's ``time`` capability and broadcasts the simulated time.
* Messages on channels no client subscribes to are neither converted nor sent.
"""

from __future__ import annotations

import threading
import time as _time
from typing import Any

from seatwin.errors import ParameterError
from seatwin.recording.foxglove_ws import DEFAULT_PORT, foxglove_sdk, ros2_channel, start_server


class LiveServer:
    """A Foxglove WebSocket server fed by a recording writer (see the module docstring). Use as a context manager:
    ``start()``, then pass :meth:`publish` as the writer's ``on_write`` (the writer's bag format ``fmt``: its
    messages are built from seatwin's type store of that format) or call :meth:`attach` with the writer."""

    def __init__(
        self,
        host: str = "127.0.0.1",
        port: int = DEFAULT_PORT,
        *,
        speed: float = 1.0,
        latched: tuple[str, ...] = ("/tf_static",),
        resend: tuple[str, ...] = ("/ground_truth/markers",),
        name: str = "seatwin live",
        fmt: str = "mcap",
    ) -> None:
        if not speed >= 0:
            raise ParameterError("speed", f"expected ≥ 0 (0: as fast as possible), got {speed}")
        self.host, self.port, self.speed, self.name = host, port, float(speed), name
        self.latched, self.resend = set(latched), set(resend)
        self.fmt = fmt
        self.server: Any = None
        self.context: Any = None
        self.channels: dict[str, Any] = {}
        self.sent: dict[str, int] = {}
        """Messages logged per topic while a client was subscribed."""
        self._kept: dict[str, list[tuple[int, bytes]]] = {}
        self._store: Any = None
        self._convert: Any = None
        self._lock = threading.Lock()
        self._t0: tuple[int, float] | None = None
        self._clock_ns = 0

    def start(self) -> int:
        """Start the server; return the port it listens on."""
        from seatwin.recording.messages import typestore

        foxglove = foxglove_sdk()
        if self._store is None:
            self.use_store(typestore(self.fmt), self.fmt)
        self.context = foxglove.Context()
        listener = _resender(foxglove, self)
        self.server = start_server(
            self.name,
            self.host,
            self.port,
            context=self.context,
            server_listener=listener,
            capabilities=[foxglove.websocket.Capability.Time],
        )
        return int(self.server.port)

    def attach(self, writer: Any) -> None:
        """Serve what ``writer`` (a :class:`~seatwin.recording.RecordingWriter`) records from now on."""
        self.use_store(writer.store, writer.format)
        writer.on_write = self.publish

    def use_store(self, store: Any, fmt: str) -> None:
        """The type store and bag format of the messages :meth:`publish` gets (ROS 1 bytes are converted to CDR)."""
        from seatwin.recording.convert import cdr_converter_for

        self._store, self._convert = cdr_converter_for(store, fmt)

    def publish(self, topic: str, msgtype: str, log_time_ns: int, data: bytes | memoryview) -> None:
        """Log one written message (the writer's ``on_write`` hook), paced by ``speed``."""
        if self.server is None:
            raise ParameterError("live", "the live server is not started")
        if self._store is None:
            raise ParameterError("live", "no type store: call attach(writer) or use_store() first")
        self._pace(log_time_ns)
        with self._lock:
            channel = self.channels.get(topic)
            if channel is None:
                channel = self.channels[topic] = ros2_channel(self._store, topic, msgtype, context=self.context)
                self.sent[topic] = 0
            keep = topic in self.latched or topic in self.resend
            if not keep and not channel.has_sinks():
                return
            cdr = bytes(self._convert(data, msgtype))
            if topic in self.latched:
                self._kept.setdefault(topic, []).append((log_time_ns, cdr))
            elif topic in self.resend:
                self._kept[topic] = [(log_time_ns, cdr)]
            if channel.has_sinks():
                channel.log(cdr, log_time=log_time_ns)
                self.sent[topic] += 1

    def _pace(self, log_time_ns: int) -> None:
        now = _time.perf_counter()
        if self._t0 is None:
            self._t0 = (log_time_ns, now)
        if log_time_ns - self._clock_ns >= 50_000_000:  # Foxglove's clock: the simulated time, every 50 ms of it
            self._clock_ns = log_time_ns
            self.server.broadcast_time(log_time_ns)
        if self.speed > 0:
            wait = (log_time_ns - self._t0[0]) * 1e-9 / self.speed - (now - self._t0[1])
            if wait > 0:
                _time.sleep(wait)

    def resend_kept(self, topic: str) -> None:
        """Log the kept messages of ``topic`` again (a client has just subscribed to it)."""
        with self._lock:
            channel = self.channels.get(topic)
            for ts, cdr in self._kept.get(topic, ()):
                channel.log(cdr, log_time=ts)

    def close(self) -> None:
        """Stop the server and close the channels (idempotent)."""
        if self.server is not None:
            self.server.stop()
            self.server = None
        with self._lock:
            for ch in self.channels.values():
                ch.close()
            self.channels.clear()

    def __enter__(self) -> LiveServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _resender(foxglove: Any, live: LiveServer) -> Any:
    """The server's listener: a subscription to a kept topic gets its kept messages again."""

    class Resender(foxglove.websocket.ServerListener):  # type: ignore[misc,name-defined]
        def on_subscribe(self, client: Any, channel: Any) -> None:
            live.resend_kept(channel.topic)

    return Resender()
