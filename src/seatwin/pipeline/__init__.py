"""Each use-case as one typed library call: what the CLI, the sweep, the fidelity method, benchmarks and tests call.

The simulation chain lives here:

* :func:`simulate_run` — a scenario → a recording (:mod:`.simulate`; default sensors :data:`DEFAULT_SENSORS`);
  :func:`simulated_scenario`, :func:`vessels_on_water`, :func:`plot_simulation` — what a run recorded, shown;
* :func:`track_recording`, :func:`track_scans` — a recording or scans → tracks (:mod:`.track`);
  :func:`tracking_summary`, :func:`plot_tracking` — a tracking run in numbers (coverage, false tracks, on land) and
  drawn;
* :func:`evaluate_run` — tracks vs ground truth (:mod:`.evaluate`);
* :func:`compare_runs` — a real vs a synthetic dataset (:mod:`.compare`);
* :func:`simulate_radar` — the radar alone (:mod:`.radar`); :func:`lidar_snapshot`, :func:`camera_snapshot`,
  :func:`export_coco` — one sweep, one set of images, the labels (:mod:`.lidar`, :mod:`.labels`);
* :func:`run_demo` — the whole loop on built-in data (:mod:`.demo`).

The call of every other verb is re-exported from the package that owns it, so that ``seatwin.pipeline``
holds every verb's call (``seatwin <verb>`` only parses, calls one or two of these, prints):
``groundtruth`` (:func:`compute_ground_truth`, :func:`write_ground_truth`), ``import``
(:func:`import_joyride`, :func:`import_ravnkloa_radar`), ``scenario`` (:func:`load_scenario`,
:func:`scenario_summary`, :func:`plot_scenario`, :func:`save_scenario`), ``bag info`` (:func:`bag_info`),
``errors`` (:func:`depth_error_table`, :func:`write_error_plots`), ``radar fit``
(:func:`fit_radar_to_recording`, :func:`save_radar_config`), ``lidar fit`` (:func:`fit_lidar_to_recording`,
:func:`save_lidar_config`), ``sweep`` (:func:`run_sweep`,
:func:`write_sweep`), ``campaign`` (:func:`run_campaign`), ``fidelity`` (:func:`run_fidelity`,
:func:`write_fidelity`), ``serve`` (:func:`serve`), ``record-stream`` (:func:`record_stream`),
``cosim`` (:func:`export_system`, :func:`run_system`), ``bag repair`` (:func:`repair_bag`), ``bag convert``
(:func:`convert_bag`), ``view`` (:class:`RecordingViewer`), ``harbour fit-alignment`` (:func:`fit_harbour_alignment`,
:func:`write_alignment`), ``harbour rasterize`` (:func:`land_raster_from_geojson`, :func:`write_land_raster`),
``verify`` (:func:`run_verification`).

Every import is lazy — a name's module is loaded when the name is first used — so the CLI starts fast,
and the packages that build on this one (campaign, sweep, fidelity) load only when one of their names is.
"""

from __future__ import annotations

from typing import Any

# name → "module" (the same name there) or "module:attribute"
_EXPORTS = {
    "simulate_run": "seatwin.pipeline.simulate",
    "simulated_scenario": "seatwin.pipeline.simulate",
    "vessels_on_water": "seatwin.pipeline.simulate",
    "plot_simulation": "seatwin.pipeline.simulate",
    "DEFAULT_SENSORS": "seatwin.defaults",
    "TrackOptions": "seatwin.pipeline.track",
    "TrackingResult": "seatwin.pipeline.track",
    "track_recording": "seatwin.pipeline.track",
    "TrackingSummary": "seatwin.pipeline.track",
    "tracking_summary": "seatwin.pipeline.track",
    "plot_tracking": "seatwin.pipeline.track",
    "track_scans": "seatwin.pipeline.track",
    "evaluate_run": "seatwin.pipeline.evaluate",
    "CompareResult": "seatwin.pipeline.compare",
    "compare_runs": "seatwin.pipeline.compare",
    "load_run": "seatwin.pipeline.compare",
    "DemoResult": "seatwin.pipeline.demo",
    "run_demo": "seatwin.pipeline.demo",
    "simulate_radar": "seatwin.pipeline.radar",
    "lidar_snapshot": "seatwin.pipeline.lidar",
    "camera_snapshot": "seatwin.pipeline.labels",
    "export_coco": "seatwin.pipeline.labels",
    "compute_ground_truth": "seatwin.groundtruth.pipeline",
    "write_ground_truth": "seatwin.groundtruth.pipeline:write_outputs",
    "import_joyride": "seatwin.perception.datasets",
    "import_ravnkloa_radar": "seatwin.perception.datasets",
    "load_scenario": "seatwin.scenario.load",
    "save_scenario": "seatwin.scenario.load",
    "scenario_summary": "seatwin.scenario.summary",
    "plot_scenario": "seatwin.scenario.plot",
    "bag_info": "seatwin.recording.info",
    "depth_error_table": "seatwin.sensors.depthbuffer.table:table_json",
    "write_error_plots": "seatwin.sensors.depthbuffer.plots",
    "fit_radar_to_recording": "seatwin.fidelity.radar_fit",
    "save_radar_config": "seatwin.sensors.radar.config",
    "fit_lidar_to_recording": "seatwin.fidelity.lidar_fit",
    "save_lidar_config": "seatwin.sensors.lidar_config",
    "SweepSettings": "seatwin.sweep.settings",
    "run_sweep": "seatwin.sweep.runner",
    "write_sweep": "seatwin.sweep.outputs",
    "run_campaign": "seatwin.campaign.run",
    "FidelityOptions": "seatwin.fidelity.options",
    "run_fidelity": "seatwin.fidelity.method",
    "write_fidelity": "seatwin.fidelity.report",
    "serve": "seatwin.api.server",
    "record_stream": "seatwin.api.streaming",
    "export_system": "seatwin.cosim.osp",
    "run_system": "seatwin.cosim.osp",
    "repair_bag": "seatwin.recording.repair",
    "convert_bag": "seatwin.recording.convert",
    "RecordingViewer": "seatwin.recording.view",
    "fit_harbour_alignment": "seatwin.scenario.on_water",
    "write_alignment": "seatwin.layout.alignment",
    "land_raster_from_geojson": "seatwin.layout.polygons",
    "write_land_raster": "seatwin.layout.raster",
    "run_verification": "seatwin.verification.campaign",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        import importlib

        module, _, attr = _EXPORTS[name].partition(":")
        return getattr(importlib.import_module(module), attr or name)
    raise AttributeError(f"module 'seatwin.pipeline' has no attribute {name!r}")
