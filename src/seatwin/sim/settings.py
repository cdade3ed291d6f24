"""What a simulation run varies: which sensors, the lidar's range model and degradations, the radar, the bag.

Flat names, so that a sweep or a campaign varies a setting by its name (``lidar_mode``, ``ray_drop``).
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, field_validator, model_validator

from seatwin.defaults import DEFAULT_IMAGE_FORMAT, DEFAULT_ROS_DISTRO, DEFAULT_SENSORS, Compression, ImageFormat
from seatwin.layout.harbours import check_harbour_spec
from seatwin.settings import Settings

SENSOR_NAMES = ("lidar", "radar", "camera")
LIDAR_MODES = ("raycast", "depthbuffer", "depthbuffer-legacy", "depthbuffer-plane")
BAG_FORMATS = ("mcap", "sqlite3", "ros1")


class BagOptions(Settings):
    """How a run's bag is written beyond its format (``fmt``, a field of the subclass): chunk compression and image format."""

    compression: Compression | None = Field(
        None,
        description="Compression of the bag: mcap chunks lz4 (default), zstd or none; ros1 chunks lz4 (default), bz2 "
        "or none; sqlite3 none (default), zstd (rosbag2's per-message zstd) or zstd-file (the .db3 file as .db3.zstd). "
        "None: the format's default.",
    )
    image_format: ImageFormat = Field(
        DEFAULT_IMAGE_FORMAT,
        description="Camera images as sensor_msgs/Image bgr8 (raw, as the thesis) or sensor_msgs/CompressedImage "
        "(jpeg quality 90, png) on <image topic>/compressed.",
    )

    @model_validator(mode="after")
    def _compression_of_format(self) -> BagOptions:
        from seatwin.recording.config import check_compression

        check_compression(getattr(self, "fmt", "mcap"), self.compression)
        return self

    def writer_options(self) -> dict[str, str | None]:
        """The :class:`~seatwin.recording.RecordingWriter` keywords these settings choose."""
        return {"compression": self.compression, "image_format": self.image_format}


class SimulationSettings(BagOptions):
    """Every choice of ``simulate`` besides the scenario and the time window."""

    sensors: tuple[Literal["lidar", "radar", "camera"], ...] = Field(
        DEFAULT_SENSORS,
        min_length=1,
        description="Sensors on the ownship, simulated in one loop (ground truth is always recorded).",
    )
    seed: int | None = Field(None, description="Seed of every random draw (default: the scenario's).")
    lidar_preset: Literal["vlp16", "vlp16-thesis"] = Field(
        "vlp16", description="vlp16 (1800 columns, the real sensor at 10 Hz) or vlp16-thesis (1024 columns)."
    )
    lidar_mode: Literal["raycast", "depthbuffer", "depthbuffer-legacy", "depthbuffer-plane"] = Field(
        "raycast",
        description="Lidar range model: exact ray casting, or the thesis's depth-buffer model (with or "
        "without the spherical projection filter), or depthbuffer-plane (rasterised by OpenGL, each beam "
        "intersected with its pixel's surface plane).",
    )
    lidar_config: str | None = Field(
        None,
        description="Lidar YAML (e.g. from 'seatwin lidar fit'): replaces the preset's parameters; ray_drop, "
        "range_noise and dissipation still apply on top of it.",
    )
    ray_drop: float | None = Field(
        None, ge=0.0, lt=1.0, description="Ray-drop probability (default: the preset's 0.8, as the thesis)."
    )
    range_noise: float | None = Field(None, ge=0.0, description="Range noise σ [m] (default: the preset's 0.015).")
    dissipation: bool = Field(False, description="Range-dependent return probability (thesis 5.2.2, Fig. 5.10).")
    mount_yaw_bias_deg: float = Field(
        0.0,
        description="Lidar turned by this much more than its nominal mount while /tf_static records the nominal "
        "one (a miscalibrated extrinsic) [deg].",
    )
    harbour: str | None = Field(
        None,
        description="Harbour to simulate in instead of the scenario's own (a Gemini CSV's is 'ravnkloa', a "
        "built-in's 'default'): 'default' (the built-in layout), 'ravnkloa' (the real land raster, found in "
        "$SEATWIN_DATA or shared/data), 'none', or a land raster (.bin/.yaml, Ravnkloa base-map format).",
    )
    radar_config: str | None = Field(None, description="Radar YAML (default: the built-in radar model).")
    radar_spokes: bool = Field(
        False,
        description="Keep each radar rotation's raw spokes (Gemini RadarStreamingRequest "
        "layout) on the captured frames, for export or streaming.",
    )
    camera_hfov_deg: float = Field(82.0, gt=1.0, lt=179.0, description="Cameras' horizontal field of view [deg].")
    camera_distortion: tuple[float, float, float, float, float] = Field(
        (0.0, 0.0, 0.0, 0.0, 0.0), description="Plumb-bob k1 k2 t1 t2 k3 applied to the camera images (zeros: pinhole)."
    )
    camera_labels: bool = Field(True, description="Record ground-truth 2-D boxes of the vessels per camera image.")
    fmt: Literal["mcap", "sqlite3", "ros1"] = Field("mcap", description="Bag format.")
    ros_distro: Literal["humble", "iron", "jazzy", "kilted"] = Field(
        DEFAULT_ROS_DISTRO,
        description="ROS 2 distribution a rosbag2 bag (mcap, sqlite3) is written for: its metadata version "
        "(humble 5, iron 7, jazzy and kilted 9); a distro reads its own version and older ones.",
    )
    ground_truth_rate_hz: float = Field(10.0, gt=0, description="Rate of the ground-truth topics [Hz].")

    @field_validator("mount_yaw_bias_deg")
    @classmethod
    def _finite(cls, v: float) -> float:
        if not math.isfinite(v):
            raise ValueError("expected a finite angle in degrees")
        return v

    @field_validator("harbour")
    @classmethod
    def _harbour(cls, v: str | None) -> str | None:
        return None if v is None else check_harbour_spec(v)

    @field_validator("sensors")
    @classmethod
    def _unique(cls, v: tuple[str, ...]) -> tuple[str, ...]:
        if len(set(v)) != len(v):
            raise ValueError("a sensor is repeated")
        return v
