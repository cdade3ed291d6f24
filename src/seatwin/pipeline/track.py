"""Track a recording (or scans) with the JIPDA or GNN agent: the use-case behind ``seatwin track``.

Recording → scans (lidar clustering, radar plots, land mask) → tracker → :class:`Tracks`. Every
caller that tracks — the CLI, compare, the sweep, the fidelity method, benchmarks, tests — goes
through :func:`track_scans`, which holds the one rule for scans at the same instant
(:func:`seatwin.tracking.run_tracker`).
"""

from __future__ import annotations

import time as _time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import NDArray
from pydantic import Field

from seatwin.errors import InputError
from seatwin.settings import Settings, validated

if TYPE_CHECKING:
    from seatwin.evaluation import Tracks, TruthSet
    from seatwin.perception.map_mask import WaterMask
    from seatwin.perception.measurements import Scan
    from seatwin.tracking import TrackerConfig

AGENTS = ("jipda", "gnn")


class TrackOptions(Settings):
    """How a recording is turned into measurements and tracked (defaults: the recording's own hints)."""

    sensors: tuple[Literal["lidar", "radar", "camera"], ...] | None = Field(
        None, description="Sensors to track with (default: the lidar and radar topics the recording has)."
    )
    tuning: str | None = Field(
        None,
        description="Tracker tuning: a preset (synthetic, real, real-thesis, joyride, ravnkloa) or a YAML/JSON file "
        "(default: the recording's suggestion, else 'real').",
    )
    map_spec: str | None = Field(
        None,
        description="Water mask for land/quay returns: 'harbour', 'none' or a raster (.yaml/.bin) "
        "(default: the recording's suggestion, else none).",
    )
    merge_distance: float | None = Field(
        None, ge=0, description="Merge radar plots closer than this [m] (default: the recording's suggestion, else 0)."
    )
    radar_kind: Literal["range_bearing", "cartesian"] = Field(
        "range_bearing", description="Measurement model of radar plots: range and bearing, or Cartesian north/east."
    )
    eps: float = Field(1.5, gt=0, description="Lidar clustering distance [m].")
    min_points: int = Field(3, ge=1, description="Smallest lidar cluster [points].")
    agent: Literal["jipda", "gnn"] = Field("jipda", description="The tracker: JIPDA (thesis ch. 5.1) or GNN.")
    detector: Literal["label", "onnx"] = Field(
        "label", description="Camera detector: 'label' (from the recorded labels) or 'onnx' (a YOLO-style model on the images)."
    )
    model: str | None = Field(None, description="The onnx detector's ONNX model file (never downloaded).")
    classes: tuple[int, ...] | None = Field(
        None, description="Class ids the onnx detector keeps (default: COCO 8, boat; empty: every class)."
    )
    ignore_crc: bool = Field(False, description="Read MCAP chunks whose CRC does not match (counted in the result).")


@dataclass
class TrackingResult:
    """What :func:`track_recording` produced, with what it used."""

    tracks: Tracks
    sensors: tuple[str, ...]
    tuning: str
    n_scans: int
    n_tracks: int
    n_confirmed: int
    elapsed_s: float
    bad_crc: int = 0
    """MCAP chunks read despite a CRC mismatch (``ignore_crc``)."""
    truth: TruthSet | None = None
    """The targets' ground truth the recording carries (None: it has none, as a real dataset)."""
    water: WaterMask | None = None
    """The water mask used (None: none), for tracks on land."""


@dataclass(frozen=True)
class TrackingSummary:
    """What a tracking run found, in a few numbers: confirmed tracks, each target's coverage and the false tracks
    (with ground truth), and the confirmed tracks whose mean position is on land (with a water mask)."""

    n_scans: int
    n_tracks: int
    n_confirmed: int
    coverage: dict[str, float | None]
    """Per target: the share of its instants with a confirmed track associated (empty without ground truth)."""
    false_tracks: int | None
    """Confirmed tracks never associated with a target nor following a moored boat (None without ground truth)."""
    on_land: int | None
    """Confirmed tracks whose mean position is on land (None without a water mask)."""


