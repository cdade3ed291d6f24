"""``seatwin.pipeline`` holds every verb's call, with the CLI's defaults (issue 25, item 14).

A new verb fails :func:`test_every_verb_has_its_calls_in_pipeline` until its calls are listed here
(and exported); a verb whose CLI default differs from its library call's default fails the default tests.
"""

from __future__ import annotations

import inspect
import json
from pathlib import Path
from typing import Any

import pytest
import typer

import seatwin.pipeline as pipeline
from seatwin.cli.main import app, run

# verb → the seatwin.pipeline names its command calls
VERB_CALLS: dict[str, tuple[str, ...]] = {
    "simulate": ("simulate_run", "simulated_scenario", "vessels_on_water", "plot_simulation"),
    "track": ("track_recording", "tracking_summary", "plot_tracking"),
    "evaluate": ("evaluate_run",),
    "compare": ("compare_runs",),
    "demo": ("run_demo",),
    "groundtruth": ("compute_ground_truth", "write_ground_truth"),
    "import joyride": ("import_joyride",),
    "import ravnkloa-radar": ("import_ravnkloa_radar",),
    "scenario list": (),  # the built-ins' table: seatwin.scenario.builtin.BUILTINS
    "scenario info": ("load_scenario", "scenario_summary"),
    "scenario plot": ("load_scenario", "plot_scenario"),
    "scenario export": ("load_scenario", "save_scenario"),
    "bag info": ("bag_info",),
    "errors": ("depth_error_table", "write_error_plots"),
    "lidar snapshot": ("lidar_snapshot",),
    "camera snapshot": ("camera_snapshot",),
    "labels export": ("export_coco",),
    "radar fit": ("fit_radar_to_recording", "save_radar_config"),
    "lidar fit": ("fit_lidar_to_recording", "save_lidar_config"),
    "radar simulate": ("simulate_radar",),
    "sweep": ("run_sweep", "write_sweep"),
    "campaign": ("run_campaign",),
    "fidelity joyride": ("run_fidelity", "write_fidelity"),
    "serve": ("serve",),
    "record-stream": ("record_stream",),
    "cosim run": ("export_system", "run_system"),
    "cosim export": ("export_system",),
    "bag repair": ("repair_bag",),
    "bag convert": ("convert_bag",),
    "view": ("RecordingViewer",),
    "harbour fit-alignment": ("fit_harbour_alignment", "write_alignment"),
    "harbour rasterize": ("land_raster_from_geojson", "write_land_raster"),
    "verify": ("run_verification",),
}


def _verbs(command: Any, path: tuple[str, ...] = ()) -> dict[str, Any]:
    subs = getattr(command, "commands", None)
    if subs is None:
        return {" ".join(path): command}
    out: dict[str, Any] = {}
    for name, sub in subs.items():
        if not sub.hidden:
            out.update(_verbs(sub, (*path, name)))
    return out


VERBS = _verbs(typer.main.get_command(app))


def test_every_verb_has_its_calls_in_pipeline() -> None:
    assert set(VERBS) == set(VERB_CALLS)
    for verb, names in VERB_CALLS.items():
        source = inspect.getsource(inspect.unwrap(VERBS[verb].callback))
        for name in names:
            assert name in pipeline.__all__, (verb, name)
            obj = getattr(pipeline, name)
            assert callable(obj), name
            assert obj.__name__ in source, f"seatwin {verb} does not call {obj.__module__}.{obj.__name__}"


def _cli_default(verb: str, param: str) -> Any:
    (p,) = [p for p in VERBS[verb].params if p.name == param]
    return p.default


def _sensors(text: str | None) -> tuple[str, ...] | None:
    return None if text is None else tuple(s for s in text.split(",") if s != "none")


def test_default_sensors_of_every_verb_equal_the_library_s() -> None:
    from seatwin.api.lockstep import LockstepSettings
    from seatwin.pipeline.track import TrackOptions

    library = {
        "simulate": pipeline.DEFAULT_SENSORS,
        "serve": LockstepSettings().sensors,
        "cosim run": inspect.signature(pipeline.run_system).parameters["sensors"].default,  # None: the export's
        "cosim export": inspect.signature(pipeline.export_system).parameters["sensors"].default,
        "track": TrackOptions().sensors,
    }
    with_sensors = {v for v, c in VERBS.items() if any(p.name == "sensors" for p in c.params)}
    assert with_sensors == set(library)
    for verb, default in library.items():
        assert _sensors(_cli_default(verb, "sensors")) == default, verb


def test_simulate_defaults_equal_the_settings_defaults() -> None:
    """Every ``seatwin simulate`` option with a default sets a SimulationSettings field to that field's default."""
    from seatwin.sim import SimulationSettings

    fields = SimulationSettings.model_fields
    names = {"camera_hfov": "camera_hfov_deg", "fmt": "fmt", "lidar_mode": "lidar_mode", "lidar_preset": "lidar_preset"}
    names |= {"dissipation": "dissipation", "ray_drop": "ray_drop", "range_noise": "range_noise", "seed": "seed"}
    names |= {"lidar": "lidar_config", "radar": "radar_config"}
    for param, field in names.items():
        default = _cli_default("simulate", param)
        default = getattr(default, "value", default)
        assert default == fields[field].default, (param, default, fields[field].default)


def test_simulate_run_records_what_seatwin_simulate_records(tmp_path: Path) -> None:
    """Without sensors named, the library and the CLI record the same sensors (were: lidar vs lidar + cameras)."""
    lib = pipeline.simulate_run("ferry_crossing", tmp_path / "lib", start_offset=35.0, duration=0.2, progress=False)
    argv = ["simulate", "ferry_crossing", "--out", str(tmp_path / "cli"), "--offset", "35", "--duration", "0.2", "--quiet"]
    assert run(argv) == 0
    settings = [json.loads((tmp_path / d / "manifest.json").read_text())["metadata"]["settings"] for d in ("lib", "cli")]
    assert settings[0] == settings[1]
    assert tuple(settings[0]["sensors"]) == pipeline.DEFAULT_SENSORS
    assert set(lib.frames) >= {"lidar", "camera"}


@pytest.mark.parametrize("name", sorted(pipeline.__all__))
def test_every_export_resolves(name: str) -> None:
    assert getattr(pipeline, name) is not None
