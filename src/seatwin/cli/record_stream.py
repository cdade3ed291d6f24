"""``seatwin record-stream``: Gemini's SensorStreaming and Navigation services, recording what arrives into a ROS bag."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import compression_option, image_format_option, overwrite_option
from seatwin.cli.simulate import BagFormat


def register(app: typer.Typer) -> None:
    @app.command("record-stream")
    def record_stream_cmd(
        out: Path = typer.Option(..., "--out", help="New run directory to record into."),
        port: int = typer.Option(50052, "--port", help="TCP port of the services (0: any free one)."),
        host: str = typer.Option("127.0.0.1", "--host", help="Address to listen on (default loopback only)."),
        ownship: str = typer.Option("milliAmpere", "--ownship", help="Vessel whose navigation messages also give a NavSatFix."),
        fmt: BagFormat = typer.Option(BagFormat.mcap, "--format", help="Bag format."),
        mounts: bool = typer.Option(
            True,
            "--mounts/--no-mounts",
            help="Write the thesis rig's sensor mounts (lidar, radar, cameras) on /tf_static as each sensor first "
            "streams (the stream carries none), so the bag can be tracked.",
        ),
        compression: str | None = compression_option(),
        image_format: str = image_format_option(),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Serve sensorstreaming.SensorStreaming and navigation.Navigation; record every message into a ROS bag.

        Lidar clouds → /<frame_id>/points (PointCloud2), camera images → /<frame_id>/image_raw (Gemini sends
        RGB rows bottom up; recorded bgr8 rows top down, as Gemini's ROS adapter publishes them),
        radar spokes → /radar/spokes (mono8, a row per spoke) with /radar/spokes/azimuth (PointCloud2, a point per
        spoke: its azimuth and time, the range start/increment), navigation → /ground_truth/<vessel>/...
        Ctrl-C or SIGTERM finishes the bag (manifest completed: true).
        """
        from seatwin.api.streaming import record_stream
        from seatwin.interrupts import interrupts_set_event, wait
        from seatwin.outputs import remove_outputs
        from seatwin.recording.manifest import check_new_run

        remove_outputs(check_new_run(out, "out", overwrite=overwrite))
        with interrupts_set_event() as stop:  # before the address is announced: a signal right after it finishes the bag
            handle = record_stream(
                out,
                port=port,
                host=host,
                fmt=fmt.value,
                ownship=ownship,
                mounts=mounts,
                compression=compression,
                image_format=image_format,
            )
            typer.echo(f"serving SensorStreaming + Navigation on {handle.address}; recording into {out} (Ctrl-C to finish)")
            try:
                wait(stop)
            finally:
                counts = handle.stop()
        typer.echo(f"completed: recorded {counts}; recording in {out}")
