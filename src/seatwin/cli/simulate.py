"""``seatwin simulate``: a scenario → a synthetic dataset (ROS bag + manifest + resolved scenario)."""

from __future__ import annotations

from enum import Enum
from pathlib import Path
from typing import Any

import typer

from seatwin.cli.output import compression_option, image_format_option, overwrite_option
from seatwin.defaults import DEFAULT_ROS_DISTRO, DEFAULT_SENSORS, ROS_DISTROS


class LidarMode(str, Enum):
    raycast = "raycast"
    depthbuffer = "depthbuffer"
    depthbuffer_legacy = "depthbuffer-legacy"
    depthbuffer_plane = "depthbuffer-plane"


class BagFormat(str, Enum):
    mcap = "mcap"
    sqlite3 = "sqlite3"
    ros1 = "ros1"


RosDistro = Enum("RosDistro", {d: d for d in ROS_DISTROS}, type=str)  # type: ignore[misc]
DEFAULT_DISTRO = RosDistro(DEFAULT_ROS_DISTRO)
ROS_DISTRO_HELP = (
    "ROS 2 distribution the rosbag2 metadata (mcap, sqlite3) is written for: "
    + ", ".join(f"{d} {v}" for d, v in ROS_DISTROS.items())
    + "; a distro reads its own version and older ones."
)


