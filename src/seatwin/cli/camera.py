"""``seatwin camera``: the RGB camera rig (thesis 3.2.1, 4.2.1) — snapshots of a scenario with ground-truth boxes."""

from __future__ import annotations

from pathlib import Path

import typer

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
        time_s: float = typer.Option(0.0, "--offset", "--time", "-t", help="Seconds after the scenario's start."),
        out: Path = typer.Option(..., "--out", "-o", metavar="DIR", help="Directory for left.png, front.png, right.png."),
        no_boxes: bool = typer.Option(False, "--no-boxes", help="Write the images without the boxes."),
    ) -> None:
        from seatwin.pipeline.labels import camera_snapshot

        snap = camera_snapshot(scenario, time_s, out, boxes=not no_boxes)
        for path in snap.files:
            labels = snap.labels[path.stem]
            names = ", ".join(f"{b.instance} ({b.visible_fraction:.2f} visible)" for b in labels) or "no vessel"
            typer.echo(f"{path}: {names}")