def tracking_summary(
    result: TrackingResult, gate: float = 10.0, recording: str | Path | None = None, map_spec: str | Path | None = None
) -> TrackingSummary:
    """:class:`TrackingSummary` of ``result``: targets associated within ``gate`` [m] (:func:`seatwin.evaluation.evaluate`);
    tracks on the moored boats of ``map_spec``'s harbour, or else of the harbour the ``recording``'s manifest names,
    are don't-care, not false (as :func:`seatwin.pipeline.evaluate.evaluate_run` counts them)."""
    import numpy as np

    from seatwin.evaluation import evaluate

    tracks = result.tracks.confirmed_only()
    on_land = None
    if result.water is not None:
        on_land = 0
        for k in np.unique(tracks.track_id):
            rows = tracks.track_id == k
            n, e = tracks.state[rows][:, 0].mean(), tracks.state[rows][:, 2].mean()
            on_land += int(not result.water.is_water(float(n), float(e)))
    coverage: dict[str, float | None] = {}
    false = None
    if result.truth is not None and len(result.truth) and len(result.tracks.scan_times):
        moored = moored_vessels(harbour_of(map_spec, recording)[1], result.truth, result.tracks.time)
        ev = evaluate(result.tracks, result.truth, gate=gate, mask=result.water, dont_care=moored)
        coverage = {s.target: s.coverage for s in ev.summaries}
        false = None if ev.false_tracks is None else ev.false_tracks.n_tracks
    return TrackingSummary(result.n_scans, result.n_tracks, result.n_confirmed, coverage, false, on_land)


def plot_tracking(result: TrackingResult, out: str | Path, *, title: str | None = None, overwrite: bool = False) -> Path:
    """Draw ``result``'s confirmed tracks (and the targets' ground truth, and the land of its water mask) from above
    into the PNG ``out`` (an existing one only with ``overwrite``)."""
    from seatwin.outputs import check_output_file, write_bytes_atomic
    from seatwin.report.figures import tracking_figure

    out = Path(out)
    if out.suffix.lower() != ".png":
        from seatwin.errors import ParameterError

        raise ParameterError("figure", f"the figure is written as PNG: give a file name ending in .png, got {str(out)!r}")
    check_output_file(out, "figure", overwrite=overwrite)
    name = title or f"tracks ({', '.join(result.sensors)}, tuning {result.tuning})"
    write_bytes_atomic(out, tracking_figure(result.tracks, result.truth, result.water, name))
    return out


def track_scans(
    scans: Iterable[Scan],
    tuning: TrackerConfig | str,
    *,
    agent: str = "jipda",
    source: str = "<scans>",
    on_scan: Callable[[Scan], None] | None = None,
    water: WaterMask | None = None,
) -> Tracks:
    """Run a fresh ``agent`` (``jipda`` or ``gnn``) with ``tuning`` (config, preset name or file) over ``scans``;
    ``water``: the map's water mask, for the tuning's rule on tracks over land (``land_scans``)."""
    import numpy as np

    from seatwin.evaluation import Tracks
    from seatwin.evaluation.tracks_io import PlotLog
    from seatwin.perception.lidar import cluster_moment_rows, cluster_shape_features
    from seatwin.perception.measurements import MeasurementKind
    from seatwin.tracking import JIPDATracker, load_tuning, run_tracker
    from seatwin.tracking.gnn import GNNTracker

    if agent not in AGENTS:
        from seatwin.errors import ParameterError

        raise ParameterError("agent", f"expected one of {', '.join(AGENTS)}, got {agent!r}")
    cfg = load_tuning(tuning) if isinstance(tuning, str) else tuning
    tracker = JIPDATracker(cfg, water) if agent == "jipda" else GNNTracker(cfg, water)
    plot_times: list[float] = []
    plot_positions: list[np.ndarray] = []
    plot_shapes: list[np.ndarray] = []
    plot_sensor: list[np.ndarray] = []
    plot_clusters: list[np.ndarray | None] = []

    def seen(scan: Scan) -> None:
        if scan.kind is not MeasurementKind.BEARING:
            plot_times.append(scan.time)
            plot_positions.append(scan.positions())
            plot_shapes.append(cluster_shape_features(scan))
            plot_sensor.append(scan.sensor_position)
            plot_clusters.append(cluster_moment_rows(scan))
        if on_scan is not None:
            on_scan(scan)

    run = run_tracker(tracker, scans, seen, source)
    tab = run.table
    return Tracks(
        tab.time,
        tab.track_id,
        tab.existence,
        tab.x,
        tab.P,
        tab.confirmed,
        scan_times=run.scan_times,
        source=f"{source} (tuning {cfg.name}, {agent})",
        plots=PlotLog(
            np.asarray(plot_times, dtype=float),
            tuple(plot_positions),
            tuple(plot_shapes),
            np.asarray(plot_sensor, dtype=float).reshape(-1, 2),
            tuple(plot_clusters),
        ),
    )


