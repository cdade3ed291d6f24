"""OSP co-simulation (thesis ch. 2, Fig. 4.17): the ScenarioPlayer and GeminiBridge FMUs, the OSP system
structure, and running it with ``libcosimpy`` against ``seatwin serve``.

:func:`export_system` writes ``ScenarioPlayer.fmu`` (a scenario played step by step: every vessel's
north, east, heading), ``GeminiBridge.fmu`` (those poses sent to a ``Simulation`` server with
``DoStep``), ``OspSystemStructure.xml`` connecting them (``<Algorithm>fixedStep</Algorithm>``) and
``seatwin-cosim.json`` (vessel order, ownship, duration, harbour, sensors: what ``seatwin cosim run`` needs to
serve; the harbour and sensors are ``seatwin simulate``'s: the scenario's own harbour — a Gemini CSV's is
``ravnkloa`` — and :data:`~seatwin.defaults.DEFAULT_SENSORS`, unless given).
:func:`run_system` starts the ``Simulation`` server in-process, points the bridge at it, and runs the
system with libcosim's fixed-step algorithm until the scenario's end (libcosim times are integer ns).
"""

from __future__ import annotations

import csv
import json
import shutil
import tempfile
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import numpy as np

from seatwin.defaults import DEFAULT_IMAGE_FORMAT, DEFAULT_SENSORS
from seatwin.errors import InputError, ParameterError
from seatwin.scenario import Scenario
from seatwin.settings import validated
from seatwin.sim.settings import SimulationSettings

FMU_SOURCES = Path(__file__).parent / "fmus"
SYSTEM_FILE = "OspSystemStructure.xml"
META_FILE = "seatwin-cosim.json"
EXPORT_FILES = ("ScenarioPlayer.fmu", "GeminiBridge.fmu", SYSTEM_FILE, META_FILE)
"""What :func:`export_system` writes into its folder."""
PLAYER, BRIDGE = "player", "bridge"
NS_PER_S = 1_000_000_000


