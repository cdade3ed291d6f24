"""The scenario YAML: metadata and vessels, with the trajectories in a Gemini CSV beside it.

Example::

    name: ferry_crossing
    description: the ferry crosses the channel    # optional
    origin: {lat: 63.4336, lon: 10.3926, height: 0.0}   # optional (default: Ravnkloa)
    seed: 0
    environment: {harbour: default, water: flat}  # harbour: default | ravnkloa | none | a land/water raster path
    rig: milliampere
    trajectory: ferry_crossing.csv                # relative to this file
    date: 2020-09-15                              # only for a CSV with TimeOfDay (UTC date)
    vessels:
      - {name: Havfruen, role: target, column: 1, model: havfruen}
      - {name: milliAmpere, role: ownship, column: 3, model: milliampere,
         dimensions: {length: 5.0, beam: 2.8, height: 2.6}}
      - {name: Mine, role: target, column: 2, model: boat.obj,    # a mesh file, relative to this file
         mesh: {scale: 0.01, yaw_deg: 90, offset: [0, 0, 0.2], z_up: true}}   # optional (defaults: 1, 0, 0s, true)

``column`` is the vessel number n of the CSV's ``V{n}x, V{n}y, V{n}Heading``; every vessel of
the CSV must be listed. Unknown keys are errors (so typos do not pass silently).
"""

from __future__ import annotations

import datetime as dt
import os
from pathlib import Path
from typing import Annotated, Any, Literal

import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError, ValidationInfo, field_validator

from seatwin.errors import InputError
from seatwin.geo import GeodeticOrigin
from seatwin.layout import HARBOUR_NAMES, harbour_name
from seatwin.mesh_placement import MESH_SUFFIXES, MeshPlacement, is_mesh_path
from seatwin.safe_yaml import Lines, line_of, load_yaml
from seatwin.scenario.defaults import RAVNKLOA
from seatwin.scenario.gemini_csv import MAX_SPEED, check_max_speed, read_gemini_csv, write_gemini_csv
from seatwin.scenario.model import Dimensions, Role, Scenario, Vessel

Positive = Annotated[float, Field(gt=0, allow_inf_nan=False)]
Finite = Annotated[float, Field(allow_inf_nan=False)]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class OriginSpec(_Strict):
    lat: float = Field(ge=-90, le=90, allow_inf_nan=False, description="latitude [deg]")
    lon: float = Field(ge=-180, le=360, allow_inf_nan=False, description="longitude [deg]")
    height: float = Field(0.0, allow_inf_nan=False, description="ellipsoidal height [m]")


class EnvironmentSpec(_Strict):
    harbour: str = Field(
        "default", min_length=1, description="'default', 'ravnkloa', 'none' or a land/water raster path (relative to the file)"
    )
    water: Literal["flat"] = "flat"


class DimensionsSpec(_Strict):
    length: Positive
    beam: Positive
    height: Positive


class MeshSpec(_Strict):
    scale: Positive = Field(1.0, description="file units → metres (0.01 for a mesh in centimetres)")
    yaw_deg: float = Field(0.0, allow_inf_nan=False, description="turn clockwise seen from above so the bow is +x")
    offset: tuple[Finite, Finite, Finite] = Field((0.0, 0.0, 0.0), description="forward, starboard, down [m]")
    z_up: bool = Field(True, description="the file's axes: x forward, y left, z up (else x forward, y starboard, z down)")


class VesselSpec(_Strict):
    name: str = Field(min_length=1)
    role: Role
    column: int = Field(ge=1, description="n of the CSV columns V{n}x, V{n}y, V{n}Heading")
    model: str = Field("generic", min_length=1, description="3-D model name or mesh path (relative to this file)")
    dimensions: DimensionsSpec | None = None
    mesh: MeshSpec | None = None

    @field_validator("mesh")
    @classmethod
    def _mesh_needs_a_file(cls, mesh: MeshSpec | None, info: ValidationInfo) -> MeshSpec | None:
        model = info.data.get("model")
        if mesh is not None and isinstance(model, str) and not is_mesh_path(model):
            files = ", ".join(MESH_SUFFIXES)
            raise ValueError(f"mesh (scale, yaw_deg, offset, z_up) needs a mesh file model ({files}), got {model!r}")
        return mesh


