"""The one simulation loop: every sensor at its own frame times, in time order, the world posed at each.

:func:`frames` is the loop: it yields each sensor's frames in time order (ties in the order the
sensors were given), each computed at its own time (``sensor.capture``). :func:`simulate` records
them into a new recording (``sensor.record``) through :class:`Stepper`, which a lock-step server
(``seatwin serve``) advances step by step instead; in-memory users (the fidelity method's replica)
iterate :func:`frames` directly. Random draws are keyed by (seed, sensor, frame), so a run is
bit-identical whatever else runs. Ctrl-C or SIGTERM stops cleanly (:mod:`seatwin.interrupts`): never
in the middle of recording a frame (its messages are written all or none), the bag is closed,
readable, and the manifest says ``completed: false`` with ``error: interrupted (Ctrl-C)`` or ``(SIGTERM)``.
"""

from __future__ import annotations

import heapq
import signal
import sys
import threading
import time as _time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from seatwin.interrupts import deferred_interrupts, interrupts_raise
from seatwin.sim.sensors import SimSensor


class _NotRendered:
    def __repr__(self) -> str:
        return "NOT_RENDERED"


NOT_RENDERED: Any = _NotRendered()
"""What a sensor's ``capture`` returns for a frame it does not make (its rendering stopped, as Gemini's
``SensorManagement.StopRendering``): the stepper moves past the frame without recording it."""


class StepInterrupted(Exception):
    """:meth:`Stepper.advance_to` stopped between two frames because its ``interrupt`` event was set."""


@dataclass
class SimulationResult:
    run_dir: Path
    completed: bool
    simulated_s: float
    wall_s: float
    frames: dict[str, int] = field(default_factory=dict)
    recording_s: float = 0.0
    """Wall time spent serialising and writing messages."""
    interrupted_by: int | None = None
    """The signal (SIGINT, SIGTERM) that stopped the run, if one did."""

    @property
    def realtime_factor(self) -> float:
        return self.simulated_s / self.wall_s if self.wall_s > 0 else float("inf")

    @property
    def recording_share(self) -> float:
        return self.recording_s / self.wall_s if self.wall_s > 0 else 0.0


def schedule(sensors: Sequence[SimSensor], t0: float, t1: float) -> list[tuple[float, int, int]]:
    """Every (time, sensor index, frame) in [t0, t1), time-ordered (ties by sensor order)."""
    events = [(float(t), i, k) for i, s in enumerate(sensors) for k, t in enumerate(s.frame_times(t0, t1))]
    heapq.heapify(events)
    return [heapq.heappop(events) for _ in range(len(events))]


def frames(sensors: Sequence[SimSensor], t0: float, t1: float) -> Iterator[tuple[float, int, int, Any]]:
    """The loop: ``(time, sensor index, frame index, captured data)`` for every frame in [t0, t1), in time order."""
    for t, i, k in schedule(sensors, t0, t1):
        yield t, i, k, sensors[i].capture(t, k)


class Stepper:
    """The loop advanced in increments: :meth:`advance_to` runs every frame not yet run before ``t``.

    :func:`simulate` advances it once to the end; a lock-step server (``seatwin serve``) advances it
    as poses arrive. Frame ``k`` of a sensor is always the k-th of ``sensor.frame_times(t0, t)``
    (times relative to the run's start ``t0``), so any sequence of increments runs the same frames,
    with the same indices and in the same order, as one call to the end.
    """

    def __init__(
        self,
        sensors: Sequence[SimSensor],
        writer: Any,
        t0: float,
        *,
        on_frame: Callable[[SimSensor, float, int, Any], None] | None = None,
    ):
        self.sensors, self.writer, self.t0, self.on_frame = list(sensors), writer, float(t0), on_frame
        self.counts = {s.name: 0 for s in self.sensors}
        self.done_t = self.t0
        """Time of the last frame run (``t0`` before any)."""
        self.horizon = self.t0
        """Every frame before this time has run."""
        self._next = [0] * len(self.sensors)
        self._tails = [getattr(s, "frame_times_from", None) for s in self.sensors]
        writer.write_static_transforms(self.t0, [m for s in self.sensors for m in s.static_transforms(writer.topics)])

    def advance_to(
        self,
        t1: float,
        advance: Callable[[float, float], None] | None = None,
        wall0: float = 0.0,
        interrupt: threading.Event | None = None,
    ) -> int:
        """Run (capture, record, ``on_frame``) every frame before ``t1`` not run yet, in time order; return how many.

        Each sensor's frames come from ``frame_times`` on the first increment and, after, from its
        ``frame_times_from(t0, t1, first)`` when it has one (only the frames from ``first`` on), so a
        lock-step increment costs the same after an hour as at the start. A sensor may return
        :data:`NOT_RENDERED` from ``capture``: the frame is passed over, not recorded.

        ``advance(simulated_s, wall_s)`` is called after each frame (progress). A frame is recorded
        whole: Ctrl-C/SIGTERM during its recording takes effect after it. ``interrupt`` set (by
        another thread) stops the loop before the next frame with :class:`StepInterrupted`; the
        frames not run stay due.
        """
        events = []
        for i, s in enumerate(self.sensors):
            first = self._next[i]
            tail = self._tails[i] if first else None
            if tail is None:  # the first increment (all of simulate's run): frame_times, which may prepare the frames
                times = s.frame_times(self.t0, t1)
                events.extend((float(times[k]), i, k) for k in range(first, len(times)))
            else:  # later increments: only the frames not run yet, at a cost independent of how many ran
                times = tail(self.t0, t1, first)
                if len(times):
                    events.extend((float(x), i, first + j) for j, x in enumerate(times.tolist()))
        heapq.heapify(events)
        n = 0
        while events:
            if interrupt is not None and interrupt.is_set():
                raise StepInterrupted(f"interrupted before the frame at {events[0][0] - self.t0:.3f} s")
            t, i, k = heapq.heappop(events)
            sensor = self.sensors[i]
            data = sensor.capture(t, k)
            if data is NOT_RENDERED:
                self._next[i] = k + 1
                continue
            with deferred_interrupts(), self.writer.frame():
                sensor.record(self.writer, t, data)
                self._next[i] = k + 1
                self.counts[sensor.name] += 1
                self.done_t = t
            n += 1
            if self.on_frame is not None:
                self.on_frame(sensor, t, k, data)
            if advance is not None:
                advance(t - self.t0, _time.perf_counter() - wall0)
        self.horizon = max(self.horizon, float(t1))
        return n


