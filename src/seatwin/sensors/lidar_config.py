"""Spinning-lidar configuration, the Velodyne VLP-16 presets and the sensor mount.

Sensor frame (REP-103): x forward, y left, z up. Beam directions of column k and laser l:
azimuth φ_k = −2πk/C (the head spins clockwise seen from its top, as Velodyne's do, and a
sweep starts on the sensor's x axis), elevation ω_l, direction
``(cos ω cos φ, cos ω sin φ, sin ω)`` — thesis (3.1) with θ = 90° − ω.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError
from seatwin.geo.frames import mount_matrix
from seatwin.world.vessels import MILLIAMPERE_LIDAR_HEIGHT


@dataclass(frozen=True)
class IntensityModel:
    """Return intensity ``scale · ρ · cos θ · (r_ref / max(r, r_ref))^exponent``, clipped to 0–255.

    ρ: object reflectivity, θ: incidence angle (ray vs surface normal), r: range. With the
    default exponent 2 it is the lidar equation for an extended diffuse target (received
    power ∝ ρ cos θ / r²), flat inside ``reference_range`` (where a real receiver's gain
    control and calibration keep the reported value about constant). The numbers are not
    fitted to real VLP-16 data: treat intensities as relative.
    """

    scale: float = 255.0
    reference_range: float = 40.0
    exponent: float = 2.0


@dataclass(frozen=True)
class RangeDissipation:
    """Range-dependent return probability ``1 / (1 + exp((r − half_range) / width))``.

    The thesis (5.2.2, Fig. 5.10) found the real VLP-16 returned far fewer points at range
    than its maximum range suggests; this models that fall-off.
    """

    half_range: float = 60.0
    """Range where half the returns survive [m]."""
    width: float = 8.0
    """Steepness of the fall-off [m]."""


@dataclass(frozen=True)
class LidarConfig:
    """A spinning multi-beam lidar."""

    name: str = "vlp16"
    elevations_deg: tuple[float, ...] = tuple(float(e) for e in range(-15, 16, 2))
    """Laser elevations, ascending (ring r = index into this tuple)."""
    columns: int = 1800
    """Firings per revolution (azimuth resolution 360°/columns)."""
    rate_hz: float = 10.0
    """Revolutions per second; a sweep lasts 1/rate_hz."""
    max_range: float = 100.0
    min_range: float = 0.05
    """Returns nearer than this are discarded (thesis 4.2.3: near plane 5 cm)."""
    range_accuracy: float = 0.03
    """± range accuracy of the data sheet [m], taken as 2σ of Gaussian noise."""
    drop_probability: float = 0.8
    """Probability that a beam returns nothing (thesis 4.2.2 used 80 %)."""
    dissipation: RangeDissipation | None = None
    intensity: IntensityModel = field(default_factory=IntensityModel)

    def __post_init__(self) -> None:
        if not self.elevations_deg or list(self.elevations_deg) != sorted(self.elevations_deg):
            raise InputError(None, f"elevations must be non-empty and ascending, got {self.elevations_deg}", where="lidar.elevations_deg")
        if self.columns < 1 or self.rate_hz <= 0 or self.max_range <= self.min_range or self.min_range < 0:
            raise InputError(None, "lidar needs columns ≥ 1, rate_hz > 0 and 0 ≤ min_range < max_range", where=f"lidar {self.name}")
        if not 0.0 <= self.drop_probability <= 1.0:
            raise InputError(None, f"drop_probability must be in [0, 1], got {self.drop_probability}", where="lidar.drop_probability")

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
            [np.cos(om)[None, :] * np.cos(phi)[:, None], np.cos(om)[None, :] * np.sin(phi)[:, None], np.broadcast_to(np.sin(om), (self.columns, len(om)))],
            axis=-1,
        )
        return d.reshape(-1, 3).astype(np.float32)

    def with_(self, **changes: object) -> LidarConfig:
        return replace(self, **changes)  # type: ignore[arg-type]


VLP16 = LidarConfig()
"""Velodyne VLP-16 Puck: 16 lasers −15°…+15° in 2° steps, 10 Hz, 1800 columns (0.2°, the real
sensor at 10 Hz), 100 m, ±3 cm (thesis 3.2.1, 4.2.3)."""

VLP16_THESIS = replace(VLP16, name="vlp16-thesis", columns=1024)
"""The VLP-16 as the thesis simulated it: 1024 columns (thesis 4.2.5, PointCloud2 width 16 × 1024)."""

PRESETS: dict[str, LidarConfig] = {"vlp16": VLP16, "vlp16-thesis": VLP16_THESIS}


def lidar_preset(name: str) -> LidarConfig:
    """A preset by name."""
    try:
        return PRESETS[name.lower()]
    except KeyError:
        raise InputError(None, f"unknown lidar preset {name!r}; known: {sorted(PRESETS)}", where="lidar") from None


@dataclass(frozen=True)
class LidarMount:
    """Pose of the sensor frame in the carrier's body frame (x fwd, y starboard, z down).

    Position ``(x, y, z)`` [m] (z < 0 above the water). Orientation: the sensor upright with
    its x axis forward, then rolled by ``roll_deg`` about its own x axis (180 = upside
    down), pitched by ``pitch_deg`` (nose up) and turned by ``yaw_deg`` clockwise seen from
    above. For a fixed (shore) sensor with no carrier the same numbers are a pose in the
    world NED frame.
    """

    x: float = 0.0
    y: float = 0.0
    z: float = -MILLIAMPERE_LIDAR_HEIGHT
    yaw_deg: float = 0.0
    pitch_deg: float = 0.0
    roll_deg: float = 0.0

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