class ScenarioSpec(_Strict):
    name: str = Field(min_length=1)
    description: str = ""
    origin: OriginSpec | None = None
    seed: int = Field(0, ge=0)
    environment: EnvironmentSpec = EnvironmentSpec()
    rig: str | None = "milliampere"
    trajectory: str = Field(min_length=1, description="Gemini CSV, relative to the YAML file")
    date: dt.date | None = None
    vessels: list[VesselSpec] = Field(min_length=1)

    @field_validator("vessels")
    @classmethod
    def _unique(cls, vessels: list[VesselSpec]) -> list[VesselSpec]:
        for key in ("name", "column"):
            values = [getattr(v, key) for v in vessels]
            dup = sorted({x for x in values if values.count(x) > 1}, key=str)
            if dup:
                raise ValueError(f"vessel {key}s must be unique, repeated: {dup}")
        owners = [v.name for v in vessels if v.role == Role.OWNSHIP]
        if len(owners) > 1:
            raise ValueError(f"at most one ownship, got {owners}")
        return vessels


def _field(loc: tuple[Any, ...]) -> str:
    out = ""
    for part in loc:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out or "(top level)"


def parse_spec(path: Path) -> ScenarioSpec:
    """Read and validate a scenario YAML; :class:`InputError` names the file, line or field."""
    lines: Lines = {}
    data = load_yaml(path, "a scenario YAML file", lines)
    if not isinstance(data, dict):
        raise InputError(path, f"expected a mapping of scenario fields at the top level, got {type(data).__name__}")
    try:
        return ScenarioSpec.model_validate(data)
    except ValidationError as exc:
        errors = exc.errors()
        first = errors[0]
        more = "".join(f"; {_field(e['loc'])}: {e['msg']}" for e in errors[1:])
        line = line_of(lines, tuple(first["loc"]))
        where = f"field {_field(first['loc'])}" if line is None else f"line {line}, field {_field(first['loc'])}"
        raise InputError(path, f"{first['msg']}{more}", where=where) from None


def read_scenario_yaml(path: str | os.PathLike[str], date: dt.date | None = None, max_speed: float = MAX_SPEED) -> Scenario:
    """A scenario from its YAML and the Gemini CSV it names; ``date`` overrides the YAML's ``date``;
    ``max_speed`` [m/s] bounds a vessel's speed between two CSV rows (:func:`read_gemini_csv`)."""
    check_max_speed(max_speed)
    path = Path(path)
    spec = parse_spec(path)
    csv_path = (path.parent / spec.trajectory).resolve()
    if not csv_path.is_file():
        raise InputError(path, f"trajectory file {str(csv_path)!r} does not exist", where="field trajectory")
    harbour = harbour_name(spec.environment.harbour) or spec.environment.harbour
    if harbour not in HARBOUR_NAMES:
        raster = (path.parent / harbour).resolve()
        if not raster.exists():
            raise InputError(
                path,
                f"harbour raster {str(raster)!r} does not exist (or use a name: {', '.join(HARBOUR_NAMES)})",
                where="field environment.harbour",
            )
        harbour = str(raster)
    use_date = date or spec.date
    try:
        trajectories = read_gemini_csv(csv_path, date=use_date, max_speed=max_speed)
    except InputError as exc:
        if use_date is None and "TimeOfDay" in exc.detail:
            raise InputError(path, f"{csv_path.name} has TimeOfDay times: give its UTC date", where="field date") from None
        raise
    listed = {v.column for v in spec.vessels}
    for i, v in enumerate(spec.vessels):
        if v.column not in trajectories:
            raise InputError(
                path,
                f"column {v.column} is not in {csv_path.name} (it has vessels {sorted(trajectories)})",
                where=f"field vessels[{i}].column",
            )
    unlisted = sorted(set(trajectories) - listed)
    if unlisted:
        raise InputError(path, f"{csv_path.name} has vessel(s) {unlisted} not listed under vessels", where="field vessels")
    vessels = [
        Vessel(
            name=v.name,
            role=v.role,
            trajectory=trajectories[v.column],
            model=_mesh_file(path, v.model, i) if is_mesh_path(v.model) else v.model,
            dimensions=None if v.dimensions is None else Dimensions(**v.dimensions.model_dump()),
            mesh=None if v.mesh is None else MeshPlacement(v.mesh.scale, v.mesh.yaw_deg, tuple(v.mesh.offset), v.mesh.z_up),
        )
        for i, v in enumerate(spec.vessels)
    ]
    origin = RAVNKLOA if spec.origin is None else GeodeticOrigin(spec.origin.lat, spec.origin.lon, spec.origin.height)
    return Scenario(
        name=spec.name,
        vessels=vessels,
        origin=origin,
        seed=spec.seed,
        environment={"harbour": harbour, "water": spec.environment.water},
        rig=spec.rig,
        source=str(path),
        description=spec.description,
    )


