"""One campaign job: simulate a scenario with some settings, track it per tuning, compare with the reference run's tracks.

Reference jobs simulate and track the reference setting once per (scenario, reference seed) and
return their tracks (per tuning, as JSON: :func:`tracks_to_json`); each synthetic job receives
them from the engine and returns one row per (tuning, target) (:func:`seatwin.campaign.results.target_row`).
Recordings live in a temporary folder on the worker and are gone when the job returns.
"""

from __future__ import annotations

import signal
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from seatwin.campaign.grid import REFERENCE, SYNTHETIC
from seatwin.errors import ParameterError

if TYPE_CHECKING:
    from seatwin.evaluation.tracks_io import Tracks


def tracks_to_json(tracks: Tracks) -> dict[str, Any]:
    """``tracks`` (and the plots behind them, when kept) as JSON values; floats survive exactly."""
    plots = getattr(tracks, "plots", None)
    return {
        "time": tracks.time.tolist(),
        "track_id": tracks.track_id.tolist(),
        "existence": tracks.existence.tolist(),
        "state": tracks.state.tolist(),
        "covariance": tracks.covariance.tolist(),
        "confirmed": tracks.confirmed.tolist(),
        "scan_times": tracks.scan_times.tolist(),
        "source": tracks.source,
        "plots": None
        if plots is None
        else {
            "times": plots.times.tolist(),
            "positions": [np.asarray(p).tolist() for p in plots.positions],
            "shapes": None if plots.shapes is None else [np.asarray(f).tolist() for f in plots.shapes],
            "sensor": None if plots.sensor is None else np.asarray(plots.sensor).tolist(),
            "clusters": None
            if plots.clusters is None
            else [None if c is None else np.asarray(c).tolist() for c in plots.clusters],
        },
    }


def tracks_from_json(data: dict[str, Any]) -> Tracks:
    """The :class:`Tracks` of :func:`tracks_to_json`."""
    from seatwin.evaluation.tracks_io import Tracks

    tracks = Tracks(
        data["time"],
        data["track_id"],
        data["existence"],
        data["state"],
        data["covariance"],
        data["confirmed"],
        scan_times=data["scan_times"],
        source=data["source"],
    )
    if data.get("plots") is not None:
        from seatwin.evaluation.tracks_io import PlotLog

        p = data["plots"]
        shapes, sensor, clusters = p.get("shapes"), p.get("sensor"), p.get("clusters")
        tracks.plots = PlotLog(
            np.asarray(p["times"], dtype=float),
            tuple(np.asarray(x, dtype=float).reshape(-1, 2) for x in p["positions"]),
            None if shapes is None else tuple(np.asarray(x, dtype=float).reshape(-1, 2) for x in shapes),
            None if sensor is None else np.asarray(sensor, dtype=float).reshape(-1, 2),
            None
            if clusters is None
            else tuple(None if x is None else np.asarray(x, dtype=float).reshape(-1, 4) for x in clusters),
        )
    return tracks


def simulate_and_track(
    params: dict[str, Any], work: Path
) -> tuple[Any, dict[str, Tracks], object | None, np.ndarray, dict[str, float]]:
    """Simulate ``params``' run into ``work`` and track it per tuning: the scenario, tracks per tuning, water mask, the
    harbour's moored boats ((n, 2) north/east: don't-care vessels), timings."""
    from seatwin.pipeline.track import harbour_of, track_recording
    from seatwin.scenario.load import load_scenario
    from seatwin.sim import simulate_scenario

    t0 = time.perf_counter()
    scenario = load_scenario(params["scenario"])
    rec = work / "run"
    result = simulate_scenario(
        scenario,
        rec,
        start=scenario.start + params["start_offset"],
        duration=params["duration"],
        progress=False,
        seed=params["seed"],
        # the tracker reads lidar and radar by default: no camera rig (the entry points' default) unless the settings ask
        **{"sensors": ("lidar",), **params["settings"]},
    )
    if not result.completed:  # Ctrl-C or SIGTERM in this process: the job did not run, it must not be recorded as if it had
        from seatwin.interrupts import Interrupted

        raise Interrupted(result.interrupted_by or signal.SIGINT)
    t1 = time.perf_counter()
    map_spec = params.get("map_spec")  # None: the recording's own water mask (its harbour)
    tracks = {tuning: track_recording(rec, tuning=tuning, map_spec=map_spec).tracks for tuning in params["tunings"]}
    t2 = time.perf_counter()
    for tuning, tr in tracks.items():  # the run's own name, not its temporary folder's: results never depend on where it ran
        tr.source = f"{params['kind']} run of {params['scenario']}, seed {params['seed']} (tuning {tuning})"
    mask, moored = harbour_of(map_spec, rec)
    return scenario, tracks, mask, moored, {"simulate_s": t1 - t0, "track_s": t2 - t1}


def reference_job(params: dict[str, Any]) -> dict[str, Any]:
    """The reference run's tracks per tuning."""
    with tempfile.TemporaryDirectory(prefix="seatwin-campaign-") as tmp:
        _, tracks, _, _, timings = simulate_and_track(params, Path(tmp))
    return {"tracks": {k: tracks_to_json(v) for k, v in tracks.items()}, "timings": timings}


def synthetic_job(params: dict[str, Any], reference: dict[str, Any]) -> dict[str, Any]:
    """Rows of (tuning, target) comparing this run with the reference's tracks of the same tuning."""
    from pydantic import TypeAdapter

    from seatwin.campaign.results import comparison_rows
    from seatwin.evaluation.compare import CompareOptions, compare
    from seatwin.evaluation.truth import truth_from_scenario
    from seatwin.pipeline.track import moored_vessels

    options = TypeAdapter(CompareOptions).validate_python(params["comparison"])
    with tempfile.TemporaryDirectory(prefix="seatwin-campaign-") as tmp:
        scenario, tracks, mask, moored, timings = simulate_and_track(params, Path(tmp))
    t0 = time.perf_counter()
    truth = truth_from_scenario(scenario)
    ignored = moored_vessels(moored, truth)  # tracks of moored boats are not false tracks
    rows = []
    for tuning in params["tunings"]:
        ref = tracks_from_json(reference["tracks"][tuning])
        rows += comparison_rows(compare(ref, tracks[tuning], truth, tuning, options, mask, ignored))
    timings["compare_s"] = time.perf_counter() - t0
    return {"rows": rows, "timings": timings}


def campaign_job(params: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    """The engine's job function (:data:`seatwin.campaign.engine.JobFn`) for both kinds of campaign job."""
    if params["kind"] == REFERENCE:
        return reference_job(params)
    if params["kind"] == SYNTHETIC:
        return synthetic_job(params, inputs[params["reference"]])
    raise ParameterError("kind", f"expected {REFERENCE!r} or {SYNTHETIC!r}, got {params['kind']!r}")
