"""A lock-step step costs the same after thousands of steps as after hundreds (issue 23, item 5).

Measured without a clock: the Python lines and calls a step executes (``sys.settrace``) and the memory it
allocates at its peak (``tracemalloc``: numpy's buffers included), medians over a window of steps early
in the run and late in it. Work that grows with the run's length — a scan of the samples so far, an
array of every frame time since the start — shows in one or the other; the test checks that it also
catches such a regression (the frame schedule rebuilt from the start each step, as before).
"""

from __future__ import annotations

import statistics
import sys
import tracemalloc
from collections.abc import Iterator
from pathlib import Path

import pytest

from seatwin.api import lockstep
from seatwin.api.lockstep import DEFAULT_VESSELS, LockstepSettings, LockstepSimulation

STEP_S = 0.1
EARLY, LATE, WINDOW = 200, 2400, 40
N_VESSELS = len(DEFAULT_VESSELS)


def _poses(k: int) -> list[tuple[float, float, float]]:
    """Three vessels on slow circles (headings crossing ±180°), deterministic."""
    import math

    a = 0.002 * k
    return [(100.0 * math.cos(a + i), 100.0 * math.sin(a + i), (57.3 * (a + i) + 90.0) % 360.0) for i in range(N_VESSELS)]


def _window_costs(sim: LockstepSimulation, ks: range) -> tuple[float, float]:
    """Median over steps ``ks`` of (trace events, peak bytes allocated) per step."""
    events, peaks = [], []
    count = 0

    def tracer(frame: object, event: str, arg: object) -> object:
        nonlocal count
        count += 1
        return tracer

    tracemalloc.start()
    try:
        for k in ks:
            count = 0
            tracemalloc.reset_peak()
            base = tracemalloc.get_traced_memory()[0]
            sys.settrace(tracer)
            try:
                sim.step(_poses(k), k * STEP_S, STEP_S)
            finally:
                sys.settrace(None)
            peaks.append(tracemalloc.get_traced_memory()[1] - base)
            events.append(count)
    finally:
        tracemalloc.stop()
    return statistics.median(events), statistics.median(peaks)


def _run(run_dir: Path) -> Iterator[tuple[float, float]]:
    sim = LockstepSimulation(run_dir, LockstepSettings(sensors=()))  # ground truth of three vessels: the bookkeeping
    sim.set_start_time("1600000000")
    done = 0
    for first in (EARLY, LATE):
        for k in range(done, first):
            sim.step(_poses(k), k * STEP_S, STEP_S)
        yield _window_costs(sim, range(first, first + WINDOW))
        done = first + WINDOW
    assert sim.close().frames["ground_truth"] == LATE + WINDOW - 1


@pytest.mark.slow
def test_step_cost_does_not_grow_with_the_run(tmp_path: Path) -> None:
    (ev0, mem0), (ev1, mem1) = _run(tmp_path / "run")
    assert ev0 > 100 and mem0 > 0  # the probes see the step's work
    assert ev1 <= 1.05 * ev0, f"trace events per step grew: {ev0} at {EARLY * STEP_S:g} s, {ev1} at {LATE * STEP_S:g} s"
    assert mem1 <= 1.1 * mem0 + 256, f"peak bytes per step grew: {mem0} at {EARLY * STEP_S:g} s, {mem1} at {LATE * STEP_S:g} s"


@pytest.mark.slow
def test_the_probe_catches_a_schedule_rebuilt_from_the_start(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Without ``frame_times_from`` a step takes every frame time since the start (``frame_times(...)[first:]``)."""
    real = lockstep._Due.__init__

    def without_tail(self: lockstep._Due, *args: object, **kwargs: object) -> None:
        real(self, *args, **kwargs)  # type: ignore[arg-type]
        self._tail = None

    monkeypatch.setattr(lockstep._Due, "__init__", without_tail)
    (_, mem0), (_, mem1) = _run(tmp_path / "run")
    assert mem1 > 1.1 * mem0 + 256  # 2400 frame times (19 kB) a step, against 200
