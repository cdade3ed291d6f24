"""Frame times of the loop, computed relative to the run's start (never with POSIX-sized margins)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import ParameterError

TIME_EPS_S = 1e-6
"""Slack for comparing times *relative to the run's start* (float64 POSIX seconds are spaced 2.4e-7)."""

_NONE = np.empty(0)
_NONE.flags.writeable = False  # shared by every call that has no frame


def periodic_times(t0: float, t1: float, rate_hz: float, phase_s: float = 0.0) -> NDArray[np.float64]:
    """Frame times ``t0 + phase + k / rate`` in [t0, t1), computed relative to ``t0`` (no POSIX-size margins)."""
    if not rate_hz > 0:
        raise ParameterError("rate_hz", f"a sensor needs a positive rate, got {rate_hz!r}")
    span = float(t1) - float(t0)
    rel = phase_s + np.arange(max(0, int(np.ceil((span - phase_s) * rate_hz)) + 1)) / rate_hz
    return float(t0) + rel[(rel >= 0) & (rel < span - TIME_EPS_S)]


def periodic_times_from(t0: float, t1: float, rate_hz: float, phase_s: float, first: int) -> NDArray[np.float64]:
    """``periodic_times(t0, t1, rate_hz, phase_s)[first:]`` computed without the frames before ``first``: the same
    values bit for bit, at a cost that does not grow with ``first`` (a lock-step server's later steps)."""
    if not rate_hz > 0:
        raise ParameterError("rate_hz", f"a sensor needs a positive rate, got {rate_hz!r}")
    span = float(t1) - float(t0)
    if phase_s >= 0 and not phase_s + int(first) / rate_hz < span - TIME_EPS_S:  # the usual lock-step case: none due
        return _NONE  # (the same arithmetic as below, on one element)
    dropped = 0  # leading frames of a negative phase, before t0: not frames
    if phase_s < 0:
        head = phase_s + np.arange(int(np.ceil(-phase_s * rate_hz)) + 2) / rate_hz
        dropped = int(np.count_nonzero(head < 0))
    n = max(0, int(np.ceil((span - phase_s) * rate_hz)) + 1)
    rel = phase_s + np.arange(min(int(first) + dropped, n), n) / rate_hz
    return float(t0) + rel[(rel >= 0) & (rel < span - TIME_EPS_S)]


def time_window(scenario_start: float, scenario_end: float, start: float | None, duration: float | None) -> tuple[float, float]:
    """The simulated interval [t0, t1) from POSIX ``start`` (default: the scenario's) for ``duration`` seconds.

    Checked relative to the scenario's start, so float64 POSIX spacing (2.4e-7 s) never fails the last frame.
    """
    span = scenario_end - scenario_start
    off = 0.0 if start is None else float(start) - scenario_start
    if not -TIME_EPS_S <= off < span:
        raise ParameterError(
            "start", f"{start:.3f} is outside the scenario: expected a POSIX time from {scenario_start:.3f} to {scenario_end:.3f}"
        )
    off = max(off, 0.0)
    if duration is not None and not duration > 0:
        raise ParameterError("duration", f"expected a positive number of seconds, got {duration:g}")
    rel_end = span if duration is None else off + float(duration)
    if rel_end > span + TIME_EPS_S:
        raise ParameterError("duration", f"start + duration ends {rel_end - span:g} s past the scenario's end")
    return scenario_start + off, scenario_start + min(rel_end, span)
