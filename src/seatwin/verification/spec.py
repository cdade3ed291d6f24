"""The verification campaign's YAML (``seatwin verify AGENT.yaml``): which agents, over which encounters, with which
sensor models; see ``docs/examples/verify.yaml``."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Literal

from pydantic import Field

from seatwin.encounters.space import SPACES
from seatwin.errors import InputError
from seatwin.safe_yaml import Lines, line_of, load_yaml
from seatwin.settings import Settings, validated


class SensorModel(Settings):
    """The ownship's sensor models for the modelled-perception agents (fields of
    :class:`seatwin.sim.settings.SimulationSettings`; null = that model's default)."""

    ray_drop: float | None = Field(None, ge=0.0, lt=1.0, description="Lidar ray-drop probability.")
    range_noise: float | None = Field(None, ge=0.0, description="Lidar range noise σ [m].")
    radar_config: str | None = Field(None, description="Radar YAML (a fitted model); relative to the spec file.")
    lidar_preset: Literal["vlp16", "vlp16-thesis"] = "vlp16"


class VerifySpec(Settings):
    """A verification campaign: ``agents`` × ``families`` × ``encounters`` sampled points."""

    agents: tuple[Literal["reference", "perfect", "late"], ...] = Field(
        ("perfect", "reference"), min_length=1, description="Agent variants (seatwin.agents.VARIANTS)."
    )
    sensors: tuple[Literal["lidar", "radar"], ...] = Field(("lidar", "radar"), min_length=1, description="Modelled sensors.")
    families: tuple[str, ...] = Field(("head_on", "crossing_give_way"), min_length=1, description=f"Of {', '.join(SPACES)}.")
    encounters: int = Field(20, ge=1, description="Encounters sampled per family.")
    sampler: Literal["lhs", "random"] = "lhs"
    seed: int = Field(0, ge=0, description="Sampling seed; encounter i is placed and simulated with seed + i.")
    harbour: str = Field("none", description="'none' (open water), 'default', 'ravnkloa' or a raster path.")
    tcpa: tuple[float, float] | None = Field(None, description="[low, high] TCPA range [s] replacing the families'.")
    run_out: float = Field(30.0, gt=0, description="Seconds the ownship sails past the last closest approach to its goal.")
    safety_distance: float = Field(10.0, gt=0, description="The safety domain's radius [m] (centre to centre).")
    sensor_model: SensorModel = SensorModel()
    worst: int = Field(3, ge=0, description="Failed runs of modelled perception saved as scenarios with the sailed path.")


def load_verify_spec(path: str | os.PathLike[str]) -> VerifySpec:
    """Read and validate a verification YAML; an :class:`InputError` names the file, line or field."""
    path = Path(path)
    lines: Lines = {}
    data = load_yaml(path, "a verification YAML file", lines)
    if not isinstance(data, dict):
        raise InputError(path, f"expected a mapping of verification fields at the top level, got {type(data).__name__}")
    unknown = [f for f in data.get("families", []) or [] if f not in SPACES] if isinstance(data.get("families"), list) else []
    if unknown:
        raise InputError(path, f"unknown encounter families {unknown}; expected some of {', '.join(SPACES)}", where="families")
    model = data.get("sensor_model")
    if isinstance(model, dict) and isinstance(model.get("radar_config"), str):
        p = Path(model["radar_config"])
        model["radar_config"] = str((path.resolve().parent / p).resolve()) if not p.is_absolute() else str(p)
    if isinstance(data.get("harbour"), str) and Path(data["harbour"]).suffix.lower() in (".yaml", ".yml", ".bin"):
        data["harbour"] = str((path.resolve().parent / data["harbour"]).resolve())
    try:
        return validated(VerifySpec, data, source=path)
    except InputError as exc:
        line = None if exc.where is None else line_of(lines, (exc.where,))
        if line is None:
            raise
        raise InputError(path, exc.detail, where=f"line {line}, field {exc.where}") from None