def scenario_samples(scenario: Scenario, rate_hz: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Seconds since the start at ``rate_hz`` (default: the fastest trajectory's rate, at least 10 Hz) over the
    scenario, and (samples, vessels × 3) north, east [m], heading [deg in [0, 360)]."""
    rate = float(rate_hz or max(10.0, *(v.trajectory.rate_hz for v in scenario.vessels)))
    n = int(np.floor(scenario.duration * rate + 1e-6))
    rel = np.arange(n + 1) / rate
    cols = []
    for v in scenario.vessels:
        s = v.trajectory.state_at(scenario.start + rel)
        cols += [s.north, s.east, np.rad2deg(s.heading) % 360.0]
    return rel, np.column_stack(cols)


def _build(script: str, files: dict[str, str], dest: Path) -> Path:
    from pythonfmu.builder import FmuBuilder

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        shutil.copy(FMU_SOURCES / script, tmp / script)
        for name, text in files.items():
            (tmp / name).write_text(text, encoding="utf-8")
        return Path(FmuBuilder.build_FMU(tmp / script, dest=dest, project_files=[tmp / n for n in files]))


def system_structure(vessels: list[str], step_size: float) -> str:
    """The OSP system structure: player → bridge, every vessel's north/east/heading and the start time."""
    conns = ["start_time"] + [f"{v}.{q}" for v in vessels for q in ("north", "east", "heading")]
    lines = [
        '<?xml version="1.0" encoding="utf-8"?>',
        '<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure" version="0.1">',
        "  <StartTime>0.0</StartTime>",
        f"  <BaseStepSize>{step_size!r}</BaseStepSize>",
        "  <Algorithm>fixedStep</Algorithm>",
        "  <Simulators>",
        f'    <Simulator name="{PLAYER}" source="ScenarioPlayer.fmu" stepSize="{step_size!r}"/>',
        f'    <Simulator name="{BRIDGE}" source="GeminiBridge.fmu" stepSize="{step_size!r}"/>',
        "  </Simulators>",
        "  <Connections>",
    ]
    for c in conns:
        lines += [
            "    <VariableConnection>",
            f"      <Variable simulator={quoteattr(PLAYER)} name={quoteattr(c)}/>",
            f"      <Variable simulator={quoteattr(BRIDGE)} name={quoteattr(c)}/>",
            "    </VariableConnection>",
        ]
    lines += ["  </Connections>", "</OspSystemStructure>", ""]
    return "\n".join(lines)


def export_system(
    scenario: Scenario,
    out_dir: str | Path,
    *,
    step_size: float = 0.1,
    address: str = "127.0.0.1:50051",
    harbour: str | None = None,
    sensors: tuple[str, ...] = DEFAULT_SENSORS,
) -> dict[str, Path]:
    """Write the two FMUs, ``OspSystemStructure.xml`` and ``seatwin-cosim.json`` for ``scenario`` into ``out_dir``.

    ``harbour`` (default: the scenario's own, as ``seatwin simulate``) and ``sensors`` are what ``cosim run``
    serves with unless it is told otherwise."""
    from seatwin.sim.run import run_harbour

    if not 0 < step_size <= scenario.duration:
        raise ParameterError("step_size", f"expected a step in (0, {scenario.duration:g}] s, got {step_size!r}")
    settings = validated(SimulationSettings, {"harbour": harbour})
    if sensors:  # () is ground truth only, as `serve`'s
        settings = validated(SimulationSettings, {"harbour": harbour, "sensors": tuple(sensors)})
    run_harbour_name = run_harbour(scenario, settings)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    names = [v.name for v in scenario.vessels]
    rel, table = scenario_samples(scenario)
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "samples.csv"
        with p.open("w", newline="", encoding="utf-8") as f:
            w = csv.writer(f)
            w.writerow(["time"] + [f"{n}.{q}" for n in names for q in ("north", "east", "heading")])
            for t, row in zip(rel.tolist(), table.tolist()):
                w.writerow([repr(t)] + [repr(x) for x in row])
        samples = p.read_text(encoding="utf-8")
    scenario_json = json.dumps({"vessels": names, "start": scenario.start, "duration": scenario.duration})
    player = _build("ScenarioPlayer.py", {"scenario.json": scenario_json, "samples.csv": samples}, out)
    bridge = _build("GeminiBridge.py", {"bridge.json": json.dumps({"vessels": names, "address": address})}, out)
    system = out / SYSTEM_FILE
    system.write_text(system_structure(names, step_size), encoding="utf-8")
    meta = out / META_FILE
    own = scenario.ownship
    meta.write_text(
        json.dumps(
            {
                "scenario": scenario.name,
                "vessels": names,
                "ownship": own.name if own is not None else None,
                "seed": scenario.seed,
                "start": scenario.start,
                "duration": scenario.duration,
                "step_size": step_size,
                "harbour": run_harbour_name,
                "sensors": list(sensors),
            },
            indent=2,
        ),
        encoding="utf-8",
    )
    return {"player": player, "bridge": bridge, "system": system, "meta": meta}


def _variable_reference(execution: Any, index: int, name: str) -> int:
    for v in execution.slave_variables(index):
        if v.name.decode() == name:
            return int(v.reference)
    raise InputError(BRIDGE, f"the bridge FMU has no variable {name!r}")


def run_system(
    system: str | Path,
    out: str | Path,
    *,
    duration: float | None = None,
    seed: int | None = None,
    sensors: tuple[str, ...] | None = None,
    harbour: str | None = None,
    lidar_mode: str = "raycast",
    fmt: str = "mcap",
    compression: str | None = None,
    image_format: str = DEFAULT_IMAGE_FORMAT,
) -> Any:
    """Run an exported system (:func:`export_system`) with libcosim against an in-process ``seatwin serve``
    recording into ``out``; return the server's :class:`~seatwin.sim.loop.SimulationResult`.

    ``sensors`` (``()``: ground truth only) and ``harbour`` default to those the export wrote into
    ``seatwin-cosim.json`` (a file without them: :data:`~seatwin.defaults.DEFAULT_SENSORS` and ``default``).

    ``duration`` (default: the scenario's) is rounded down to whole steps ``h``; libcosim runs one step
    past it, so the bridge sends the poses at 0, h, …, duration and the recording holds the frames
    ``seatwin simulate --duration`` would (those in [0, duration)).
    """
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level

    from seatwin.api.server import serve

    system = Path(system)
    if not system.is_file():
        raise InputError(system, "no such OSP system structure file")
    meta_path = system.parent / META_FILE
    if not meta_path.is_file():
        raise InputError(meta_path, f"missing: `seatwin cosim export` writes it beside {SYSTEM_FILE}")
    meta = json.loads(meta_path.read_text(encoding="utf-8"))
    step = float(meta["step_size"])
    total = float(meta["duration"]) if duration is None else float(duration)
    if not 0 < total <= float(meta["duration"]) + 1e-9:
        raise ParameterError("duration", f"expected (0, {meta['duration']:g}] s, got {duration!r}")
    n_steps = int(np.floor(total / step + 1e-9))
    if n_steps < 1:
        raise ParameterError("duration", f"{total:g} s is shorter than a step of {step:g} s")
    log_output_level(CosimLogLevel.WARNING)
    handle = serve(
        out,
        port=0,
        vessels=tuple(meta["vessels"]),
        ownship=meta.get("ownship"),
        seed=int(meta.get("seed", 0) if seed is None else seed),
        sensors=tuple(meta.get("sensors", DEFAULT_SENSORS) if sensors is None else sensors),
        harbour=str(meta.get("harbour", "default") if harbour is None else harbour),
        lidar_mode=lidar_mode,
        fmt=fmt,
        compression=compression,
        image_format=image_format,
    )
    ok = False
    try:
        execution = CosimExecution.from_osp_config_file(str(system.resolve()))
        bridge = execution.slave_index_from_instance_name(BRIDGE)
        execution.string_initial_value(bridge, _variable_reference(execution, bridge, "address"), handle.address)
        # one step past the duration: the bridge sends the poses at 0, h, …, duration (n_steps + 1 DoSteps)
        ok = execution.simulate_until((n_steps + 1) * round(step * NS_PER_S))
        if not ok:
            from libcosimpy._internal import get_last_error_message

            raise InputError(system, f"libcosim stopped: {get_last_error_message()}")
    finally:
        result = handle.stop(completed=ok)
    if handle.servicer.steps != n_steps + 1:
        raise InputError(system, f"the bridge sent {handle.servicer.steps} steps, expected {n_steps + 1}")
    return result
