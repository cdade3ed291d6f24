"""``seatwin import``: real datasets → seatwin recordings (joyride radar, Ravnkloa shore radar)."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_JOYRIDE_HELP = (
    "Import the joyride radar dataset (joyride.mat, VIMMJIPDA experiments near Trondheim) as a recording.\n\n"
    "Per scan: the radar plots (rows with inf dropped) as a world-frame radar detection cloud, and ground "
    "truth of the ownship Telemetron (the radar platform) and the target boat. Times stay the dataset's "
    "POSIX seconds, so tracks carry the same times."
)
_RAVNKLOA_HELP = (
    "Import a Ravnkloa shore-radar CSV (scan_time_s,north_m,east_m; radar at north −8 m, east 0 m in the "
    "Fosenkaia NED frame) as a recording. No ground truth of targets; the radar is recorded as a "
    "stationary ownship. Scan times are the file name's date-time read as UTC plus scan_time_s."
)


def register(app: typer.Typer) -> None:
    group = typer.Typer(help="Import real datasets as seatwin recordings.", no_args_is_help=True)
    app.add_typer(group, name="import")

    @group.command("joyride", help=_JOYRIDE_HELP)
    def joyride_cmd(
        mat: Path = typer.Argument(..., metavar="JOYRIDE.mat", help="The joyride .mat file (MATLAB v5)."),
        out: Path = typer.Option(..., "--out", metavar="RUN_DIR", help="New run directory for the recording."),
        fmt: str = typer.Option("mcap", "--format", metavar="FMT", help="Bag format: mcap, sqlite3 or ros1."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.perception.datasets import import_joyride

        summary = import_joyride(mat, out, fmt, overwrite=overwrite)
        typer.echo(f"wrote {out}: {summary}")

    @group.command("ravnkloa-radar", help=_RAVNKLOA_HELP)
    def ravnkloa_cmd(
        csv: Path = typer.Argument(..., metavar="RADAR.csv", help="One Ravnkloa radar-2023 CSV file."),
        out: Path = typer.Option(..., "--out", metavar="RUN_DIR", help="New run directory for the recording."),
        fmt: str = typer.Option("mcap", "--format", metavar="FMT", help="Bag format: mcap, sqlite3 or ros1."),
        map_spec: str = typer.Option(
            None, "--map", metavar="RASTER", help="Land/water raster to suggest to 'seatwin track' (stored in the manifest)."
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.perception.datasets import import_ravnkloa_radar

        summary = import_ravnkloa_radar(csv, out, fmt, map_path=map_spec, overwrite=overwrite)
        typer.echo(f"wrote {out}: {summary}")
