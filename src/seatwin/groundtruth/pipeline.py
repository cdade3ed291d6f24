"""From antenna log files to vessel ground truth and the output files (thesis §3.3.2).

read each file → one common clock over the overlap of all antennas → per vessel NED
(flat earth, eqs. 3.2–3.5), position, heading, ε_gnss, flags → trajectories, Gemini CSV,
quality JSON, figures. Outputs are written to temporary names and renamed only when all
of them are complete, so an error leaves no half-written output.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.geo import GeodeticOrigin
from seatwin.geo.flat_earth import Meridian
from seatwin.groundtruth.detect import read_antenna_log
from seatwin.groundtruth.log import AntennaLog, check_log_motion
from seatwin.groundtruth.resample import DEFAULT_MAX_GAP_S, DEFAULT_RATE_HZ, check_rate, common_clock, resample_log
from seatwin.groundtruth.vessel import (
    DEFAULT_EPS_THRESHOLD_M,
    DEFAULT_MIN_COG_SPEED,
    DEFAULT_SMOOTH_S,
    VesselGroundTruth,
    VesselSpec,
    build_vessel,
)
from seatwin.scenario.defaults import model_of_name
from seatwin.scenario.model import Role, Scenario, Trajectory, Vessel
from seatwin.scenario.plausibility import MAX_SPEED, MAX_TURN_RATE, first_heading_spike, first_teleport

SCENARIO_SUFFIXES = (".yaml", ".yml")
"""An ``out`` ending so is a scenario YAML (name, roles, models, origin, harbour) with its Gemini CSV beside it."""
DEFAULT_HARBOUR = "ravnkloa"
"""The harbour of a scenario YAML written from logs (as of a Gemini CSV read on its own: logs about Ravnkloa)."""


@dataclass
class GroundTruthResult:
    """Every vessel's ground truth on one clock, and the settings that produced it."""

    origin: GeodeticOrigin
    rate_hz: float
    meridian: str
    max_gap_s: float
    time: NDArray[np.float64]
    vessels: list[VesselGroundTruth]

    def trajectories(self) -> list[Trajectory]:
        """One trajectory per vessel, in the order given (vessel numbers 1, 2, …)."""
        return [v.trajectory() for v in self.vessels]

    def scenario(self, name: str = "groundtruth", ownship: str | None = None, harbour: str | None = None) -> Scenario:
        """A :class:`Scenario` of the vessels (all targets, except ``ownship`` if named; a known vessel name gets its
        model and size, :func:`~seatwin.scenario.defaults.model_of_name`) in ``harbour`` (default :data:`DEFAULT_HARBOUR`)."""
        check_scenario_options(None, [v.name for v in self.vessels], name, ownship, harbour)
        harbour = DEFAULT_HARBOUR if harbour is None else harbour
        vessels = []
        for v in self.vessels:
            role = Role.OWNSHIP if v.name == ownship else Role.TARGET
            vessels.append(Vessel(v.name, role, v.trajectory(), *model_of_name(v.name)))
        rig = "milliampere" if ownship is not None else None
        environment = {"harbour": harbour, "water": "flat"}
        return Scenario(name, vessels, origin=self.origin, rig=rig, source=name, environment=environment)


def compute_ground_truth(
    vessels: Sequence[VesselSpec],
    origin: GeodeticOrigin,
    *,
    rate_hz: float = DEFAULT_RATE_HZ,
    meridian: Meridian = "correct",
    eps_threshold_m: float = DEFAULT_EPS_THRESHOLD_M,
    max_gap_s: float = DEFAULT_MAX_GAP_S,
    smooth_s: float = DEFAULT_SMOOTH_S,
    min_cog_speed: float = DEFAULT_MIN_COG_SPEED,
    max_speed: float = MAX_SPEED,
    max_turn_rate: float = MAX_TURN_RATE,
    logs: dict[Path, AntennaLog] | None = None,
) -> GroundTruthResult:
    """Read every vessel's antenna files (or take them from ``logs``) and build the ground truth.

    Bad settings raise :class:`ParameterError` naming the parameter (``vessels``, ``rate_hz``, …).
    The checks a scenario CSV gets when it is read (:mod:`seatwin.scenario.plausibility`) are made
    here, so the CSV written is one seatwin reads back: a fix that moves faster than ``max_speed``
    [m/s] is an :class:`InputError` naming its file and line, and so is a vessel whose heading
    spikes for one sample faster than ``max_turn_rate`` [°/s] (naming the nearest fix of each antenna).
    """
    if not vessels:
        raise ParameterError("vessels", "give at least one vessel")
    names = [s.name for s in vessels]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ParameterError("vessels", f"vessel names must be unique, repeated: {dup}")
    check_rate(rate_hz)
    for param, value in (("eps_threshold_m", eps_threshold_m), ("max_gap_s", max_gap_s)):
        if not np.isfinite(value) or value <= 0:
            raise ParameterError(param, f"must be a positive number, got {value!r}")
    if not np.isfinite(smooth_s) or smooth_s < 0:
        raise ParameterError("smooth_s", f"must be zero or a positive number of seconds, got {smooth_s!r}")
    if not np.isfinite(min_cog_speed) or min_cog_speed < 0:
        raise ParameterError("min_cog_speed", f"must be zero or a positive speed in m/s, got {min_cog_speed!r}")
    for param, value in (("max_speed", max_speed), ("max_turn_rate", max_turn_rate)):
        if not value > 0:
            raise ParameterError(param, f"must be a positive number (inf: no check), got {value!r}")
    if meridian not in ("correct", "printed"):
        raise ParameterError("meridian", f"expected 'correct' or 'printed', got {meridian!r}")
    logs = dict(logs or {})
    for spec in vessels:
        for f in spec.files:
            if f not in logs:
                logs[f] = read_antenna_log(f)
            check_log_motion(logs[f], max_speed)
    all_logs = [logs[f] for spec in vessels for f in spec.files]
    time = common_clock(all_logs, rate_hz)
    truths = []
    for spec in vessels:
        antennas = [resample_log(logs[f], time, max_gap_s) for f in spec.files]
        truth = build_vessel(
            spec,
            antennas,
            origin,
            meridian=meridian,
            eps_threshold_m=eps_threshold_m,
            smooth_s=smooth_s,
            min_cog_speed=min_cog_speed,
        )
        check_vessel_motion(truth, max_speed, max_turn_rate)
        truths.append(truth)
    return GroundTruthResult(origin, float(rate_hz), meridian, float(max_gap_s), time, truths)


