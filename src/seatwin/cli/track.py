"""``seatwin track``: run the JIPDA tracker over a recording and write TRACKS.csv (thesis ch. 5.1)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import typer

from seatwin.cli.output import overwrite_option

if TYPE_CHECKING:
    from seatwin.pipeline.track import TrackingSummary

_HELP = (
    "Track targets in a recording with the JIPDA tracker and extended Kalman filters (thesis ch. 5.1).\n\n"
    "Lidar sweeps are masked (ownship, land) and clustered; radar plots are masked and optionally merged; "
    "each cluster/plot becomes a range-bearing measurement from the sensor in the world frame; camera detections "
    "(--detector) become bearings (thesis 5.1.3). Writes one "
    "row per (scan time, live track): time,track_id,existence,north,v_north,east,v_east, P00…P33 "
    "(row-major, that state order), confirmed; and a marker row (track_id −1) for scans without tracks."
)


def register(app: typer.Typer) -> None:
    @app.command("track", help=_HELP)
    def track_cmd(
        recording: Path = typer.Argument(
            ..., metavar="RECORDING", help="A run directory, rosbag2 directory, or .mcap/.db3/.bag file."
        ),
        out: Path | None = typer.Option(None, "--out", metavar="TRACKS.csv", help="Where to write the track file."),
        out_bag: Path | None = typer.Option(
            None,
            "--out-bag",
            metavar="DIR",
            help="Also (or instead) write a copy of the run with the tracks in its bag: /tracks/odom (nav_msgs/Odometry), "
            "/tracks/markers (visualization_msgs/MarkerArray) and /tracks/scene (foxglove_msgs/SceneUpdate). "
            "The input is not modified.",
        ),
        sensors: str | None = typer.Option(
            None,
            "--sensors",
            metavar="LIST",
            help="Comma-separated sensors: lidar, radar, camera. Default: the lidar and radar topics the recording has.",
        ),
        tuning: str | None = typer.Option(
            None,
            "--tuning",
            metavar="NAME|FILE",
            help=(
                "Tracker tuning: a preset (synthetic, real, joyride, ravnkloa — thesis Tables 5.1/5.2, the joyride and "
                "Ravnkloa radars; real-thesis: the thesis's tracker without speed gate or land rule) or "
                "a YAML/JSON file. Default: the one the recording's manifest suggests, else 'real'."
            ),
        ),
        map_spec: str | None = typer.Option(
            None,
            "--map",
            metavar="harbour|ravnkloa|none|RASTER",
            help=(
                "Water mask for land/quay returns: the built-in harbour, none, or a raster (.yaml/.bin, Ravnkloa "
                "format). Default: the recording's suggestion, else none."
            ),
        ),
        merge: float | None = typer.Option(
            None,
            "--radar-merge",
            metavar="M",
            help="Merge radar plots closer than M metres into one measurement (default: the recording's suggestion, else 0).",
        ),
        radar_kind: str = typer.Option(
            "range_bearing",
            "--radar-model",
            metavar="range_bearing|cartesian",
            help=(
                "Measurement model of radar plots: range and bearing from the radar (R from r_range, r_bearing), or "
                "Cartesian north/east (R from r_cartesian)."
            ),
        ),
        eps: float = typer.Option(1.5, "--cluster-eps", metavar="M", help="Lidar clustering distance (m)."),
        min_points: int = typer.Option(3, "--min-points", metavar="N", help="Smallest lidar cluster (points)."),
        agent: str = typer.Option(
            "jipda", "--agent", metavar="jipda|gnn", help="The tracker: JIPDA (thesis ch. 5.1) or global nearest neighbour."
        ),
        detector: str = typer.Option(
            "label",
            "--detector",
            metavar="label|onnx",
            help=(
                "Camera detector for --sensors ...,camera: 'label' (the recorded ground-truth labels with misses and box "
                "noise) or 'onnx' (a YOLO-style ONNX model, --model, run on the recorded images)."
            ),
        ),
        model: Path | None = typer.Option(
            None, "--model", metavar="FILE.onnx", help="The onnx detector's model (YOLOv5/YOLOv8 export; never downloaded)."
        ),
        classes: str | None = typer.Option(
            None, "--classes", metavar="ID[,ID…]", help="Class ids the onnx detector keeps (default: 8, COCO 'boat')."
        ),
        figure: Path | None = typer.Option(
            None,
            "--figure",
            metavar="FILE.png",
            help="Also draw the confirmed tracks from above (with the ground truth and land the recording has) as PNG.",
        ),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar on long recordings."),
        overwrite: bool = overwrite_option(),
        ignore_crc: bool = typer.Option(
            False, "--ignore-crc", help="Read MCAP chunks whose CRC does not match, with a warning that counts them."
        ),
    ) -> None:
        from seatwin.cli.output import progress_counter, split_list
        from seatwin.errors import ParameterError
        from seatwin.outputs import check_output_file
        from seatwin.pipeline.track import TrackOptions, plot_tracking, track_into_run, track_recording, tracking_summary
        from seatwin.settings import validated

        if out is None and out_bag is None:
            raise ParameterError("out", "nowhere to write the tracks: give --out TRACKS.csv, --out-bag DIR, or both")
        if out is not None:
            check_output_file(out, "out", inputs=[recording, model, tuning, map_spec], overwrite=overwrite)
        if figure is not None:
            outputs = [p for p in (out, out_bag) if p is not None]
            check_output_file(figure, "figure", inputs=[recording, model, tuning, map_spec], overwrite=overwrite, outputs=outputs)
        options = validated(
            TrackOptions,
            dict(
                sensors=split_list(sensors, "sensors"),
                tuning=tuning,
                map_spec=map_spec,
                merge_distance=merge,
                radar_kind=radar_kind,
                eps=eps,
                min_points=min_points,
                agent=agent,
                detector=detector,
                model=None if model is None else str(model),
                classes=None if classes is None else split_list(classes, "classes"),
                ignore_crc=ignore_crc,
            ),
        )
        with progress_counter("tracking", enabled=progress) as advance:
            if out_bag is not None:
                result, copy = track_into_run(recording, out_bag, options, overwrite=overwrite, progress=advance)
            else:
                result, copy = track_recording(recording, options, progress=advance), None
        from seatwin.evaluation import write_tracks

        if result.bad_crc:
            typer.echo(f"warning: {recording}: {result.bad_crc} CRC mismatch(es) ignored (--ignore-crc)", err=True)
        wrote = []
        if out is not None:
            result.tracks.source = str(out)
            write_tracks(out, result.tracks)
            wrote.append(str(out))
        if copy is not None:
            wrote.append(f"{copy.path} (the run with /tracks/odom, /tracks/markers, /tracks/scene)")
        summary = tracking_summary(result, recording=recording, map_spec=map_spec)
        typer.echo(
            f"{result.n_scans} scans ({', '.join(result.sensors)}), tuning {result.tuning!r}: {result.n_tracks} tracks, "
            f"{result.n_confirmed} confirmed; {result.elapsed_s:.2f} s; wrote {' and '.join(wrote)}"
        )
        for line in summary_lines(summary):
            typer.echo(line)
        if figure is not None:
            title = f"{recording}: {', '.join(result.sensors)}, tuning {result.tuning}"
            plot_tracking(result, figure, title=title, overwrite=True)
            typer.echo(f"wrote {figure}")


def summary_lines(summary: TrackingSummary) -> list[str]:
    """The console lines of a :class:`~seatwin.pipeline.track.TrackingSummary`: per-target coverage, false tracks and
    tracks on land (each only where the recording has what it needs: ground truth, a water mask)."""
    s = summary
    lines: list[str] = []
    if s.coverage:
        cov = ", ".join(
            f"{name} {'never tracked' if c is None or c == 0 else f'{100 * c:.0f} %'}" for name, c in s.coverage.items()
        )
        lines.append(f"  targets (share of their time with a confirmed track): {cov}")
    false = "— (no ground truth in the recording)" if s.false_tracks is None else str(s.false_tracks)
    land = "— (no water mask)" if s.on_land is None else str(s.on_land)
    lines.append(f"  confirmed tracks {s.n_confirmed}: false tracks {false}, on land {land}")
    return lines
