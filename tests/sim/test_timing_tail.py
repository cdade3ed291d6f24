"""``periodic_times_from``: the tail of ``periodic_times`` bit for bit, without the frames before it (lock-step cost)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.sim.timing import periodic_times, periodic_times_from


@settings(max_examples=300, deadline=None)
@given(
    t0=st.sampled_from([0.0, 1.6e9, 1_599_470_000.123]),
    span=st.floats(0.0, 500.0),
    rate=st.sampled_from([0.4, 1.0, 5.0, 10.0, 12.5, 30.0, 100.0]),
    phase=st.floats(-0.5, 0.5),
    first=st.integers(0, 6000),
)
def test_tail_equals_the_full_times_from_first(t0, span, rate, phase, first):
    full = periodic_times(t0, t0 + span, rate, phase)
    tail = periodic_times_from(t0, t0 + span, rate, phase, first)
    assert tail.dtype == full.dtype and np.array_equal(tail, full[first:])


def test_tail_of_a_long_run():
    t0 = 1.6e9
    full = periodic_times(t0, t0 + 3600.0, 10.0, 0.03)
    assert len(full) == 36000
    assert np.array_equal(periodic_times_from(t0, t0 + 3600.0, 10.0, 0.03, 35990), full[35990:])
