"""Multi-target tracking: JIPDA with extended Kalman filters (thesis ch. 5.1)."""

from seatwin.tracking.config import PRESETS, SensorTuning, TrackerConfig, load_tuning
from seatwin.tracking.tracker import COLUMNS, JIPDATracker, TrackRun, TrackTable, run_tracker, track

__all__ = [
    "COLUMNS",
    "JIPDATracker",
    "PRESETS",
    "SensorTuning",
    "TrackRun",
    "TrackTable",
    "TrackerConfig",
    "load_tuning",
    "run_tracker",
    "track",
]
