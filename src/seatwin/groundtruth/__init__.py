"""Vessel ground truth from GNSS antenna logs (thesis §3.3.2).

Readers (GPX, NMEA 0183 GGA, RTKLIB .pos, generic CSV) → :class:`AntennaLog`; one common
clock (:mod:`.resample`); per vessel position, heading (eq. 3.6 or course over ground) and
ε_gnss (eq. 3.7) flags (:mod:`.vessel`); Gemini CSV, JSON quality report and figures
(:mod:`.pipeline`).
"""

from seatwin.groundtruth.detect import detect_format, read_antenna_log
from seatwin.groundtruth.equations import (
    antenna_distance,
    antenna_midpoint,
    course_over_ground,
    gnss_baseline_error,
    velocity_central,
)
from seatwin.groundtruth.gpstime import gps_minus_utc, gps_week_to_utc, gpst_to_utc
from seatwin.groundtruth.log import AntennaLog, quality_name
from seatwin.groundtruth.pipeline import GroundTruthResult, compute_ground_truth, write_outputs
from seatwin.groundtruth.read_csv import read_csv_log
from seatwin.groundtruth.read_gpx import read_gpx
from seatwin.groundtruth.read_nmea import read_nmea
from seatwin.groundtruth.read_rtklib import read_rtklib_pos
from seatwin.groundtruth.resample import ResampledLog, common_clock, resample_log
from seatwin.groundtruth.vessel import (
    FLAG_EPS,
    FLAG_GAP,
    FLAG_LOW_SPEED,
    KNOWN_BASELINES_M,
    VesselGroundTruth,
    VesselSpec,
    build_vessel,
)

__all__ = [
    "FLAG_EPS",
    "FLAG_GAP",
    "FLAG_LOW_SPEED",
    "KNOWN_BASELINES_M",
    "AntennaLog",
    "GroundTruthResult",
    "ResampledLog",
    "VesselGroundTruth",
    "VesselSpec",
    "antenna_distance",
    "antenna_midpoint",
    "build_vessel",
    "common_clock",
    "compute_ground_truth",
    "course_over_ground",
    "detect_format",
    "gnss_baseline_error",
    "gps_minus_utc",
    "gps_week_to_utc",
    "gpst_to_utc",
    "quality_name",
    "read_antenna_log",
    "read_csv_log",
    "read_gpx",
    "read_nmea",
    "read_rtklib_pos",
    "resample_log",
    "velocity_central",
    "write_outputs",
]
