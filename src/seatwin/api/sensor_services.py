"""Gemini's ``Sensordata`` and ``SensorManagement`` services, as ``seatwin serve`` offers them.

* :func:`served_sensors` lists the ownship's sensors as Gemini's ``SensorManagement.Sensor``: an id
  (1, 2, … in the order lidar, radar, each camera of the rig), a type (``LIDAR``, ``RADAR``,
  ``OPTICAL``), a width and height (lidar: columns × rings; radar: range samples × spokes; camera:
  the image), and where its ``Sensordata`` is served — seatwin serves every sensor's data on the
  ``serve`` address (Gemini gave each sensor a server of its own), the request's ``operation``
  naming the sensor (its id or name; empty or Gemini's ``"streaming"`` when there is one sensor).
* :class:`FrameBoard` keeps each sensor's latest frames (the loop's ``on_frame`` hook) and wakes the
  ``StreamSensordata`` calls waiting for the next one; the stream ends when the server stops.
* :func:`sensordata_bytes`: a frame as ``SensordataResponse.data`` — a camera image in Gemini's
  wire order (RGB, rows bottom up, as its ``Sensor`` read the GPU back), a lidar sweep in the
  Table 4.2 point layout (as ``LidarStreamingRequest.data``), a radar rotation's spokes (a byte per
  range sample, a row per spoke: ``RadarStreamingRequest.radarSpokes``).

``StartRendering``/``StopRendering`` start or stop a sensor's frames from the next one on (recorded,
streamed and served alike; a stopped rig camera's image is left out of the rig's frame); an unknown
id answers ``success: false``, as Gemini's.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from seatwin.api.wire import camera_bytes, lidar_bytes
from seatwin.errors import ParameterError

LIDAR, RADAR, OPTICAL = "LIDAR", "RADAR", "OPTICAL"
"""Gemini's ``SensorType`` names of seatwin's sensors (``INFRARED`` has none)."""

STREAMING_OPERATION = "streaming"
"""The ``operation`` Gemini's own Sensordata client sends."""


@dataclass(frozen=True)
class ServedSensor:
    """One sensor as ``SensorManagement`` lists it."""

    id: int
    name: str
    """``lidar``, ``radar`` (the simulation sensor's name) or ``camera/<name>`` (a rig camera: its streamed frame id)."""
    type: str
    width: int
    height: int
    vessel: str
    source: str
    """The simulation sensor whose frames carry it."""


def served_sensors(sensors: list[Any], ownship: str | None) -> list[ServedSensor]:
    """The ownship's sensors (``sensors``: a lock-step simulation's; ground truth is not a sensor here)."""
    out: list[ServedSensor] = []
    for s in sensors:
        if hasattr(s, "lidar"):
            cfg = s.lidar.config
            out.append(ServedSensor(len(out) + 1, s.name, LIDAR, int(cfg.columns), int(cfg.rings), str(ownship), s.name))
        elif getattr(s, "mounts", None) is not None:
            for m in s.mounts:
                name = f"camera/{m.name}"
                w, h = int(s.config.width), int(s.config.height)
                out.append(ServedSensor(len(out) + 1, name, OPTICAL, w, h, str(ownship), s.name))
        elif getattr(s, "model", None) is not None and hasattr(s.model, "config"):
            cfg = s.model.config
            out.append(ServedSensor(len(out) + 1, s.name, RADAR, int(cfg.n_samples), int(cfg.n_spokes), str(ownship), s.name))
    return out


def sensordata_bytes(sensor: ServedSensor, data: Any) -> bytes:
    """A frame of ``sensor`` (what its simulation sensor captured) as ``SensordataResponse.data``."""
    if sensor.type == LIDAR:
        return lidar_bytes(data)
    if sensor.type == OPTICAL:
        camera = sensor.name.split("/", 1)[1]
        for img in data:
            if img.name == camera:
                return camera_bytes(img.bgr)
        return b""
    spokes = getattr(data, "spokes", None)
    return b"" if spokes is None else bytes(spokes.to_request_dict()["radar_spokes"])


HISTORY = 8
"""Frames of each sensor a :class:`FrameBoard` keeps for ``StreamSensordata`` readers that fall behind."""


class FrameBoard:
    """The latest frames of each simulation sensor (fed by the loop's ``on_frame``), and a way to wait for the next.

    Each sensor's last :data:`HISTORY` frames are kept (references to what the sensor captured: every
    frame is a new array), so a stream reader gets every frame unless it falls that far behind (then
    it skips to the oldest kept)."""

    def __init__(self, history: int = HISTORY) -> None:
        self._frames: dict[str, deque[tuple[int, float, Any]]] = {}
        """Simulation sensor name → its last frames: (frame counter from 1, time, captured data)."""
        self._history = int(history)
        self._cond = threading.Condition()
        self.closed = False

    def on_frame(self, sensor: Any, t: float, frame: int, data: Any) -> None:
        with self._cond:
            frames = self._frames.setdefault(sensor.name, deque(maxlen=self._history))
            frames.append((frames[-1][0] + 1 if frames else 1, float(t), data))
            self._cond.notify_all()

    def latest(self, source: str) -> tuple[int, float, Any]:
        """(counter, time, data) of ``source``'s latest frame; counter 0 and no data before the first."""
        with self._cond:
            frames = self._frames.get(source)
            return frames[-1] if frames else (0, 0.0, None)

    def _after(self, source: str, seq: int) -> tuple[int, float, Any] | None:
        for f in self._frames.get(source, ()):
            if f[0] > seq:
                return f
        return None

    def wait_newer(self, source: str, seq: int, timeout_s: float) -> tuple[int, float, Any] | None:
        """The first kept frame of ``source`` after counter ``seq``, waiting up to ``timeout_s``; None if none came
        (or the board closed)."""
        with self._cond:
            self._cond.wait_for(lambda: self.closed or self._after(source, seq) is not None, timeout=timeout_s)
            return self._after(source, seq)

    def close(self) -> None:
        with self._cond:
            self.closed = True
            self._cond.notify_all()


def find_sensor(sensors: list[ServedSensor], operation: str) -> ServedSensor:
    """The sensor a ``SensordataRequest.operation`` names: its id or name; empty or ``"streaming"`` with one sensor."""
    op = str(operation).strip()
    listing = ", ".join(f"{s.id} {s.name}" for s in sensors) or "none"
    if op in ("", STREAMING_OPERATION) and len(sensors) == 1:
        return sensors[0]
    for s in sensors:
        if op == s.name or op == str(s.id):
            return s
    raise ParameterError("operation", f"expected a served sensor's id or name ({listing}), got {operation!r}")


def sensordata_stream(
    board: FrameBoard, sensor: ServedSensor, is_active: Any, poll_s: float = 0.5
) -> Iterator[tuple[float, bytes]]:
    """``StreamSensordata``: the sensor's latest frame if there is one, then every new one as it is made (see
    :class:`FrameBoard` for a reader that falls behind), until ``is_active()`` is false or the board closes."""
    seq, t, data = board.latest(sensor.source)
    if seq:
        yield t, sensordata_bytes(sensor, data)
    while is_active() and not board.closed:
        got = board.wait_newer(sensor.source, seq, poll_s)
        if got is None:
            continue
        seq, t, data = got
        payload = sensordata_bytes(sensor, data)
        if payload:
            yield t, payload
