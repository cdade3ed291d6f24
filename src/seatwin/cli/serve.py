"""``seatwin serve``: Gemini's ``Simulation`` gRPC service — an OSP scenario generator poses the vessels, seatwin records."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import typer

from seatwin.cli.output import compression_option, image_format_option, overwrite_option
from seatwin.cli.simulate import BagFormat, LidarMode
from seatwin.defaults import DEFAULT_SENSORS


def register(app: typer.Typer) -> None:
    @app.command("serve")
    def serve_cmd(
        out: Path = typer.Option(..., "--out", help="New run directory to record into."),
        port: int = typer.Option(50051, "--port", help="TCP port of the Simulation service (0: any free one)."),
        host: str = typer.Option("127.0.0.1", "--host", help="Address to listen on (default loopback only)."),
        seed: int = typer.Option(0, "--seed", help="Seed of every random draw."),
        vessels: str = typer.Option(
            "Havfruen,Finn,milliAmpere", "--vessels", metavar="LIST", help="Vessel names in the order of the steps' poses."
        ),
        ownship: str = typer.Option("milliAmpere", "--ownship", help="The vessel carrying the sensors."),
        sensors: str = typer.Option(
            ",".join(DEFAULT_SENSORS),
            "--sensors",
            metavar="LIST",
            help="Comma-separated ownship sensors: lidar, radar, camera; 'none' for ground truth only.",
        ),
        lidar_mode: LidarMode = typer.Option(LidarMode.raycast, "--lidar-mode", help="Lidar range model."),
        lidar_preset: str = typer.Option("vlp16", "--lidar-preset", help="vlp16 (1800 columns) or vlp16-thesis (1024)."),
        fmt: BagFormat = typer.Option(BagFormat.mcap, "--format", help="Bag format."),
        compression: str | None = compression_option(),
        image_format: str = image_format_option(),
        harbour: str = typer.Option(
            "default",
            "--harbour",
            help="Harbour the poses are in: 'default', 'ravnkloa' (the Gemini scenarios' frame; the real land raster "
            "from $SEATWIN_DATA or ../shared/data), 'none' or a land raster .bin/.yaml.",
        ),
        stream: str | None = typer.Option(
            None,
            "--stream",
            metavar="HOST:PORT",
            help="Also stream lidar clouds, camera images and radar spokes to this SensorStreaming server.",
        ),
        overwrite: bool = overwrite_option(),
        live: bool = typer.Option(
            False, "--live", help="Serve the run to Foxglove (WebSocket, see `seatwin view`) while the steps make it."
        ),
        live_port: int = typer.Option(8765, "--live-port", help="WebSocket port of --live (0: any free one)."),
        max_step: float | None = typer.Option(
            None,
            "--max-step",
            metavar="S",
            help="The most seconds one DoStep may advance past the last (default: max(10 × its stepSize, 1 s)).",
        ),
        max_message_bytes: int = typer.Option(
            1024 * 1024, "--max-message-bytes", metavar="N", help="Largest request accepted, in bytes (17 bytes a vessel)."
        ),
    ) -> None:
        """Serve Gemini's GeminiOSPInterface.Simulation (DoStep, SetStartTime) and record what the steps make.

        Each DoStep poses the vessels (north, east [m], heading [deg clockwise from north], in --vessels
        order) at `time` seconds since the SetStartTime POSIX start, runs every sensor due in the one
        loop and records as `seatwin simulate` does, then answers (lock-step). Steps at negative
        times are history before the start (no frames; the first frame's velocities then equal
        `seatwin simulate`'s). A step may not go back in time nor advance more than --max-step; a refused
        request changes nothing. Ctrl-C or SIGTERM refuses further steps, stops a step in progress and
        finishes the bag (manifest completed: true; false if a step was cut short).
        """
        from seatwin.api.server import serve
        from seatwin.cli.output import split_list
        from seatwin.cli.simulate import start_live
        from seatwin.interrupts import interrupts_set_event, wait
        from seatwin.outputs import remove_outputs
        from seatwin.recording.manifest import check_new_run

        remove_outputs(check_new_run(out, "out", inputs=[harbour], overwrite=overwrite))
        sensor_list = split_list(sensors, "sensors") or ()
        streamer = None
        if stream:
            from seatwin.api.streaming import SensorStreamer

            streamer = SensorStreamer(stream)
        viewer = start_live(live_port, 0.0, fmt.value) if live else None  # the client's steps set the pace
        with interrupts_set_event() as stop, _closing(viewer):  # before the address is announced: a signal finishes the bag
            handle = serve(
                out,
                port=port,
                host=host,
                seed=seed,
                vessels=split_list(vessels, "vessels"),
                ownship=ownship,
                sensors=() if sensor_list == ("none",) else sensor_list,
                lidar_mode=lidar_mode.value,
                lidar_preset=lidar_preset,
                fmt=fmt.value,
                compression=compression,
                image_format=image_format,
                harbour=harbour,
                radar_spokes=True,  # a rotation's spokes: streamed, and served by Sensordata
                on_frame=streamer.on_frame if streamer is not None else None,
                interrupt=stop,
                max_step_s=max_step,
                max_message_bytes=max_message_bytes,
            )
            if viewer is not None:
                viewer.attach(handle.sim.writer)  # before the address is announced: no step has run yet
            typer.echo(
                f"serving GeminiOSPInterface.Simulation (and ForceControl, Sensordata, SensorManagement) on {handle.address}; "
                f"recording into {out} (Ctrl-C to finish)"
            )
            try:
                wait(stop)
            finally:
                result = handle.stop()
                if streamer is not None:
                    streamer.close()
        state = "completed" if result.completed else "INCOMPLETE (a step was interrupted or failed: the manifest says why)"
        typer.echo(
            f"{state}: {handle.servicer.steps} steps ({handle.servicer.rejected} refused), "
            f"{result.simulated_s:.1f} s simulated; frames {result.frames}; recording in {result.run_dir}"
        )


@contextlib.contextmanager
def _closing(viewer: Any) -> Iterator[None]:
    """Close the --live server (if any) on leaving."""
    try:
        yield
    finally:
        if viewer is not None:
            viewer.close()
