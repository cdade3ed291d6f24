"""``seatwin camera``: the RGB camera rig (thesis 3.2.1, 4.2.1) — snapshots of a scenario with ground-truth boxes."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.flags import either, old_spelling
from seatwin.cli.output import overwrite_option

_SNAPSHOT_HELP = (
    "Render the three frontal cameras (left, front, right: 72° apart, 15° down, 82° HFOV, 612 × 512) of a "
    "scenario's ownship at one time and write <camera>.png into DIR with every vessel's ground-truth box drawn "
    "(label: vessel name and visible fraction). Rendering: OpenGL through a headless EGL context."
)


def register(app: typer.Typer) -> None:
    group = typer.Typer(help="The RGB camera rig: snapshots with ground-truth boxes.", no_args_is_help=True)
    app.add_typer(group, name="camera")

    @group.command("snapshot", help=_SNAPSHOT_HELP)
    def snapshot_cmd(
        scenario: str = typer.Argument(..., metavar="SCENARIO", help="A built-in scenario name or a scenario file."),
        time_s: float = typer.Option(0.0, "--offset", "-t", help="Seconds after the scenario's start."),
        time_old: float | None = old_spelling("--time", "--offset"),
        out: Path = typer.Option(..., "--out", "-o", metavar="DIR", help="Directory for left.png, front.png, right.png."),
        no_boxes: bool = typer.Option(False, "--no-boxes", help="Write the images without the boxes."),
        harbour: str | None = typer.Option(
            None,
            "--harbour",
            help="Harbour instead of the scenario's own: 'default', 'ravnkloa' (a Gemini CSV's default), 'none' "
            "or a land raster .bin/.yaml.",
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.errors import ParameterError
        from seatwin.pipeline.labels import camera_snapshot

        time_s = either(time_s, time_old, 0.0, "--offset", "--time")
        try:
            snap = camera_snapshot(scenario, time_s, out, boxes=not no_boxes, harbour=harbour, overwrite=overwrite)
        except ParameterError as exc:  # the library's ``time`` (seconds after the start) is this verb's --offset
            raise ParameterError("--offset", exc.detail) if exc.param == "time" else exc from None
        for path in snap.files:
            labels = snap.labels[path.stem]
            names = ", ".join(f"{b.instance} ({b.visible_fraction:.2f} visible)" for b in labels) or "no vessel"
            typer.echo(f"{path}: {names}")