def tracking_hints(manifest: dict[str, Any] | None) -> dict[str, Any]:
    """What a recording's manifest suggests for tracking it (``metadata.tracking``: tuning, map, radar_merge)."""
    return ((manifest or {}).get("metadata") or {}).get("tracking") or {}


def map_hint(manifest: dict[str, Any] | None, run_dir: Path | None) -> str | None:
    """The manifest's water-mask hint: a preset name (harbour, none), or a raster path relative to the run directory."""
    value = tracking_hints(manifest).get("map")
    if value is None:
        return None
    text = str(value)
    if text in ("harbour", "none", "ravnkloa"):  # names (load_mask resolves ravnkloa's raster)
        return text
    p = Path(text)
    return str(p if p.is_absolute() or run_dir is None else run_dir / p)


def vessel_truth(rec: Any) -> dict[str, Any] | None:
    """Every vessel's truth of an open recording (its topics, else the scenario beside it); None if it has none."""
    from seatwin.evaluation.truth import recording_truth

    try:
        return recording_truth(rec)
    except InputError:
        return None


def default_sensors(rec: Any) -> tuple[str, ...]:
    """The sensors :func:`track_recording` uses when none are named: the radar and lidar topics an open
    recording has (both when it has neither, so that the error names what is missing)."""
    present = []
    if rec.radar_topics():
        present.append("radar")
    if len(rec.topics_of_type("sensor_msgs/msg/PointCloud2")) > len(rec.radar_topics()):
        present.append("lidar")
    return tuple(present) or ("lidar", "radar")


def track_recording(
    recording: str | Path,
    options: TrackOptions | None = None,
    *,
    progress: Callable[[int, int], None] | None = None,
    **changes: Any,
) -> TrackingResult:
    """Track ``recording`` (run directory, rosbag2 directory, .mcap/.db3/.bag) with ``options`` (+ field ``changes``).

    ``progress(done, total)`` is called after every scan.
    """
    options = validated(TrackOptions, {**(options or TrackOptions()).model_dump(), **changes})
    path = Path(recording)
    if not path.exists():
        raise InputError(path, "no such recording (a run directory, rosbag2 directory, or .mcap/.db3/.bag file)")
    from seatwin.evaluation.truth import targets_truth
    from seatwin.perception.camera_frames import camera_detector
    from seatwin.perception.from_recording import scans_from_recording
    from seatwin.perception.lidar import LidarClustering
    from seatwin.perception.map_mask import NoMask, load_mask
    from seatwin.perception.measurements import MeasurementKind
    from seatwin.perception.radar import RadarPlots
    from seatwin.recording import ReadOptions, open_bag
    from seatwin.tracking import load_tuning

    camera = camera_detector(options.detector, options.model, options.classes)
    if camera is not None and "camera" not in (options.sensors or ()):
        from seatwin.errors import ParameterError

        raise ParameterError("detector", "the onnx detector reads the camera images: track with camera among the sensors")
    t_start = _time.perf_counter()
    with open_bag(path, ReadOptions.from_env(ignore_crc=options.ignore_crc)) as rec:
        bad_crc = rec.bad_crc
        hints = tracking_hints(rec.manifest)
        cfg = load_tuning(options.tuning or hints.get("tuning") or "real")
        mask = load_mask(options.map_spec if options.map_spec is not None else map_hint(rec.manifest, rec.run_dir))
        merge = options.merge_distance if options.merge_distance is not None else float(hints.get("radar_merge", 0.0))
        radar = RadarPlots(merge_distance=merge, kind=MeasurementKind(options.radar_kind))
        wanted = options.sensors if options.sensors is not None else default_sensors(rec)
        for s in wanted:
            cfg.sensor(s)  # the tuning must cover every sensor used
        vessels = vessel_truth(rec)
        found = scans_from_recording(
            rec,
            wanted,
            mask=mask,
            lidar=LidarClustering(eps=options.eps, min_points=options.min_points),
            radar=radar,
            truth=vessels,
            camera=camera,
        )
        done = 0

        def advance(_scan: Scan) -> None:
            nonlocal done
            done += 1
            if progress is not None:
                progress(done, found.total)

        water = None if isinstance(mask, NoMask) else mask
        tracks = track_scans(found.scans, cfg, agent=options.agent, source=str(path), on_scan=advance, water=water)
    import numpy as np

    return TrackingResult(
        tracks,
        tuple(wanted),
        cfg.name,
        len(tracks.scan_times),
        len(np.unique(tracks.track_id)),
        len(np.unique(tracks.track_id[tracks.confirmed])),
        _time.perf_counter() - t_start,
        bad_crc,
        None if vessels is None else targets_truth(vessels, str(path)),
        water,
    )


