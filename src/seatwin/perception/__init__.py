"""Perception: sensor data → measurements (:class:`Scan`) for the tracker."""

from seatwin.perception.measurements import MeasurementKind, Scan, cartesian_to_polar, polar_to_cartesian

__all__ = ["MeasurementKind", "Scan", "cartesian_to_polar", "polar_to_cartesian"]
