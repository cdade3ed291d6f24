"""``seatwin labels``: the camera images of a run and their ground-truth boxes as a COCO dataset."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_EXPORT_HELP = (
    "Export every camera image of a recording (simulated with --sensors ...,camera) as PNG under DIR/images and "
    "the ground-truth boxes of the labels topics as COCO DIR/annotations.json (category 'vessel'; attributes: "
    "instance = vessel name, visible_fraction, truncation)."
)


def register(app: typer.Typer) -> None:
    group = typer.Typer(help="Ground-truth image labels: export them for detector training.", no_args_is_help=True)
    app.add_typer(group, name="labels")

    @group.command("export", help=_EXPORT_HELP)
    def export_cmd(
        run: Path = typer.Argument(..., metavar="RUN", help="A run directory or bag with camera images."),
        out: Path = typer.Option(..., "--out", "-o", metavar="DIR", help="Output directory (images/ and annotations.json)."),
        min_visible: float = typer.Option(
            0.0, "--min-visible", min=0.0, max=1.0, help="Leave out boxes whose visible fraction is at most this."
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.pipeline.labels import export_coco

        res = export_coco(run, out, min_visible_fraction=min_visible, overwrite=overwrite)
        typer.echo(f"{res.images} images, {res.annotations} boxes: {res.annotations_file}")
