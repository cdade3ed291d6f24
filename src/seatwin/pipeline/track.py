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

from pydantic import Field

from seatwin.errors import InputError
from seatwin.settings import Settings, validated

if TYPE_CHECKING:
    from seatwin.evaluation import Tracks
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
        found = scans_from_recording(
            rec,
            wanted,
            mask=mask,
            lidar=LidarClustering(eps=options.eps, min_points=options.min_points),
            radar=radar,
            truth=vessel_truth(rec),
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
    )
