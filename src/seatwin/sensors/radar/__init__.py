"""A rotating marine radar: ray-cast illumination, Swerling detection, plot extraction, clutter, fit.

Public API:

* :class:`RadarConfig` (+ :func:`load_radar_config`, :func:`save_radar_config`) — parameters.
* :class:`RadarModel` — ``scan(frame, time, antenna, caster, kinds)`` → :class:`RadarScan` plots.
* :class:`AntennaPose` — where the antenna is and which way the platform points.
* :func:`detection_probability` — Pd(range, visible area).
* :mod:`seatwin.sensors.radar.fit` — parameters from a real recording's statistics.
"""

from seatwin.sensors.radar.config import RadarConfig, load_radar_config, radar_config_from_dict, save_radar_config
from seatwin.sensors.radar.detection import detection_probability, snr_linear, swerling1_pd
from seatwin.sensors.radar.geometry import AntennaPose, illuminate
from seatwin.sensors.radar.model import RadarModel, RadarScan
from seatwin.sensors.radar.plots import Cells, extract_plots
from seatwin.sensors.radar.spokes import RadarSpokes

__all__ = [
    "AntennaPose",
    "Cells",
    "RadarConfig",
    "RadarModel",
    "RadarScan",
    "RadarSpokes",
    "detection_probability",
    "extract_plots",
    "illuminate",
    "load_radar_config",
    "radar_config_from_dict",
    "save_radar_config",
    "snr_linear",
    "swerling1_pd",
]