def _mesh_file(path: Path, model: str, index: int) -> str:
    """A vessel's mesh file, relative to the scenario file ``path``; one relative to the current folder is used only
    when none is beside the scenario (an older scenario's way); neither is an :class:`InputError` naming both."""
    p = Path(model).expanduser()
    candidates = [p] if p.is_absolute() else [(path.parent / p).resolve(), p.resolve()]
    for c in candidates:
        if c.is_file():
            return str(c)
    looked = " or ".join(dict.fromkeys(str(c) for c in candidates))
    raise InputError(path, f"mesh file {model!r} not found (looked for {looked})", where=f"field vessels[{index}].model")


def _relative(target: str, folder: Path) -> str:
    """``target`` relative to ``folder`` (absolute on another drive)."""
    try:
        return os.path.relpath(Path(target).resolve(), folder.resolve())
    except ValueError:  # another drive on Windows
        return str(Path(target).resolve())


def csv_order(scenario: Scenario) -> list[Vessel]:
    """Vessels in CSV column order: targets (and others) as listed, the ownship last (Gemini: V3)."""
    return [v for v in scenario.vessels if v.role != Role.OWNSHIP] + [v for v in scenario.vessels if v.role == Role.OWNSHIP]


def write_scenario_yaml(
    scenario: Scenario,
    path: str | os.PathLike[str],
    time_format: Literal["posix", "time_of_day"] = "posix",
) -> tuple[Path, Path]:
    """Write ``scenario`` as ``path`` (YAML) and its CSV beside it (same stem); return both paths.

    Every vessel is sampled at the first CSV vessel's sample times within the scenario's common
    span (vessels sampled at other times are interpolated).
    """
    path = Path(path)
    if path.suffix.lower() not in (".yaml", ".yml"):
        raise InputError(path, "a scenario file name must end in .yaml or .yml")
    csv_path = path.with_suffix(".csv")
    ordered = csv_order(scenario)
    ref = ordered[0].trajectory.time
    time = ref[(ref >= scenario.start - 1e-9) & (ref <= scenario.end + 1e-9)]
    if len(time) < 2:
        raise InputError(scenario.source, f"the vessels share less than two sample times ({scenario.start}…{scenario.end})")
    date = write_gemini_csv(csv_path, [v.trajectory for v in ordered], time=time, time_format=time_format)
    harbour = str(scenario.environment.get("harbour", "default"))
    harbour = harbour_name(harbour) or harbour
    if harbour not in HARBOUR_NAMES:
        harbour = _relative(harbour, path.parent)
    data: dict[str, Any] = {"name": scenario.name}
    if scenario.description:
        data["description"] = scenario.description
    if scenario.origin is not None:
        o = scenario.origin
        data["origin"] = {"lat": float(o.lat_deg), "lon": float(o.lon_deg), "height": float(o.height_m)}
    data["seed"] = int(scenario.seed)
    data["environment"] = {"harbour": harbour, "water": str(scenario.environment.get("water", "flat"))}
    data["rig"] = scenario.rig
    data["trajectory"] = csv_path.name
    if date is not None:
        data["date"] = date
    data["vessels"] = []
    for n, v in enumerate(ordered, start=1):
        model = _relative(v.model, path.parent) if is_mesh_path(v.model) else v.model
        entry: dict[str, Any] = {"name": v.name, "role": v.role.value, "column": n, "model": model}
        if v.dimensions is not None:
            d = v.dimensions
            entry["dimensions"] = {"length": float(d.length), "beam": float(d.beam), "height": float(d.height)}
        if v.mesh is not None:
            m = v.mesh
            entry["mesh"] = {"scale": float(m.scale), "yaw_deg": float(m.yaw_deg), "offset": [float(x) for x in m.offset]}
            entry["mesh"]["z_up"] = bool(m.z_up)
        data["vessels"].append(entry)
    tmp = path.with_name(path.name + ".part")
    try:
        tmp.write_text(yaml.safe_dump(data, sort_keys=False, allow_unicode=True), encoding="utf-8")
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path, csv_path