def register(app: typer.Typer) -> None:
    @app.command("simulate")
    def simulate_cmd(
        scenario: str = typer.Argument(
            ..., metavar="SCENARIO", help="A built-in scenario name, a scenario .yaml, or a Gemini .csv (vessel 3 = ownship)."
        ),
        out: Path = typer.Option(
            ..., "--out", help="New (or empty) run directory to record into; --overwrite replaces an earlier run there."
        ),
        duration: float | None = typer.Option(None, "--duration", help="Simulated seconds (default: to the scenario's end)."),
        start: float | None = typer.Option(None, "--start", help="POSIX start time (default: the scenario's start)."),
        offset: float | None = typer.Option(
            None, "--offset", help="Start this many seconds after the scenario's start (instead of --start)."
        ),
        harbour: str | None = typer.Option(
            None,
            "--harbour",
            help="Harbour instead of the scenario's own (a Gemini CSV's: ravnkloa; a built-in's: default): 'default', "
            "'ravnkloa' (the real land raster, found in $SEATWIN_DATA or ../shared/data), 'none' or a land raster .bin/.yaml.",
        ),
        seed: int | None = typer.Option(None, "--seed", help="Seed of every random draw (default: the scenario's)."),
        lidar_mode: LidarMode = typer.Option(LidarMode.raycast, "--lidar-mode", help="Lidar range model."),
        lidar_preset: str = typer.Option("vlp16", "--lidar-preset", help="vlp16 (1800 columns) or vlp16-thesis (1024)."),
        lidar: str | None = typer.Option(
            None, "--lidar", metavar="LIDAR.yaml", help="Lidar configuration, e.g. from 'seatwin lidar fit' (replaces the preset)"
        ),
        ray_drop: float | None = typer.Option(None, "--ray-drop", help="Ray-drop probability (default 0.8, as the thesis)."),
        range_noise: float | None = typer.Option(None, "--range-noise", help="Range noise σ in metres (default 0.015)."),
        dissipation: bool = typer.Option(False, "--dissipation", help="Range-dependent return probability."),
        fmt: BagFormat = typer.Option(BagFormat.mcap, "--format", help="Bag format."),
        ros_distro: RosDistro = typer.Option(DEFAULT_DISTRO, "--ros-distro", help=ROS_DISTRO_HELP),
        compression: str | None = compression_option(),
        image_format: str = image_format_option(),
        date: str | None = typer.Option(None, "--date", help="UTC date YYYY-MM-DD of a TimeOfDay CSV."),
        sensors: str = typer.Option(
            ",".join(DEFAULT_SENSORS),
            "--sensors",
            metavar="LIST",
            help="Comma-separated ownship sensors: lidar, radar, camera (the thesis's twin: lidar and the three cameras).",
        ),
        radar: str | None = typer.Option(
            None, "--radar", metavar="RADAR.yaml", help="Radar configuration (default: the built-in model)."
        ),
        camera_hfov: float = typer.Option(82.0, "--camera-hfov", help="Cameras' horizontal field of view [deg]."),
        camera_distortion: str | None = typer.Option(
            None, "--camera-distortion", metavar="K1,K2,T1,T2,K3", help="Plumb-bob distortion of the camera images."
        ),
        figure: Path | None = typer.Option(
            None,
            "--figure",
            metavar="FILE.png",
            help="Also draw the vessels' tracks over the recorded window and the harbour used, as PNG (outside --out).",
        ),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar (lines on a pipe)."),
        quiet: bool = typer.Option(False, "--quiet", "-q", hidden=True, help="Old spelling of --no-progress."),
        stream: str | None = typer.Option(
            None,
            "--stream",
            metavar="HOST:PORT",
            help="Also stream lidar clouds, camera images, radar spokes and navigation to a SensorStreaming server.",
        ),
        live: bool = typer.Option(
            False, "--live", help="Serve the run to Foxglove (WebSocket, see `seatwin view`) while it is made."
        ),
        live_port: int = typer.Option(8765, "--live-port", help="WebSocket port of --live (0: any free one)."),
        live_speed: float = typer.Option(
            1.0, "--live-speed", help="With --live: hold the run to this × real time (0: as fast as it goes)."
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Simulate the ownship's sensors along a scenario and record a ROS bag (MCAP by default).

        Topics (defaults): /lidar/points (PointCloud2, VLP-16 layout of thesis Table 4.2),
        /radar/detections (with --sensors lidar,radar), /camera/{left,front,right}/image_raw|camera_info|labels
        (camera: on by default), /ground_truth/<vessel>/pose|odom|fix, /tf, /tf_static.
        """
        streamer = None
        if stream:  # first: nothing listening there fails in seconds, before the simulator is imported
            from seatwin.api.streaming import SensorStreamer

            streamer = SensorStreamer(stream)
        from seatwin.cli.output import split_list
        from seatwin.cli.scenario import _date
        from seatwin.pipeline.simulate import (
            check_simulation_figure,
            plot_simulation,
            simulate_run,
            simulated_scenario,
            vessels_on_water,
        )

        if figure is not None:
            check_simulation_figure(figure, out, [scenario, radar], overwrite=overwrite)
        viewer = start_live(live_port, live_speed, fmt.value) if live else None
        try:
            result = simulate_run(
                scenario,
                out,
                on_frame=streamer.on_frame if streamer is not None else None,
                on_write=viewer.publish if viewer is not None else None,
                overwrite=overwrite,
                start=start,
                start_offset=offset,
                duration=duration,
                harbour=harbour,
                date=_date(date),
                progress=progress and not quiet,
                sensors=split_list(sensors, "sensors"),
                seed=seed,
                lidar_preset=lidar_preset,
                lidar_mode=lidar_mode.value,
                ray_drop=ray_drop,
                range_noise=range_noise,
                dissipation=dissipation,
                fmt=fmt.value,
                ros_distro=ros_distro.value,
                compression=compression,
                image_format=image_format,
                radar_config=radar,
                lidar_config=lidar,
                radar_spokes=streamer is not None,
                camera_hfov_deg=camera_hfov,
                **({"camera_distortion": split_list(camera_distortion, "camera_distortion")} if camera_distortion else {}),
            )
        finally:
            if viewer is not None:
                viewer.close()
        if streamer is not None:
            streamer.close()
            typer.echo(f"streamed to {stream}: {streamer.sent}")
        state = "completed" if result.completed else "INCOMPLETE (interrupted)"
        frames = ", ".join(f"{sensor.replace('_', ' ')} {n}" for sensor, n in result.frames.items()) or "none"
        typer.echo(
            f"{state}: {result.simulated_s:.1f} s simulated in {result.wall_s:.1f} s "
            f"(×{result.realtime_factor:.1f} real time); frames: {frames}; recording in {result.run_dir}"
        )
        if not result.completed:
            raise typer.Exit(130)
        water = vessels_on_water(simulated_scenario(result.run_dir))
        if water is not None:
            typer.echo("  on water: " + ", ".join(f"{name} {100 * f:.0f} %" for name, f in water.items()))
        if figure is not None:
            typer.echo(f"wrote {plot_simulation(result.run_dir, figure, overwrite=True)}")


def start_live(port: int, speed: float, fmt: str) -> Any:
    """A started :class:`~seatwin.recording.live.LiveServer` (its errors naming the --live-* flags); says where."""
    from seatwin.errors import ParameterError
    from seatwin.recording.live import LiveServer

    server = None
    try:
        server = LiveServer(port=port, speed=speed, fmt=fmt)
        bound = server.start()
    except ParameterError as exc:
        if server is not None:
            server.close()
        raise ParameterError(f"--live-{exc.param}", exc.detail) from None
    typer.echo(f"live view: Foxglove → Open connection → Foxglove WebSocket → ws://127.0.0.1:{bound}", err=True)
    return server
