"""``seatwin track``: run the JIPDA tracker over a recording and write TRACKS.csv (thesis ch. 5.1)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

_HELP = (
    "Track targets in a recording with the JIPDA tracker and extended Kalman filters (thesis ch. 5.1).\n\n"
    "Lidar sweeps are masked (ownship, land) and clustered; radar plots are masked and optionally merged; "
    "each cluster/plot becomes a range-bearing measurement from the sensor in the world frame. Writes one "
    "row per (scan time, live track): time,track_id,existence,north,v_north,east,v_east, P00…P33 "
    "(row-major, that state order), confirmed; and a marker row (track_id −1) for scans without tracks."
)


def _parse_sensors(text: str | None) -> tuple[str, ...] | None:
    if text is None:
        return None
    parts = tuple(p.strip() for p in text.split(",") if p.strip())
    from seatwin.errors import InputError
    from seatwin.perception.from_recording import SENSORS

    if not parts:
        raise InputError("--sensors", "expected a comma-separated list such as lidar,radar")
    for p in parts:
        if p not in SENSORS:
            raise InputError("--sensors", f"unknown sensor {p!r}; expected some of {', '.join(SENSORS)}")
    return parts


def register(app: typer.Typer) -> None:
    @app.command("track", help=_HELP)
    def track_cmd(
        recording: Path = typer.Argument(..., metavar="RECORDING", help="A run directory, rosbag2 directory, or .mcap/.db3/.bag file."),
        out: Path = typer.Option(..., "--out", metavar="TRACKS.csv", help="Where to write the track file."),
        sensors: Optional[str] = typer.Option(None, "--sensors", metavar="LIST", help="Comma-separated sensors: lidar, radar, camera. Default: the lidar and radar topics the recording has."),
        tuning: Optional[str] = typer.Option(None, "--tuning", metavar="NAME|FILE", help="Tracker tuning: a preset (synthetic, real, joyride — thesis Tables 5.1/5.2 and the joyride radar) or a YAML/JSON file. Default: the one the recording's manifest suggests, else 'real'."),
        map_spec: Optional[str] = typer.Option(None, "--map", metavar="harbour|none|RASTER", help="Water mask for land/quay returns: the built-in harbour, none, or a raster (.yaml/.bin, Ravnkloa format). Default: the recording's suggestion, else none."),
        merge: Optional[float] = typer.Option(None, "--radar-merge", metavar="M", help="Merge radar plots closer than M metres into one measurement (default: the recording's suggestion, else 0)."),
        radar_kind: str = typer.Option("range_bearing", "--radar-model", metavar="range_bearing|cartesian", help="Measurement model of radar plots: range and bearing from the radar (R from r_range, r_bearing), or Cartesian north/east (R from r_cartesian)."),
        eps: float = typer.Option(1.5, "--cluster-eps", metavar="M", help="Lidar clustering distance (m)."),
        min_points: int = typer.Option(3, "--min-points", metavar="N", help="Smallest lidar cluster (points)."),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar on long recordings."),
    ) -> None:
        import sys
        import time as _time

        import numpy as np

        from seatwin.errors import InputError
        from seatwin.evaluation import Tracks, write_tracks
        from seatwin.perception.from_recording import scans_from_recording
        from seatwin.perception.lidar import LidarClustering
        from seatwin.perception.measurements import MeasurementKind
        from seatwin.perception.map_mask import load_mask
        from seatwin.perception.radar import RadarPlots
        from seatwin.recording import open_bag
        from seatwin.tracking import JIPDATracker, load_tuning

        if not eps > 0:
            raise InputError("--cluster-eps", f"must be positive, got {eps}")
        if min_points < 1:
            raise InputError("--min-points", f"must be at least 1, got {min_points}")
        if radar_kind not in ("range_bearing", "cartesian"):
            raise InputError("--radar-model", f"expected range_bearing or cartesian, got {radar_kind!r}")
        if merge is not None and merge < 0:
            raise InputError("--radar-merge", f"must be non-negative, got {merge}")
        wanted = _parse_sensors(sensors)
        with open_bag(recording) as rec:
            hints = ((rec.manifest or {}).get("metadata") or {}).get("tracking") or {}
            cfg = load_tuning(tuning or hints.get("tuning") or "real")
            mask = load_mask(map_spec if map_spec is not None else _hint_path(hints.get("map"), rec))
            radar = RadarPlots(merge_distance=merge if merge is not None else float(hints.get("radar_merge", 0.0)),
                               kind=MeasurementKind(radar_kind))
            if wanted is None:
                present = []
                if rec.radar_topics():
                    present.append("radar")
                if len(rec.topics_of_type("sensor_msgs/msg/PointCloud2")) > len(rec.radar_topics()):
                    present.append("lidar")
                wanted = tuple(present) or ("lidar", "radar")
            for s in wanted:
                if s != "camera":
                    cfg.sensor(s)  # the tuning must cover every sensor used
            found = scans_from_recording(rec, wanted, mask=mask, lidar=LidarClustering(eps=eps, min_points=min_points),
                                         radar=radar)
            tracker = JIPDATracker(cfg)
            parts, times = [], []
            t_start = _time.perf_counter()
            show = progress and found.total >= 200 and sys.stderr.isatty()
            bar = None
            if show:
                from rich.console import Console
                from rich.progress import Progress

                bar = Progress(console=Console(stderr=True), transient=True)
                bar.start()
                task = bar.add_task("tracking", total=found.total)
            try:
                last_t = None
                for scan in found.scans:
                    if last_t is not None and scan.time < last_t:
                        raise InputError(recording, f"scans out of time order: {scan.time!r} after {last_t!r}")
                    table = tracker.step(scan)
                    if times and times[-1] == scan.time:  # two sensors at one instant: keep the later estimate
                        parts.pop()
                        times.pop()
                    parts.append(table)
                    times.append(scan.time)
                    last_t = scan.time
                    if bar is not None:
                        bar.advance(task)
            finally:
                if bar is not None:
                    bar.stop()
        from seatwin.tracking import TrackTable

        tab = TrackTable.concatenate(parts)
        tracks = Tracks(tab.time, tab.track_id, tab.existence, tab.x, tab.P, tab.confirmed,
                        scan_times=np.unique(np.asarray(times, dtype=float)), source=str(out))
        write_tracks(out, tracks)
        elapsed = _time.perf_counter() - t_start
        n_ids = len(np.unique(tab.track_id))
        n_conf = len(np.unique(tab.track_id[tab.confirmed]))
        typer.echo(f"{len(times)} scans ({', '.join(wanted)}), tuning {cfg.name!r}: {n_ids} tracks, {n_conf} confirmed; "
                   f"{elapsed:.2f} s; wrote {out}")


def _hint_path(value: object, rec) -> str | None:  # noqa: ANN001
    """A map hint from the manifest: a preset name, or a path relative to the run directory."""
    if value is None:
        return None
    text = str(value)
    if text in ("harbour", "none"):
        return text
    base = rec.run_dir if rec.run_dir is not None else Path(".")
    p = Path(text)
    return str(p if p.is_absolute() else base / p)
