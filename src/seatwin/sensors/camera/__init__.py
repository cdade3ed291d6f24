"""The RGB camera rig of milliAmpere (thesis 3.2.1, 4.2.1): rig, intrinsics, plumb-bob distortion, auto-labels.

Rendering is :mod:`seatwin.render`; the camera as a loop sensor is :mod:`seatwin.sim.camera`.
"""

from seatwin.sensors.camera.config import CameraConfig
from seatwin.sensors.camera.intrinsics import DistortionMap, distort, focal_from_hfov, intrinsic_matrix, project, undistort
from seatwin.sensors.camera.labels import BoxLabel, ground_truth_boxes
from seatwin.sensors.camera.rig import CameraMount, camera_info_fields, optical_frame, rig_mounts

__all__ = [
    "BoxLabel",
    "CameraConfig",
    "CameraMount",
    "DistortionMap",
    "camera_info_fields",
    "distort",
    "focal_from_hfov",
    "ground_truth_boxes",
    "intrinsic_matrix",
    "optical_frame",
    "project",
    "rig_mounts",
    "undistort",
]
