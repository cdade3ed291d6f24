"""The one simulation loop: every sensor at its own frame times, in time order, the world posed at each.

:func:`frames` is the loop: it yields each sensor's frames in time order (ties in the order the
sensors were given), each computed at its own time (``sensor.capture``). :func:`simulate` records
them into a new recording (``sensor.record``); in-memory users (the fidelity method's replica)
iterate :func:`frames` directly. Random draws are keyed by (seed, sensor, frame), so a run is
bit-identical whatever else runs. Ctrl-C stops cleanly: the bag is closed, readable, and the
manifest says ``completed: false``.
"""

from __future__ import annotations

import heapq
import time as _time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from seatwin.sim.sensors import SimSensor
from seatwin.sim.timing import periodic_times, time_window  # noqa: F401 - re-exported


@dataclass
class SimulationResult:
    run_dir: Path
    completed: bool
    simulated_s: float
    wall_s: float
    frames: dict[str, int] = field(default_factory=dict)
    recording_s: float = 0.0
    """Wall time spent serialising and writing messages."""

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

    counts = {s.name: 0 for s in sensors}
    wall0 = _time.perf_counter()
    done_t = t0
    completed = False
    writer = RecordingWriter(
        run_dir, fmt, topics=topics, sensors={s.name: s.parameters() for s in sensors}, **(writer_kwargs or {})
    )
    try:
        writer.write_static_transforms(t0, [m for s in sensors for m in s.static_transforms(writer.topics)])
        with _progress(progress, t1 - t0) as advance:
            for t, i, k, data in frames(sensors, t0, t1):
                sensors[i].record(writer, t, data)
                if on_frame is not None:
                    on_frame(sensors[i], t, k, data)
                counts[sensors[i].name] += 1
                done_t = t
                advance(t - t0, _time.perf_counter() - wall0)
        completed = True
    except KeyboardInterrupt:
        writer.close(completed=False, error="interrupted (Ctrl-C)")
    except BaseException as exc:
        writer.close(completed=False, error=f"{type(exc).__name__}: {exc}")
        raise
    else:
        writer.close(completed=True)
    wall = _time.perf_counter() - wall0
    rec_s = writer.timing.get("total_s", writer.timing["serialize_s"] + writer.timing["write_s"])
    sim_s = (t1 - t0) if completed else max(0.0, done_t - t0)
    return SimulationResult(Path(run_dir), completed, sim_s, wall, counts, rec_s)


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
