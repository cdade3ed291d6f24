"""Spinning-lidar configuration, the Velodyne VLP-16 presets and the sensor mount (settings models, :mod:`seatwin.settings`).

Sensor frame (REP-103): x forward, y left, z up. Beam directions of column k and laser l:
azimuth φ_k = −2πk/C (the head spins clockwise seen from its top, as Velodyne's do, and a
sweep starts on the sensor's x axis), elevation ω_l, direction
``(cos ω cos φ, cos ω sin φ, sin ω)`` — thesis (3.1) with θ = 90° − ω.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, ValidationInfo, field_validator

from seatwin.errors import InputError, ParameterError
from seatwin.geo.frames import mount_matrix
from seatwin.settings import Settings
from seatwin.world.vessels import MILLIAMPERE_LIDAR_HEIGHT


class IntensityModel(Settings):
    """Return intensity ``scale · ρ · cos θ · (r_ref / max(r, r_ref))^exponent``, clipped to 0–255.

    ρ: object reflectivity, θ: incidence angle (ray vs surface normal), r: range. With the
    default exponent 2 it is the lidar equation for an extended diffuse target (received
    power ∝ ρ cos θ / r²), flat inside ``reference_range`` (where a real receiver's gain
    control and calibration keep the reported value about constant). The numbers are not
    fitted to real VLP-16 data: treat intensities as relative.
    """

    scale: float = Field(
        255.0, ge=0, description="Intensity of a perpendicular return from reflectivity 1 inside the reference range."
    )
    reference_range: float = Field(40.0, gt=0, description="Range inside which the intensity does not fall off [m].")
    exponent: float = Field(
        2.0, ge=0, description="Exponent of the fall-off with range beyond the reference range (2: the lidar equation)."
    )


class RangeDissipation(Settings):
    """Range-dependent return probability ``1 / (1 + exp((r − half_range) / width))``.

    The thesis (5.2.2, Fig. 5.10) found the real VLP-16 returned far fewer points at range
    than its maximum range suggests; this models that fall-off.
    """

    half_range: float = Field(60.0, gt=0, description="Range where half the returns survive [m].")
    width: float = Field(8.0, gt=0, description="Steepness of the fall-off [m].")


class LidarConfig(Settings):
    """A spinning multi-beam lidar (build variants with :meth:`with_`)."""

    name: str = Field("vlp16", description="Name of the sensor model.")
    elevations_deg: tuple[float, ...] = Field(
        tuple(float(e) for e in range(-15, 16, 2)),
        min_length=1,
        description="Laser elevations, ascending (ring r = index into this tuple) [deg].",
    )
    columns: int = Field(1800, ge=1, description="Firings per revolution (azimuth resolution 360°/columns).")
    rate_hz: float = Field(10.0, gt=0, description="Revolutions per second; a sweep lasts 1/rate_hz [Hz].")
    max_range: float = Field(100.0, gt=0, description="Farthest return [m].")
    min_range: float = Field(
        0.05, ge=0, description="Returns nearer than this are discarded (thesis 4.2.3: near plane 5 cm) [m]."
    )
    range_accuracy: float = Field(
        0.03, ge=0, description="± range accuracy of the data sheet, taken as 2σ of Gaussian noise [m]."
    )
    drop_probability: float = Field(
        0.8, ge=0, le=1, description="Probability that a beam returns nothing (thesis 4.2.2 used 80 %)."
    )
    dissipation: RangeDissipation | None = Field(None, description="Range-dependent return probability (default: none).")
    intensity: IntensityModel = Field(default_factory=IntensityModel, description="Return intensity model.")

    @field_validator("elevations_deg")
    @classmethod
    def _ascending(cls, v: tuple[float, ...]) -> tuple[float, ...]:
        if list(v) != sorted(v):
            raise ValueError("elevations must be ascending")
        return v

    @field_validator("min_range")
    @classmethod
    def _below_max(cls, v: float, info: ValidationInfo) -> float:
        if "max_range" in info.data and not v < info.data["max_range"]:
            raise ValueError(f"must be below max_range {info.data['max_range']}")
        return v

    @property
    def rings(self) -> int:
        return len(self.elevations_deg)

    @property
    def beams(self) -> int:
        """Beams per sweep (columns × rings)."""
        return self.columns * self.rings

    @property
    def period(self) -> float:
        return 1.0 / self.rate_hz

    @property
    def range_noise_std(self) -> float:
        return self.range_accuracy / 2.0

    def column_offsets(self) -> NDArray[np.float64]:
        """Time of each column's firing since the sweep start [s]."""
        return np.arange(self.columns) * (self.period / self.columns)

    def sensor_directions(self) -> NDArray[np.float32]:
        """Unit beam directions in the sensor frame, (columns·rings, 3), azimuth-major."""
        phi = -2.0 * np.pi * np.arange(self.columns) / self.columns
        om = np.radians(np.asarray(self.elevations_deg))
        d = np.stack(
            [
                np.cos(om)[None, :] * np.cos(phi)[:, None],
                np.cos(om)[None, :] * np.sin(phi)[:, None],
                np.broadcast_to(np.sin(om), (self.columns, len(om))),
            ],
            axis=-1,
        )
        return d.reshape(-1, 3).astype(np.float32)


