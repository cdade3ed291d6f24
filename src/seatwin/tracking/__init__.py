"""Multi-target tracking: JIPDA with extended Kalman filters (thesis ch. 5.1)."""

from seatwin.tracking.config import PRESETS, SensorTuning, TrackerConfig, load_tuning
from seatwin.tracking.tracker import COLUMNS, JIPDATracker, TrackTable, track

__all__ = ["COLUMNS", "JIPDATracker", "PRESETS", "SensorTuning", "TrackTable", "TrackerConfig", "load_tuning", "track"]
