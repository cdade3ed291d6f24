"""The shipped example logs are the generator's output and give back their vessels."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.groundtruth.examples import EXAMPLES_DIR, write_example_logs


def test_shipped_examples_equal_the_generator(tmp_path):
    written = write_example_logs(tmp_path)
    assert len(written) == 5
    for path in written:
        assert (EXAMPLES_DIR / path.name).read_bytes() == path.read_bytes(), path.name


def test_examples_make_a_scenario(tmp_path):
    from seatwin.groundtruth import compute_ground_truth
    from seatwin.groundtruth.examples import BASELINE_M, ORIGIN
    from seatwin.groundtruth.vessel import VesselSpec

    e = EXAMPLES_DIR
    vessels = [
        VesselSpec("Havfruen", (e / "havfruen_bow.pos", e / "havfruen_stern.pos"), BASELINE_M),
        VesselSpec("milliAmpere", (e / "milliampere.nmea",)),
    ]
    result = compute_ground_truth(vessels, ORIGIN)
    hav = result.vessels[0]
    assert hav.name == "Havfruen" and len(hav.time) == 601  # 60 s on the 10 Hz common clock
    assert abs(float(hav.eps_gnss.mean())) < 0.05  # 2 cm antenna noise
    # The generator's Havfruen: heading 60° turning 0.5°/s, from (-60, -40) m at 2.5 m/s.
    assert np.degrees(hav.heading[[0, -1]]) == pytest.approx([60.0, 90.0], abs=2.0)
    assert (hav.north[0], hav.east[0]) == pytest.approx((-60.0, -40.0), abs=0.2)
    assert np.hypot(hav.v_north, hav.v_east)[100:-100] == pytest.approx(2.5, abs=0.1)
