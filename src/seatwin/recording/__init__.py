"""Recording: ROS messages (thesis ch. 4.2.5, Table 4.2), bag writing and reading in MCAP, SQLite3 and ROS 1."""

from seatwin.recording.chunks import ReadOptions
from seatwin.recording.config import FORMATS, TopicConfig, ros_name
from seatwin.recording.messages import StaticTransform, VesselPose, mount_rotation
from seatwin.recording.pointcloud import RADAR_LAYOUT, VLP16_LAYOUT, Field, Layout, dtype_from_fields, pack, unpack
from seatwin.recording.reader import ImageFrame, PointCloud, Recording, VesselTruth, open_bag
from seatwin.recording.writer import RecordingError, RecordingWriter, open_recording

__all__ = [
    "FORMATS",
    "RADAR_LAYOUT",
    "VLP16_LAYOUT",
    "Field",
    "ImageFrame",
    "Layout",
    "PointCloud",
    "ReadOptions",
    "Recording",
    "RecordingError",
    "RecordingWriter",
    "StaticTransform",
    "TopicConfig",
    "VesselPose",
    "VesselTruth",
    "dtype_from_fields",
    "mount_rotation",
    "open_bag",
    "open_recording",
    "pack",
    "ros_name",
    "unpack",
]