def simulate(
    sensors: Sequence[SimSensor],
    run_dir: str | Path,
    t0: float,
    t1: float,
    *,
    fmt: str = "mcap",
    topics: Any = None,
    writer_kwargs: dict | None = None,
    progress: bool | Callable[[float, float], None] = True,
    on_frame: Callable[[SimSensor, float, int, Any], None] | None = None,
) -> SimulationResult:
    """Run ``sensors`` over [t0, t1) into a new recording in ``run_dir``.

    ``progress``: True for a progress bar, False for none, or a callback ``(simulated_s, wall_s)``;
    ``on_frame(sensor, t, frame, data)`` sees every captured frame too (e.g. to export it).
    """
    from seatwin.recording import RecordingWriter

    wall0 = _time.perf_counter()
    completed = False
    writer = RecordingWriter(
        run_dir, fmt, topics=topics, sensors={s.name: s.parameters() for s in sensors}, **(writer_kwargs or {})
    )
    stepper = None
    interrupted_by = None
    with interrupts_raise():
        try:
            stepper = Stepper(sensors, writer, t0, on_frame=on_frame)
            with _progress(progress, t1 - t0) as advance:
                stepper.advance_to(t1, advance, wall0)
            completed = True
        except KeyboardInterrupt as exc:
            interrupted_by = getattr(exc, "signum", signal.SIGINT)
            with deferred_interrupts(discard=True):  # a second Ctrl-C does not cut the bag's finishing
                writer.close(completed=False, error=f"interrupted ({exc or 'Ctrl-C'})")
        except BaseException as exc:
            with deferred_interrupts(discard=True):
                writer.close(completed=False, error=f"{type(exc).__name__}: {exc}")
            raise
        else:
            with deferred_interrupts(discard=True):
                writer.close(completed=True)
    wall = _time.perf_counter() - wall0
    rec_s = writer.timing.get("total_s", writer.timing["serialize_s"] + writer.timing["write_s"])
    done_t = stepper.done_t if stepper is not None else t0
    counts = stepper.counts if stepper is not None else {s.name: 0 for s in sensors}
    sim_s = (t1 - t0) if completed else max(0.0, done_t - t0)
    return SimulationResult(Path(run_dir), completed, sim_s, wall, counts, rec_s, interrupted_by)


class _progress:
    """A rich progress bar of simulated time with wall time and real-time factor, a callback, or nothing."""

    def __init__(self, enabled: bool | Callable[[float, float], None], total_s: float):
        self.enabled, self.total = enabled, total_s
        self._bar = None

    def __enter__(self) -> Callable[[float, float], None]:
        if callable(self.enabled):
            return self.enabled
        if not self.enabled:
            return lambda sim_s, wall_s: None
        if not sys.stderr.isatty():  # a pipe or a log: a line every 10 s of wall time, no bar
            last = [0.0]

            def log(sim_s: float, wall_s: float) -> None:
                if wall_s - last[0] >= 10.0:
                    last[0] = wall_s
                    rtf = sim_s / wall_s if wall_s > 0 else 0.0
                    print(
                        f"simulating: {sim_s:.1f} / {self.total:.1f} s simulated, ×{rtf:.2f} real time",
                        file=sys.stderr,
                        flush=True,
                    )

            return log
        from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

        self._bar = Progress(
            TextColumn("simulating"),
            BarColumn(),
            TextColumn("{task.fields[sim]:7.1f} / {task.total:.1f} s simulated"),
            TimeElapsedColumn(),
            TextColumn("×{task.fields[rtf]:.2f} real time"),
            transient=False,
        )
        self._bar.__enter__()
        task = self._bar.add_task("sim", total=self.total, sim=0.0, rtf=0.0)

        def advance(sim_s: float, wall_s: float) -> None:
            self._bar.update(task, completed=sim_s, sim=sim_s, rtf=sim_s / wall_s if wall_s > 0 else 0.0)

        return advance

    def __exit__(self, *exc: object) -> None:
        if self._bar is not None:
            self._bar.__exit__(*exc)
