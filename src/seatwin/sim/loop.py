"""``simulate``: step every sensor at its own rate and phase through a scenario and record it.

Frame k of a sensor happens at ``start + phase + k / rate``; all sensor events are processed
in time order (ties: in the order the sensors were given), and each sensor poses the world at
its own time. Random draws are keyed by (seed, sensor, frame), so a run is bit-identical
whatever else runs. Ctrl-C stops cleanly: the bag is closed, readable, and the manifest says
``completed: false``.
"""

from __future__ import annotations

import heapq
import time as _time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from seatwin.errors import InputError
from seatwin.recording import RecordingWriter, TopicConfig
from seatwin.sim.sensors import SimSensor


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


def time_window(scenario_start: float, scenario_end: float, start: float | None, duration: float | None) -> tuple[float, float]:
    """The simulated interval [t0, t1), checked against the scenario's span."""
    t0 = scenario_start if start is None else float(start)
    if not scenario_start - 1e-9 <= t0 < scenario_end:
        raise InputError("--start", f"start {t0!r} is outside the scenario's span [{scenario_start!r}, {scenario_end!r})")
    t1 = scenario_end if duration is None else t0 + float(duration)
    if duration is not None and duration <= 0:
        raise InputError("--duration", f"expected a positive duration, got {duration!r}")
    if t1 > scenario_end + 1e-9:
        raise InputError("--duration", f"start + duration = {t1!r} is past the scenario's end {scenario_end!r}")
    return t0, t1


def schedule(sensors: Sequence[SimSensor], t0: float, t1: float) -> list[tuple[float, int, int]]:
    """Every (time, sensor index, frame) in [t0, t1), time-ordered (ties by sensor order)."""
    events: list[tuple[float, int, int]] = []
    for i, s in enumerate(sensors):
        if s.rate_hz <= 0:
            raise InputError(None, f"sensor {s.name!r} needs a positive rate, got {s.rate_hz}", where="rate_hz")
        period = 1.0 / s.rate_hz
        k = 0
        while (t := t0 + s.phase_s + k * period) < t1 - 1e-9:
            events.append((t, i, k))
            k += 1
    heapq.heapify(events)
    return [heapq.heappop(events) for _ in range(len(events))]


def simulate(
    sensors: Sequence[SimSensor],
    run_dir: str | Path,
    t0: float,
    t1: float,
    *,
    fmt: str = "mcap",
    topics: TopicConfig | None = None,
    writer_kwargs: dict | None = None,
    progress: bool = True,
) -> SimulationResult:
    """Run ``sensors`` over [t0, t1) into a new recording in ``run_dir``."""
    events = schedule(sensors, t0, t1)
    frames = {s.name: 0 for s in sensors}
    wall0 = _time.perf_counter()
    done_t = t0
    completed = False
    writer = RecordingWriter(
        run_dir, fmt, topics=topics, sensors={s.name: s.parameters() for s in sensors}, **(writer_kwargs or {})
    )
    try:
        mounts = [m for s in sensors for m in s.static_transforms(writer.topics)]
        writer.write_static_transforms(t0, mounts)
        with _progress(progress, t1 - t0) as advance:
            for t, i, k in events:
                sensors[i].record(writer, t, k)
                frames[sensors[i].name] += 1
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
    return SimulationResult(Path(run_dir), completed, sim_s, wall, frames, rec_s)


class _progress:
    """A rich progress bar of simulated time with wall time and real-time factor (or nothing)."""

    def __init__(self, enabled: bool, total_s: float):
        self.enabled, self.total = enabled, total_s
        self._bar = None

    def __enter__(self):
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

    def __exit__(self, *exc) -> None:
        if self._bar is not None:
            self._bar.__exit__(*exc)
