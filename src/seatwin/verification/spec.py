"""The verification campaign's YAML (``seatwin verify AGENT.yaml``): which agents, over which encounters, with which
sensor models; see ``docs/examples/verify.yaml``."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import Discriminator, Field, Tag, model_validator

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


class GrpcAgent(Settings):
    """An agent in another process, driven over gRPC (:class:`seatwin.api.agent_link.RemoteAgent`): seatwin listens
    and the agent connects — either launched per run from ``command`` (``{address}`` replaced by the address seatwin
    listens on; run in the spec file's folder), or already running and connecting to ``address`` (then one run at a
    time: a single worker)."""

    kind: Literal["grpc"]
    name: str = Field(..., min_length=1, pattern=r"^[A-Za-z0-9_.-]+$", description="The agent's name in the results.")
    command: tuple[str, ...] | None = Field(None, min_length=1, description="The agent's command line, launched per run.")
    address: str | None = Field(None, description="HOST:PORT seatwin listens on for an agent started separately.")
    sensors: tuple[Literal["truth", "lidar", "radar"], ...] = Field(
        ("truth",), min_length=1, description="The frames it is sent."
    )
    timeout_s: float = Field(30.0, gt=0, description="How long a step waits for its command before the run fails.")
    startup_timeout_s: float = Field(60.0, gt=0, description="How long a run's first step waits (the agent's start-up).")

    @model_validator(mode="after")
    def _one_way(self) -> GrpcAgent:
        if (self.command is None) == (self.address is None):
            raise ValueError("give exactly one of command (to launch the agent) and address (an agent started separately)")
        return self


AgentName = Literal["reference", "perfect", "late"]


def _entry_kind(v: Any) -> str:
    return "variant" if isinstance(v, str) else "grpc"


AgentEntry = Annotated[Annotated[AgentName, Tag("variant")] | Annotated[GrpcAgent, Tag("grpc")], Discriminator(_entry_kind)]
"""An ``agents`` entry: a variant's name, or a mapping of a gRPC agent (errors are the chosen kind's)."""


def agent_name(agent: AgentName | GrpcAgent) -> str:
    """A spec entry's name in the results (a variant's own, a gRPC agent's ``name``)."""
    return agent if isinstance(agent, str) else agent.name


class VerifySpec(Settings):
    """A verification campaign: ``agents`` × ``families`` × ``encounters`` sampled points."""

    agents: tuple[AgentEntry, ...] = Field(
        ("perfect", "reference"),
        min_length=1,
        description="Agent variants (seatwin.agents.VARIANTS) or gRPC agents ({kind: grpc, name, command | address}).",
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

    @model_validator(mode="after")
    def _unique_names(self) -> VerifySpec:
        names = [agent_name(a) for a in self.agents]
        if len(set(names)) != len(names):
            raise ValueError(f"agent names must be unique, got {names}")
        return self

    @property
    def agent_names(self) -> tuple[str, ...]:
        return tuple(agent_name(a) for a in self.agents)


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
