"""The radar's parameters (pydantic), loaded from and saved to YAML.

Angles are radians inside; the YAML file states them in degrees where the key says
``_deg`` (that is the file boundary). Every field has a default so that a file may set
only what differs (a fitted file sets the noise, detection and clutter sections).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from seatwin.errors import InputError


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", validate_assignment=True, allow_inf_nan=False)


class DetectionConfig(_Strict):
    """Probability of detecting a vessel in one scan: Swerling I with a radar-equation SNR.

    ``SNR = snr_ref · (A / area_ref) · (range_ref / R)^4`` with ``A`` the target's visible
    area (cross-range width × height seen from the antenna, m²), and
    ``Pd = pd_max · pfa^(1 / (1 + SNR))`` (Swerling I in a square-law detector).
    """

    snr_ref_db: float = Field(20.0, description="SNR [dB] of a reference target at range_ref")
    range_ref_m: float = Field(1000.0, gt=0)
    area_ref_m2: float = Field(10.0, gt=0, description="visible area of the reference target [m²]")
    pfa: float = Field(1e-6, gt=0, lt=1, description="false-alarm probability of one cell's threshold")
    pd_max: float = Field(0.99, gt=0, le=1, description="cap on Pd (blockage, interference, processing losses)")


class NoiseConfig(_Strict):
    """Gaussian errors of a plot's position, in range and bearing (bias + standard deviation)."""

    range_sigma_m: float = Field(3.0, ge=0)
    range_bias_m: float = 0.0
    bearing_sigma_deg: float = Field(0.5, ge=0)
    bearing_bias_deg: float = 0.0

    @property
    def bearing_sigma(self) -> float:
        return math.radians(self.bearing_sigma_deg)

    @property
    def bearing_bias(self) -> float:
        return math.radians(self.bearing_bias_deg)


class ClutterMap(_Strict):
    """A spatial clutter density in the world frame: ``density[row][col]`` plots per m² per scan.

    Cell (row r, column c) covers north ∈ [north0 + r·cell, north0 + (r+1)·cell) and
    east ∈ [east0 + c·cell, east0 + (c+1)·cell); outside the grid ``outside_density`` holds.
    """

    north0_m: float
    east0_m: float
    cell_m: float = Field(gt=0)
    density: list[list[float]]
    outside_density: float = Field(0.0, ge=0)

    @model_validator(mode="after")
    def _rectangular(self) -> ClutterMap:
        if not self.density or not self.density[0]:
            raise ValueError("density must be a non-empty 2-D grid")
        w = len(self.density[0])
        for i, row in enumerate(self.density):
            if len(row) != w:
                raise ValueError(f"density row {i} has {len(row)} values, row 0 has {w}")
            if any(v < 0 or not math.isfinite(v) for v in row):
                raise ValueError(f"density row {i} has a negative or non-finite value")
        return self


class ClutterConfig(_Strict):
    """False plots: Poisson in number, placed by a uniform density or by a map."""

    kind: Literal["uniform", "map", "none"] = "uniform"
    density_per_km2: float = Field(0.5, ge=0, description="uniform density: false plots per km² per scan")
    map: ClutterMap | None = None

    @model_validator(mode="after")
    def _map_given(self) -> ClutterConfig:
        if self.kind == "map" and self.map is None:
            raise ValueError("clutter kind 'map' needs a 'map' section")
        return self


class LandConfig(_Strict):
    """Returns from land, quays and buildings (objects whose kind is ``land``)."""

    enabled: bool = True
    cell_pd: float = Field(0.6, ge=0, le=1, description="probability that one illuminated land cell crosses the threshold")


class PlotExtractionConfig(_Strict):
    """How cells above threshold become plots: merged when close, split when large."""

    merge_gap_spokes: int = Field(2, ge=1, description="cells this many spokes apart (or fewer) join one plot")
    merge_gap_samples: int = Field(2, ge=1, description="cells this many range samples apart (or fewer) join one plot")
    max_plot_extent_m: float = Field(40.0, gt=0, description="larger blobs are split into tiles of this size")
    min_cells: int = Field(1, ge=1, description="blobs with fewer cells are dropped")


class SpokesConfig(_Strict):
    """Raw spoke output in the Gemini ``RadarStreamingRequest`` layout (optional, costly)."""

    enabled: bool = False
    noise_floor: float = Field(8.0, ge=0, le=255, description="mean of the Rayleigh background intensity")


