"""Small generated GNSS logs shipped with seatwin, so step 1 of the loop (logs → scenario) can be tried at once.

Three vessels in the Ravnkloa canal, one minute at 5 Hz, 2 cm antenna noise, about the Ravnkloa origin
(:data:`seatwin.scenario.defaults.RAVNKLOA`, 63.4336 N, 10.3926 E: the frame of the Gemini scenarios, to which the
Ravnkloa land raster is aligned), so the scenario they give plays in harbour ``ravnkloa`` with every vessel on water
(a test checks it on the real raster): Havfruen with bow and stern antennas 2.01 m apart (the thesis's baseline;
RTKLIB ``.pos``, GPST) heads up the canal turning to starboard, Finn (one antenna: GPX, and the same fixes as CSV)
comes down it, and the ownship milliAmpere (one antenna: NMEA GGA + RMC) crosses it, as the ferry does. Every path
keeps at least 7 m from the shore in the aligned raster. The files in ``examples/`` beside this module are
:func:`write_example_logs`'s output (a test keeps them equal).
"""

from __future__ import annotations

import calendar
from pathlib import Path

import numpy as np

from seatwin.geo import GeodeticOrigin, ned_to_llh_exact
from seatwin.groundtruth.log_writers import write_csv, write_gpx, write_nmea, write_pos
from seatwin.rng import frame_rng
from seatwin.scenario.defaults import RAVNKLOA

EXAMPLES_DIR = Path(__file__).with_name("examples")
ORIGIN: GeodeticOrigin = RAVNKLOA
T0 = float(calendar.timegm((2020, 9, 15, 10, 0, 0)))
DURATION_S = 60.0
RATE_HZ = 5.0
BASELINE_M = 2.01
"""Havfruen's bow–stern antenna distance [m], the thesis's (§3.3.2) and seatwin's default for Havfruen."""
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


TRACK_SPECS: dict[str, tuple[tuple[float, float], float, float, float]] = {
    "Havfruen": ((-60.0, -40.0), 60.0, 2.5, 0.5),
    "Finn": ((40.0, 110.0), 235.0, 3.0, 0.3),
    "milliAmpere": ((-30.0, 10.0), 155.0, 1.2, 0.0),
}
"""Each vessel's start (north, east [m] about :data:`ORIGIN`), heading [deg], speed [m/s] and turn rate [deg/s]."""


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
    havfruen = _track(t, *TRACK_SPECS["Havfruen"])
    milliampere = _track(t, *TRACK_SPECS["milliAmpere"])
    finn = _track(t, *TRACK_SPECS["Finn"])
    return [
        write_pos(out / "havfruen_bow.pos", t, *_antenna(t, havfruen, BASELINE_M / 2, "havfruen/bow")),
        write_pos(out / "havfruen_stern.pos", t, *_antenna(t, havfruen, -BASELINE_M / 2, "havfruen/stern")),
        write_nmea(out / "milliampere.nmea", t, *_antenna(t, milliampere, 0.0, "milliampere")),
        write_gpx(out / "finn.gpx", t, *_antenna(t, finn, 0.0, "finn")),
        write_csv(out / "finn.csv", t, *_antenna(t, finn, 0.0, "finn")),
    ]