VLP16 = LidarConfig()
"""Velodyne VLP-16 Puck: 16 lasers −15°…+15° in 2° steps, 10 Hz, 1800 columns (0.2°, the real
sensor at 10 Hz), 100 m, ±3 cm (thesis 3.2.1, 4.2.3)."""

VLP16_THESIS = VLP16.with_(name="vlp16-thesis", columns=1024)
"""The VLP-16 as the thesis simulated it: 1024 columns (thesis 4.2.5, PointCloud2 width 16 × 1024)."""

PRESETS: dict[str, LidarConfig] = {"vlp16": VLP16, "vlp16-thesis": VLP16_THESIS}


def lidar_preset(preset: str) -> LidarConfig:
    """A preset by name (case-insensitive)."""
    try:
        return PRESETS[preset.lower()]
    except KeyError:
        raise ParameterError("preset", f"unknown lidar preset {preset!r}; known: {', '.join(sorted(PRESETS))}") from None


class LidarMount(Settings):
    """Pose of the sensor frame in the carrier's body frame (x fwd, y starboard, z down).

    Position ``(x, y, z)`` [m] (z < 0 above the water). Orientation: the sensor upright with
    its x axis forward, then rolled by ``roll_deg`` about its own x axis (180 = upside
    down), pitched by ``pitch_deg`` (nose up) and turned by ``yaw_deg`` clockwise seen from
    above. For a fixed (shore) sensor with no carrier the same numbers are a pose in the
    world NED frame.
    """

    x: float = Field(0.0, description="Forward offset from the carrier's reference point [m].")
    y: float = Field(0.0, description="Starboard offset [m].")
    z: float = Field(-MILLIAMPERE_LIDAR_HEIGHT, description="Down offset; negative above the water [m].")
    yaw_deg: float = Field(0.0, description="Turned clockwise seen from above [deg].")
    pitch_deg: float = Field(0.0, description="Pitched nose up [deg].")
    roll_deg: float = Field(0.0, description="Rolled about the sensor's own x axis (180: upside down) [deg].")

    @property
    def translation(self) -> NDArray[np.float64]:
        return np.array([self.x, self.y, self.z])

    def rotation(self) -> NDArray[np.float64]:
        """R such that ``v_body = R @ v_sensor`` (REP-103 sensor axes, :func:`seatwin.geo.mount_matrix`)."""
        r, p, y = np.radians([self.roll_deg, self.pitch_deg, self.yaw_deg])
        return mount_matrix("flu", roll=r, pitch=p, yaw=y)


MILLIAMPERE_LIDAR_MOUNT = LidarMount(x=0.0, y=0.0, z=-MILLIAMPERE_LIDAR_HEIGHT, yaw_deg=57.3, roll_deg=180.0)
"""The VLP-16 on milliAmpere's rig (thesis 3.2.1): "attached upside down, rotated 57.3°
clockwise relative to the sensor rig's front camera direction, seen from above"; the front
camera is aligned with the vessel's longitudinal axis, so the sensor's x axis points 57.3°
to starboard of the bow, and its z axis points down. (57.3° is one radian.)"""


def load_lidar_config(path: str | Path) -> LidarConfig:
    """A lidar YAML file (the parameters under a top-level ``lidar:`` key, or at the top; e.g. ``seatwin lidar fit``'s
    output, whose ``fit:`` report is not read); an :class:`InputError` naming the file and field on bad content."""
    from seatwin.safe_yaml import load_yaml
    from seatwin.settings import validated

    p = Path(path)
    if not p.is_file():
        raise InputError(p, "no such lidar configuration file")
    data = load_yaml(p, "a lidar YAML file")
    if not isinstance(data, dict):
        raise InputError(p, f"expected a mapping of lidar parameters, got {type(data).__name__}")
    data = data.get("lidar", data)
    if not isinstance(data, dict):
        raise InputError(p, f"expected a mapping of lidar parameters, got {type(data).__name__}", where="lidar")
    return validated(LidarConfig, data, p)


def save_lidar_config(config: LidarConfig, path: str | Path, report: dict[str, Any] | None = None) -> Path:
    """Write ``config`` as YAML under a top-level ``lidar:`` key (and ``report`` under ``fit:``); returns the path."""
    import yaml

    from seatwin.outputs import write_text_atomic

    doc: dict[str, Any] = {"lidar": config.model_dump(mode="json")}
    if report is not None:
        doc["fit"] = report
    p = Path(path)
    write_text_atomic(p, yaml.safe_dump(doc, sort_keys=False, allow_unicode=True))
    return p