def _nearest_fixes(truth: VesselGroundTruth, t: float) -> str:
    """The fix of each antenna nearest time ``t``, as ``FILE line N``."""
    out = []
    for a in truth.antennas:
        log = a.log
        k = int(np.clip(np.searchsorted(log.time, t), 1, len(log) - 1))
        k = k if abs(log.time[k] - t) < abs(log.time[k - 1] - t) else k - 1
        where = f"line {int(log.lines[k])}" if log.lines is not None else f"fix {k + 1}"
        out.append(f"{log.source} {where}")
    return ", ".join(out)


def check_vessel_motion(truth: VesselGroundTruth, max_speed: float = MAX_SPEED, max_turn_rate: float = MAX_TURN_RATE) -> None:
    """An :class:`InputError` if the vessel's ground truth holds a teleport or a heading spike, the
    checks its Gemini CSV would fail when read (:mod:`seatwin.scenario.plausibility`)."""
    jump = first_teleport(truth.time, truth.north, truth.east, max_speed)
    if jump is not None:
        t = float(truth.time[jump.index + 1])
        raise InputError(
            _nearest_fixes(truth, t),
            f"vessel {truth.name!r} moves {jump.step:.4g} m in {jump.dt:.3g} s ({jump.speed:.4g} m/s) at t = {t:.3f}, "
            f"faster than max_speed {max_speed:g} m/s: a teleport",
        )
    spike = first_heading_spike(truth.time, np.degrees(truth.heading), max_turn_rate)
    if spike is not None:
        t = float(truth.time[spike.index])
        raise InputError(
            _nearest_fixes(truth, t),
            f"vessel {truth.name!r} heading ({truth.heading_source}) jumps {spike.jump:.1f}° and back at t = {t:.3f} "
            f"(from {spike.before:.1f}° to {spike.at:.1f}° to {spike.after:.1f}° within {spike.span:.3g} s), faster than "
            f"max_turn_rate {max_turn_rate:g} °/s: a heading spike (a corrupt fix?)",
        )


def check_scenario_options(
    out: str | os.PathLike[str] | None, vessels: Sequence[str], name: str | None, ownship: str | None, harbour: str | None
) -> bool:
    """True when ``out`` is a scenario YAML (None: no file, a scenario in memory); a :class:`ParameterError` for a
    ``name``/``ownship``/``harbour`` that a Gemini CSV ``out`` cannot hold, an empty name, an ``ownship`` that is not
    one of ``vessels``, an unknown ``harbour`` or a harbour raster that is not there."""
    from seatwin.layout.harbours import check_harbour_spec, harbour_name

    as_yaml = out is None or Path(out).suffix.lower() in SCENARIO_SUFFIXES
    if not as_yaml:
        for param, value in (("name", name), ("ownship", ownship), ("harbour", harbour)):
            if value is not None:
                raise ParameterError(param, f"a Gemini CSV ({out}) holds no {param}; write a scenario .yaml to give one")
    if name is not None and not name.strip():
        raise ParameterError("name", "expected a non-empty scenario name")
    if ownship is not None and ownship not in vessels:
        raise ParameterError("ownship", f"no vessel named {ownship!r}; vessels are {', '.join(vessels)}")
    if harbour is not None:
        try:
            check_harbour_spec(harbour)
        except ValueError as e:
            raise ParameterError("harbour", f"{e}, got {harbour!r}") from None
        if harbour_name(harbour) is None and not Path(harbour).is_file():
            raise ParameterError("harbour", f"land raster {harbour!r} not found")
    return as_yaml


