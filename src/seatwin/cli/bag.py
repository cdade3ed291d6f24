"""``seatwin bag``: inspect recordings (ours and real ROS 1 / rosbag2 SQLite3 / MCAP bags)."""

from __future__ import annotations

from pathlib import Path

import typer


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