def track_into_run(
    recording: str | Path,
    out_bag: str | Path,
    options: TrackOptions | None = None,
    *,
    overwrite: bool = False,
    progress: Callable[[int, int], None] | None = None,
    **changes: Any,
) -> tuple[TrackingResult, Any]:
    """Track ``recording`` (as :func:`track_recording`) and write a copy of it at ``out_bag`` with the tracks as ROS
    messages beside the sensors (:mod:`seatwin.recording.tracks`: ``/tracks/odom``, ``/tracks/markers``,
    ``/tracks/scene``); the input is never modified, an existing ``out_bag`` only replaced with ``overwrite``.
    Returns the tracking result and the copy's :class:`~seatwin.recording.convert.ConvertResult`."""
    from seatwin.recording.annotate import bag_format, copy_with_messages
    from seatwin.recording.manifest import check_bag_output
    from seatwin.recording.tracks import track_messages

    if not overwrite:
        check_bag_output(Path(out_bag), recording, False, "out_bag")  # before the tracking's time is spent
    result = track_recording(recording, options, progress=progress, **changes)
    messages = track_messages(result.tracks, bag_format(recording))
    added = {
        "what": "tracks",
        "sensors": list(result.sensors),
        "tuning": result.tuning,
        "agent": validated(TrackOptions, {**(options or TrackOptions()).model_dump(), **changes}).agent,
        "tracks": result.n_tracks,
        "confirmed": result.n_confirmed,
    }
    return result, copy_with_messages(recording, out_bag, messages, added=added, overwrite=overwrite, param="out_bag")


def recording_mask(spec: str | Path | None) -> object | None:
    """The water mask a run directory's manifest names (:func:`seatwin.pipeline.track.map_hint`), else None."""
    from seatwin.perception.map_mask import load_mask
    from seatwin.recording.manifest import read_manifest

    if spec is None or not Path(spec).is_dir():
        return None
    hint = map_hint(read_manifest(Path(spec)), Path(spec))
    return None if hint is None else load_mask(hint)


def recording_moored_boats(spec: str | Path | None) -> NDArray[np.float64]:
    """(n, 2) north/east of the moored boats of the harbour a run directory's manifest names (its map hint:
    :func:`seatwin.layout.moored_boat_positions`); none for anything else. They are real objects without ground
    truth: tracks on them are don't-care, not false tracks."""
    from seatwin.layout import moored_boat_positions
    from seatwin.recording.manifest import read_manifest

    if spec is None or not Path(spec).is_dir():
        return np.empty((0, 2))
    hint = map_hint(read_manifest(Path(spec)), Path(spec))
    return np.empty((0, 2)) if hint is None else moored_boat_positions(hint)


def harbour_of(map_spec: str | Path | None, run_dir: str | Path | None) -> tuple[object | None, NDArray[np.float64]]:
    """The water mask and the moored boats' (n, 2) positions of ``map_spec``, or else of the harbour the run directory
    ``run_dir``'s manifest names (none for anything else)."""
    if map_spec is not None:
        from seatwin.layout import moored_boat_positions
        from seatwin.perception.map_mask import load_mask

        return load_mask(map_spec), moored_boat_positions(map_spec)
    return recording_mask(run_dir), recording_moored_boats(run_dir)


def moored_vessels(points: NDArray[np.float64], truth: TruthSet, times: NDArray[np.float64] | None = None) -> TruthSet | None:
    """Moored boats at ``points`` as don't-care vessels, still over the span of ``truth`` and ``times`` (a day either
    side: a moored boat is there all along); None when there are none."""
    from seatwin.evaluation import stationary_truth

    if not len(points):
        return None
    spans = [t for tr in truth.targets.values() for t in (tr.start, tr.end)]
    if times is not None and len(times):
        spans += [float(np.min(times)), float(np.max(times))]
    if not spans:
        return None
    return stationary_truth(points, min(spans) - 86400.0, max(spans) + 86400.0)