def check_outputs(
    vessels: Sequence[VesselSpec],
    out_csv: str | os.PathLike[str],
    quality_json: str | os.PathLike[str] | None = None,
    plots_dir: str | os.PathLike[str] | None = None,
    *,
    overwrite: bool = False,
    name: str | None = None,
    ownship: str | None = None,
    harbour: str | None = None,
) -> None:
    """Refuse, before any work, outputs that would replace an antenna log or each other, or an existing file
    (unless ``overwrite``), or that cannot be written, and scenario options that cannot be honoured
    (:func:`check_scenario_options`)."""
    from seatwin.groundtruth.plots import plot_names
    from seatwin.outputs import check_output_file, check_output_folder

    check_scenario_options(out_csv, [spec.name for spec in vessels], name, ownship, harbour)
    logs = [f for spec in vessels for f in spec.files]
    outs = _scenario_files(out_csv)
    for i, f in enumerate(outs):
        check_output_file(f, "out", inputs=logs, overwrite=overwrite, outputs=outs[:i])
    if quality_json is not None:
        check_output_file(quality_json, "quality_json", inputs=logs, overwrite=overwrite, outputs=outs)
    if plots_dir is not None:
        names = plot_names([spec.name for spec in vessels])
        check_output_folder(plots_dir, "plots_dir", names, inputs=[*logs, *outs, quality_json], overwrite=overwrite)


def _scenario_files(out: str | os.PathLike[str]) -> list[Path]:
    """The files ``out`` stands for: a Gemini CSV, or a scenario YAML and the CSV beside it."""
    p = Path(out)
    return [p, p.with_suffix(".csv")] if p.suffix.lower() in SCENARIO_SUFFIXES else [p]


def write_outputs(
    result: GroundTruthResult,
    out_csv: str | os.PathLike[str],
    quality_json: str | os.PathLike[str] | None = None,
    plots_dir: str | os.PathLike[str] | None = None,
    *,
    name: str | None = None,
    ownship: str | None = None,
    harbour: str | None = None,
) -> list[Path]:
    """Write the scenario, and optionally the quality report and figures; all or nothing (check them first
    with :func:`check_outputs`).

    ``out_csv`` ending in ``.csv`` is a Gemini CSV (no name: a reader names it after the file; its last vessel is
    the ownship); ending in ``.yaml``/``.yml`` it is a scenario YAML with the CSV beside it, named ``name`` (default:
    the file's stem), ``ownship`` (default: the last vessel, as in a Gemini CSV) the ownship, in ``harbour`` (default
    :data:`DEFAULT_HARBOUR`). ``name``/``ownship``/``harbour`` with a CSV are a :class:`ParameterError` (a CSV cannot
    hold them).

    Returns the paths written.
    """
    from seatwin.groundtruth.report import quality_report
    from seatwin.scenario.gemini_csv import write_gemini_csv
    from seatwin.scenario.yaml_format import write_scenario_yaml

    out_csv = Path(out_csv)
    as_yaml = check_scenario_options(out_csv, [v.name for v in result.vessels], name, ownship, harbour)
    pending: list[tuple[Path, Path]] = []  # (temporary, final)
    tmp_dirs: list[Path] = []
    try:
        out_csv.parent.mkdir(parents=True, exist_ok=True)
        if as_yaml:
            own = ownship if ownship is not None else result.vessels[-1].name
            scenario = result.scenario(name if name is not None else out_csv.stem, own, harbour)
            staging_out = Path(tempfile.mkdtemp(prefix=f".{out_csv.name}.", dir=out_csv.parent))
            tmp_dirs.append(staging_out)
            for f in write_scenario_yaml(scenario, staging_out / out_csv.name):
                pending.append((f, out_csv.with_name(f.name)))
        else:
            tmp = out_csv.with_name(f".{out_csv.name}.tmp")
            write_gemini_csv(tmp, result.trajectories(), time=result.time)
            pending.append((tmp, out_csv))
        if quality_json is not None:
            qpath = Path(quality_json)
            qpath.parent.mkdir(parents=True, exist_ok=True)
            qtmp = qpath.with_name(f".{qpath.name}.tmp")
            pending.append((qtmp, qpath))
            qtmp.write_text(json.dumps(quality_report(result), indent=2, allow_nan=False) + "\n")
        if plots_dir is not None:
            from seatwin.groundtruth.plots import write_plots

            pdir = Path(plots_dir)
            if pdir.exists() and not pdir.is_dir():
                raise ParameterError("plots_dir", f"{pdir} exists and is not a folder")
            pdir.parent.mkdir(parents=True, exist_ok=True)
            staging = Path(tempfile.mkdtemp(prefix=f".{pdir.name}.", dir=pdir.parent))
            tmp_dirs.append(staging)
            for f in write_plots(result, staging):
                pending.append((f, pdir / f.name))
            pdir.mkdir(exist_ok=True)
        for tmp_path, final in pending:
            os.replace(tmp_path, final)
    except BaseException:
        (out_csv.with_name(f".{out_csv.name}.tmp.part")).unlink(missing_ok=True)
        for tmp_path, _ in pending:
            tmp_path.unlink(missing_ok=True)
        raise
    finally:
        for d in tmp_dirs:
            shutil.rmtree(d, ignore_errors=True)
    return [final for _, final in pending]
