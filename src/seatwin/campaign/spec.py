"""What a campaign varies, as its YAML file says: scenarios × seeds × synthetic settings × tunings, against a reference.

Example (docs/examples/campaign.yaml)::

    scenarios: [ferry_crossing, stop_and_evade]
    seeds: [1, 2, 3]
    duration: 20
    synthetic: {lidar_mode: [depthbuffer, raycast]}
    reference: {lidar_mode: raycast}
    tunings: [synthetic]

``synthetic`` and ``reference`` name fields of :class:`seatwin.sim.SimulationSettings` (``lidar_mode``,
``ray_drop``, ``range_noise``, ``dissipation``, ``sensors``, ``harbour``…); ``synthetic`` lists values
per field and the campaign runs every combination, ``reference`` gives one value per field (unnamed
fields keep their defaults, but ``sensors`` is ``lidar`` unless named: the tracker reads no images). The
reference run of seed ``s`` uses seed ``s + reference_seed_offset``:
a real dataset never shares the synthetic one's random draws, so neither may the reference that
stands in for it (sharing them would hide the seed-to-seed difference every real comparison has).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from pydantic import Field, field_validator

from seatwin.errors import InputError, ParameterError
from seatwin.evaluation.compare import CompareOptions
from seatwin.safe_yaml import Lines, line_of, load_yaml
from seatwin.settings import Seeds, Settings, validated
from seatwin.sim.settings import SimulationSettings

NOT_VARIED = ("seed", "fmt", "radar_spokes")
"""SimulationSettings fields a campaign does not vary: the seed is the campaign's own, the others do not change results."""
PATH_SETTINGS = ("radar_config", "lidar_config", "harbour")
"""SimulationSettings fields that may name a file (relative to the campaign file)."""
DEFAULT_REFERENCE_SEED_OFFSET = 1000


def setting_value(name: str, value: Any) -> Any:
    """``value`` of SimulationSettings field ``name``, validated and in its JSON form (a ``ParameterError`` naming it)."""
    if name not in SimulationSettings.model_fields or name in NOT_VARIED:
        known = [f for f in SimulationSettings.model_fields if f not in NOT_VARIED]
        raise ParameterError(name, f"not a simulation setting a campaign can vary; expected one of {', '.join(known)}")
    return SimulationSettings(**{name: value}).model_dump(mode="json")[name]


class CampaignSpec(Settings):
    """Every choice of a campaign (see the module docstring)."""

    scenarios: tuple[str, ...] = Field(..., min_length=1, description="Built-in scenario names or scenario files.")
    seeds: Seeds = Field(..., min_length=1, description="Seeds of the synthetic runs; each grid point runs with each.")
    duration: float = Field(..., gt=0, description="Simulated seconds per run.")
    offset: float | None = Field(
        None, ge=0, description="Window start in seconds after each scenario's start (default: the window centred in it)."
    )
    synthetic: dict[str, tuple[Any, ...]] = Field(
        default_factory=dict,
        description="Simulation settings to vary, each with its list of values; every combination is a grid point.",
    )
    reference: dict[str, Any] = Field(
        default_factory=dict, description="Simulation settings of the reference run (the stand-in for real data)."
    )
    tunings: tuple[str, ...] = Field(
        ("synthetic",), min_length=1, description="Tracker tunings (presets or files); each run is tracked with each."
    )
    reference_seed_offset: int = Field(
        DEFAULT_REFERENCE_SEED_OFFSET,
        description="The reference run of seed s uses seed s + this: never the synthetic run's own draws.",
    )
    comparison: CompareOptions = Field(default_factory=CompareOptions, description="Conventions of each comparison.")

    @field_validator("scenarios", "tunings")
    @classmethod
    def _distinct_names(cls, v: tuple[str, ...]) -> tuple[str, ...]:
        if len(set(v)) != len(v):
            raise ValueError("expected distinct entries")
        return v

    @field_validator("tunings")
    @classmethod
    def _known_tunings(cls, v: tuple[str, ...]) -> tuple[str, ...]:
        from seatwin.tracking import load_tuning

        for name in v:
            try:
                load_tuning(name)
            except InputError as exc:
                raise ValueError(str(exc)) from None
        return v

    @field_validator("synthetic", mode="before")
    @classmethod
    def _synthetic_lists(cls, v: Any) -> Any:
        if isinstance(v, dict):
            for name, values in v.items():
                if not isinstance(values, list | tuple) or not values:
                    raise ValueError(f"{name}: expected a list of values, got {values!r}")
        return v

    @field_validator("synthetic")
    @classmethod
    def _synthetic_values(cls, v: dict[str, tuple[Any, ...]]) -> dict[str, tuple[Any, ...]]:
        out = {}
        for name, values in v.items():
            checked = tuple(setting_value(name, x) for x in values)
            if len({repr(x) for x in checked}) != len(checked):
                raise ParameterError(name, f"expected distinct values, got {list(values)}")
            out[name] = checked
        return out

    @field_validator("reference")
    @classmethod
    def _reference_values(cls, v: dict[str, Any]) -> dict[str, Any]:
        return {name: setting_value(name, x) for name, x in v.items()}

    @property
    def varied(self) -> tuple[str, ...]:
        """The synthetic settings' names, in the file's order (a column each in results.csv)."""
        return tuple(self.synthetic)

    def n_points(self) -> int:
        """Synthetic settings combinations."""
        n = 1
        for values in self.synthetic.values():
            n *= len(values)
        return n

    def describe(self) -> dict[str, Any]:
        """The spec as campaign.json records it."""
        return self.model_dump(mode="json")


def _resolve(value: Any, base: Path) -> Any:
    """A relative path that exists next to the campaign file, made absolute; anything else as it is."""
    if isinstance(value, str) and value and not os.path.isabs(value) and (base / value).exists():
        return str((base / value).resolve())
    return value


def load_campaign(path: str | os.PathLike[str]) -> CampaignSpec:
    """Read and validate a campaign YAML; an :class:`InputError` names the file, line or field.

    Scenario files, tuning files and the file-valued settings (``radar_config``, ``lidar_config``, ``harbour``) are
    relative to the campaign file and are made absolute here, so every job names the same file.
    """
    path = Path(path)
    lines: Lines = {}
    data = load_yaml(path, "a campaign YAML file", lines)
    if not isinstance(data, dict):
        raise InputError(path, f"expected a mapping of campaign fields at the top level, got {type(data).__name__}")
    base = path.resolve().parent
    for key in ("scenarios", "tunings"):
        if isinstance(data.get(key), list):
            data[key] = [_resolve(x, base) for x in data[key]]
    for key in ("synthetic", "reference"):
        section = data.get(key)
        if isinstance(section, dict):
            for name in PATH_SETTINGS:
                if isinstance(section.get(name), list):
                    section[name] = [_resolve(x, base) for x in section[name]]
                elif name in section:
                    section[name] = _resolve(section[name], base)
    try:
        return validated(CampaignSpec, data, source=path)
    except InputError as exc:
        line = None if exc.where is None else line_of(lines, (exc.where,))
        if line is None:
            raise
        raise InputError(path, exc.detail, where=f"line {line}, field {exc.where}") from None
