"""Teleports and heading spikes: smooth motion never trips them, one corrupt sample always does."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.scenario.plausibility import MAX_TURN_RATE, SPIKE_JUMP_DEG, first_heading_spike, first_teleport


@st.composite
def _motion(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A vessel at ≤ 15 m/s turning at ≤ 60 °/s, sampled every 0.05–1 s."""
    n = draw(st.integers(3, 40))
    dt = np.array(draw(st.lists(st.floats(0.05, 1.0), min_size=n - 1, max_size=n - 1)))
    t = 1.6e9 + np.concatenate([[0.0], np.cumsum(dt)])
    turn = np.array(draw(st.lists(st.floats(-60.0, 60.0), min_size=n - 1, max_size=n - 1))) * dt
    heading = draw(st.floats(-180.0, 180.0)) + np.concatenate([[0.0], np.cumsum(turn)])
    speed = np.array(draw(st.lists(st.floats(0.0, 15.0), min_size=n - 1, max_size=n - 1)))
    step_n, step_e = speed * dt * np.cos(np.radians(heading[1:])), speed * dt * np.sin(np.radians(heading[1:]))
    north = np.concatenate([[0.0], np.cumsum(step_n)])
    east = np.concatenate([[0.0], np.cumsum(step_e)])
    return t, north, east, (heading + 180.0) % 360.0 - 180.0


@settings(max_examples=150, deadline=None)
@given(_motion(), st.data())
def test_smooth_motion_passes_and_one_corrupt_sample_is_found(motion, data) -> None:  # type: ignore[no-untyped-def]
    t, north, east, heading = motion
    assert first_teleport(t, north, east) is None
    assert first_heading_spike(t, heading) is None
    k = data.draw(st.integers(1, len(t) - 2))
    # A heading spike: opposite the neighbours (±25°), which differ by ≤ 60°, so each jump is > 95°;
    # over steps shorter than 95° / MAX_TURN_RATE that is too fast.
    spiked = heading.copy()
    spiked[k] = heading[k - 1] + 180.0 + data.draw(st.floats(-25.0, 25.0))
    spike = first_heading_spike(t, spiked)
    if max(t[k] - t[k - 1], t[k + 1] - t[k]) < 95.0 / MAX_TURN_RATE:
        assert spike is not None and spike.index == k
        assert spike.jump > SPIKE_JUMP_DEG
    elif spike is not None:
        assert spike.index == k  # a slower spike may still be one: both steps faster than the limit
    # A teleport: one sample 1 km away.
    moved = north.copy()
    moved[k] += 1000.0
    jump = first_teleport(t, moved, east)
    assert jump is not None and jump.index == k - 1 and jump.speed > 30.0


def test_nan_counts_as_a_teleport() -> None:
    jump = first_teleport([0.0, 1.0, 2.0], [0.0, np.nan, 2.0], [0.0, 0.0, 0.0])
    assert jump is not None and jump.index == 0
