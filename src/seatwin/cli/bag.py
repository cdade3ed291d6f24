"""``seatwin bag``: inspect recordings (ours and real ROS 1 / rosbag2 SQLite3 / MCAP bags)."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import compression_option, overwrite_option
from seatwin.cli.simulate import DEFAULT_DISTRO, ROS_DISTRO_HELP, BagFormat, RosDistro


def register(app: typer.Typer) -> None:
    bag_app = typer.Typer(
        help="Inspect recordings: ROS 1 .bag, rosbag2 (SQLite3, MCAP) and seatwin run directories.", no_args_is_help=True
    )
    app.add_typer(bag_app, name="bag")

    @bag_app.command("info")
    def info(
        path: Path = typer.Argument(..., help="A run directory, a rosbag2 directory, or a .mcap, .db3 or .bag file."),
        fast: bool = typer.Option(False, "--fast", help="Skip the scan for per-topic rates (rate = (count - 1) / bag duration)."),
        as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
        ignore_crc: bool = typer.Option(
            False, "--ignore-crc", help="Read MCAP chunks whose CRC does not match, with a warning that counts them."
        ),
    ) -> None:
        """Format, duration, start and end, completeness, and every topic with its type, count and rate."""
        import json

        from seatwin.recording.info import bag_info, format_info

        data = bag_info(path, scan=not fast, ignore_crc=ignore_crc)
        if data["bad_crc"]:
            typer.echo(f"warning: {path}: {data['bad_crc']} CRC mismatch(es) ignored (--ignore-crc)", err=True)
        typer.echo(json.dumps(data, indent=2) if as_json else format_info(data))

    @bag_app.command("repair")
    def repair(
        path: Path = typer.Argument(
            ..., metavar="RUN", help="A killed run's directory, or its bag (rosbag2 folder, .mcap, .db3, .bag)."
        ),
        out: Path | None = typer.Option(
            None, "--out", metavar="DIR", help="Where to write the repaired run (default: RUN.repaired beside it)."
        ),
        in_place: bool = typer.Option(False, "--in-place", help="Replace the original (once the repaired copy is complete)."),
        compression: str | None = compression_option(),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Rewrite a killed run's bag (MCAP without summary, rosbag2 without metadata.yaml, ROS 1 without index)
        into a finished one that standard readers (mcap, rosbags, ROS tools) open. The messages up to the
        bag's last flush are kept, bytes unchanged; the original is not touched unless --in-place."""
        from seatwin.recording.repair import repair_bag

        result = repair_bag(path, out, in_place=in_place, overwrite=overwrite, compression=compression)
        how = "was finished already; rewritten" if result.was_finished else "repaired"
        lost = "; the scan stopped at a damaged record (what follows it is lost)" if result.truncated else ""
        typer.echo(f"{result.format} bag {how}: {result.messages} messages on {len(result.topics)} topics in {result.bag}{lost}")

    @bag_app.command("convert")
    def convert(
        src: Path = typer.Argument(..., help="A run directory, a rosbag2 directory, or a .mcap, .db3 or .bag file."),
        out: Path = typer.Option(..., "--out", help="New path: a run directory for a run, else the bag (a .bag file for ros1)."),
        fmt: BagFormat = typer.Option(BagFormat.mcap, "--format", help="Format of the new bag."),
        ros_distro: RosDistro = typer.Option(DEFAULT_DISTRO, "--ros-distro", help=ROS_DISTRO_HELP),
        compression: str | None = compression_option(),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Write a bag in another format (MCAP, SQLite3, ROS 1) or for another ROS 2 distribution's metadata version.

        Every message is kept with its log time; a run directory becomes a run directory (scenario and
        manifest copied) that every seatwin command reads as the original.
        """
        from seatwin.recording.convert import convert_bag

        result = convert_bag(src, out, fmt=fmt.value, ros_distro=ros_distro.value, overwrite=overwrite, compression=compression)
        distro = f" for ROS 2 {result.ros_distro}" if result.ros_distro else ""
        n = sum(result.counts.values())
        typer.echo(f"wrote {n} messages on {len(result.counts)} topics as {result.format}{distro}: {result.bag}")
