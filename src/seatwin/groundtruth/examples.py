"""Small generated GNSS logs shipped with seatwin, so step 1 of the loop (logs → scenario) can be tried at once.

Three vessels near Ravnkloa (origin 63.4346 N, 10.3977 E), one minute at 5 Hz, 2 cm antenna noise:
Havfruen with bow and stern antennas 2.93 m apart (RTKLIB ``.pos``, GPST), milliAmpere with one
antenna (NMEA GGA + RMC) and Finn with one antenna (GPX, and the same fixes as CSV). The files in
``examples/`` beside this module are :func:`write_example_logs`'s output (a test keeps them equal).
"""

from __future__ import annotations

import calendar
from pathlib import Path

import numpy as np

from seatwin.geo import GeodeticOrigin, ned_to_llh_exact
from seatwin.groundtruth.log_writers import write_csv, write_gpx, write_nmea, write_pos
from seatwin.rng import frame_rng

EXAMPLES_DIR = Path(__file__).with_name("examples")
ORIGIN = GeodeticOrigin(63.4346, 10.3977, 0.0)
T0 = float(calendar.timegm((2020, 9, 15, 10, 0, 0)))
DURATION_S = 60.0
RATE_HZ = 5.0
BASELINE_M = 2.93
NOISE_M = 0.02
ANTENNA_HEIGHT_M = 40.0
"""Ellipsoidal height of the antennas [m] (sea level is about 40 m above the ellipsoid here)."""


def _track(t: np.ndarray, start: tuple[float, float], heading_deg: float, speed: float, turn_deg_s: float):  # noqa: ANN202
    """North, east, heading of a vessel at ``speed`` turning at a constant rate from ``start`` (exact integral)."""
    tau = t - t[0]
    psi0, w = np.radians(heading_deg), np.radians(turn_deg_s)
    if w == 0:
        north = start[0] + speed * tau * np.cos(psi0)
        east = start[1] + speed * tau * np.sin(psi0)
    else:
        north = start[0] + speed / w * (np.sin(psi0 + w * tau) - np.sin(psi0))
        east = start[1] - speed / w * (np.cos(psi0 + w * tau) - np.cos(psi0))
    return north, east, psi0 + w * tau


def _antenna(t: np.ndarray, track: tuple, along: float, stream: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    north, east, psi = track
    rng = frame_rng(7, f"examples/{stream}", 0)
    n = north + along * np.cos(psi) + NOISE_M * rng.standard_normal(len(t))
    e = east + along * np.sin(psi) + NOISE_M * rng.standard_normal(len(t))
    return ned_to_llh_exact(n, e, np.full(len(t), -ANTENNA_HEIGHT_M), ORIGIN)


def write_example_logs(out_dir: str | Path) -> list[Path]:
    """Write the example logs into ``out_dir``; the paths written."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t = T0 + np.arange(0.0, DURATION_S + 1e-9, 1.0 / RATE_HZ)
    havfruen = _track(t, (-60.0, -40.0), 60.0, 2.5, 0.5)
    milliampere = _track(t, (-20.0, 40.0), 270.0, 1.5, 0.0)
    finn = _track(t, (40.0, -80.0), 120.0, 3.0, -0.8)
    return [
        write_pos(out / "havfruen_bow.pos", t, *_antenna(t, havfruen, BASELINE_M / 2, "havfruen/bow")),
        write_pos(out / "havfruen_stern.pos", t, *_antenna(t, havfruen, -BASELINE_M / 2, "havfruen/stern")),
        write_nmea(out / "milliampere.nmea", t, *_antenna(t, milliampere, 0.0, "milliampere")),
        write_gpx(out / "finn.gpx", t, *_antenna(t, finn, 0.0, "finn")),
        write_csv(out / "finn.csv", t, *_antenna(t, finn, 0.0, "finn")),
    ]
