"""The camera rig's settings (thesis 3.2.1, 4.2.1, Table 4.1).

milliAmpere's rig carries 5 RGB cameras evenly spread in azimuth (72° apart), the front one
along the vessel's axis, each pitched 15° down; only the 3 frontal ones (left, front, right)
were recorded, at 5 Hz. The thesis renders 612 × 512 images (the real ones cropped to that) with
a hand-calibrated field of view (82° nominal), near plane 8 cm, far plane 10 km.
"""

from __future__ import annotations

import math

from pydantic import Field, field_validator, model_validator

from seatwin.settings import Settings

RIG_CAMERAS = 5
"""Cameras on the rig, evenly spread in azimuth."""
RIG_SPACING_DEG = 360.0 / RIG_CAMERAS
"""72°: the azimuth between neighbouring cameras."""


class CameraConfig(Settings):
    """The three frontal RGB cameras of milliAmpere's rig (all share one set of intrinsics)."""

    names: tuple[str, ...] = Field(("left", "front", "right"), min_length=1, description="Camera names (topic prefixes).")
    azimuths_deg: tuple[float, ...] = Field(
        (-RIG_SPACING_DEG, 0.0, RIG_SPACING_DEG),
        description="Yaw of each camera from the bow, clockwise (to starboard) [deg]; one per name.",
    )
    pitch_down_deg: float = Field(15.0, ge=-90.0, le=90.0, description="Downward pitch of every camera [deg].")
    hfov_deg: float = Field(82.0, gt=1.0, lt=179.0, description="Horizontal field of view [deg] (pinhole).")
    width: int = Field(612, ge=16, le=8192, description="Image width [pixels].")
    height: int = Field(512, ge=16, le=8192, description="Image height [pixels].")
    rate_hz: float = Field(5.0, gt=0.0, le=60.0, description="Frame rate [Hz].")
    phase_s: float = Field(0.0, ge=0.0, description="Offset of the first frame after the start [s].")
    distortion: tuple[float, float, float, float, float] = Field(
        (0.0, 0.0, 0.0, 0.0, 0.0),
        description="Plumb-bob distortion k1 k2 t1 t2 k3 applied to the synthetic image (all zero: a pinhole).",
    )
    near_m: float = Field(0.08, gt=0.0, description="Near plane [m] (thesis: 8 cm, outside the rig).")
    far_m: float = Field(10_000.0, gt=0.0, description="Far plane [m] (thesis: 10 km).")
    mount_x_m: float = Field(0.0, description="Rig position forward of the vessel's reference point [m].")
    mount_y_m: float = Field(0.0, description="Rig position to starboard [m].")
    height_m: float = Field(2.8, gt=0.0, description="Camera centres above the waterline [m] (just below the lidar).")
    sun_azimuth_deg: float = Field(200.0, description="Sun azimuth, clockwise from north [deg].")
    sun_elevation_deg: float = Field(35.0, ge=-10.0, le=90.0, description="Sun elevation [deg].")
    labels: bool = Field(True, description="Record ground-truth 2-D boxes (vision_msgs/Detection2DArray) per image.")
    min_visible_pixels: int = Field(
        1, ge=0, description="A vessel in view is labelled when at least this many of its pixels are seen (0: hidden ones too)."
    )

    @field_validator("distortion", "azimuths_deg")
    @classmethod
    def _finite(cls, v: tuple[float, ...]) -> tuple[float, ...]:
        if not all(math.isfinite(x) for x in v):
            raise ValueError("expected finite numbers")
        return v

    @model_validator(mode="after")
    def _one_azimuth_per_camera(self) -> CameraConfig:
        if len(self.azimuths_deg) != len(self.names):
            raise ValueError(f"azimuths_deg: expected one azimuth per camera ({len(self.names)}), got {len(self.azimuths_deg)}")
        if len(set(self.names)) != len(self.names):
            raise ValueError("names: a camera name is repeated")
        if self.far_m <= self.near_m:
            raise ValueError("far_m must exceed near_m")
        return self

    @property
    def has_distortion(self) -> bool:
        return any(x != 0.0 for x in self.distortion)