class RadarConfig(_Strict):
    """A rotating marine radar: geometry, resolution, detection, noise, clutter, plot extraction."""

    name: str = "generic-x-band"
    rotation_period_s: float = Field(2.5, gt=0)
    n_spokes: int = Field(2048, ge=16, description="azimuth steps per rotation (bearing resolution)")
    range_increment_m: float = Field(2.0, gt=0, description="range resolution (one sample)")
    range_start_m: float = Field(0.0, ge=0)
    min_range_m: float = Field(20.0, ge=0)
    max_range_m: float = Field(2500.0, gt=0)
    beam_width_deg: float = Field(1.8, gt=0, lt=90, description="horizontal one-way beam width")
    vertical_beam_width_deg: float = Field(25.0, gt=0, lt=90)
    antenna_height_m: float = Field(3.0, gt=0, description="above the water line")
    mount_x_m: float = Field(0.0, description="antenna position in the body frame, forward")
    mount_y_m: float = Field(0.0, description="antenna position in the body frame, starboard")
    pose_at: Literal["scan", "beam"] = Field(
        "scan",
        description="where other vessels are when seen: at the scan stamp ('scan'), or when the beam passes "
        "them ('beam': stamp + azimuth/2π × rotation period, spoke 0 at the bow)",
    )
    detection: DetectionConfig = Field(default_factory=DetectionConfig)
    noise: NoiseConfig = Field(default_factory=NoiseConfig)
    clutter: ClutterConfig = Field(default_factory=ClutterConfig)
    land: LandConfig = Field(default_factory=LandConfig)
    plots: PlotExtractionConfig = Field(default_factory=PlotExtractionConfig)
    spokes: SpokesConfig = Field(default_factory=SpokesConfig)
    fit: dict[str, Any] | None = Field(None, description="the fit's report (estimates with uncertainties), if fitted")

    @model_validator(mode="after")
    def _ranges(self) -> RadarConfig:
        if self.min_range_m >= self.max_range_m:
            raise ValueError(f"min_range_m ({self.min_range_m}) must be below max_range_m ({self.max_range_m})")
        return self

    @property
    def n_samples(self) -> int:
        """Range samples per spoke (up to ``max_range_m``)."""
        return int(math.ceil((self.max_range_m - self.range_start_m) / self.range_increment_m))

    @property
    def spoke_step(self) -> float:
        """Azimuth step [rad]."""
        return 2.0 * math.pi / self.n_spokes

    @property
    def beam_width(self) -> float:
        return math.radians(self.beam_width_deg)

    @property
    def vertical_beam_width(self) -> float:
        return math.radians(self.vertical_beam_width_deg)

    @property
    def beam_half_spokes(self) -> int:
        """Spokes on each side of a reflector that still see it (half the beam width)."""
        return int(round(0.5 * self.beam_width / self.spoke_step))


def load_radar_config(path: str | Path) -> RadarConfig:
    """Read a radar YAML file; an :class:`InputError` naming the field on bad content."""
    from seatwin.safe_yaml import load_yaml

    p = Path(path)
    if not p.exists():
        raise InputError(p, "no such radar configuration file")
    data = load_yaml(p, "a radar YAML file")
    if data is None:
        data = {}
    if not isinstance(data, dict):
        raise InputError(p, f"expected a mapping of radar parameters, got {type(data).__name__}")
    data = data.get("radar", data)
    return radar_config_from_dict(data, source=p)


def radar_config_from_dict(data: dict[str, Any], source: str | Path = "<memory>") -> RadarConfig:
    try:
        return RadarConfig.model_validate(data)
    except ValidationError as exc:
        err = exc.errors()[0]
        field = ".".join(str(x) for x in err["loc"]) or None
        raise InputError(source, f"{err['msg']} (got {err.get('input')!r})", where=field) from None


def save_radar_config(config: RadarConfig, path: str | Path) -> Path:
    """Write ``config`` as YAML under a top-level ``radar:`` key; returns the path."""
    import yaml

    from seatwin.outputs import write_text_atomic

    p = Path(path)
    write_text_atomic(p, yaml.safe_dump({"radar": config.model_dump(mode="json")}, sort_keys=False))
    return p
