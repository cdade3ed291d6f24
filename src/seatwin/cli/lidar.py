"""``seatwin lidar``: simulate the ownship's lidar (VLP-16 on milliAmpere's rig) along a scenario."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.flags import either, old_spelling
from seatwin.cli.output import overwrite_option


def register(app: typer.Typer) -> None:
    lidar_app = typer.Typer(help="Simulate the ownship's lidar along a scenario.", no_args_is_help=True)
    app.add_typer(lidar_app, name="lidar")

    @lidar_app.command("snapshot")
    def snapshot(
        scenario: str = typer.Argument(..., help="A built-in scenario name, a scenario .yaml or a Gemini .csv."),
        offset: float = typer.Option(0.0, "--offset", "-t", help="Start of the sweep, seconds after the scenario's start."),
        offset_old: float | None = old_spelling("--time", "--offset"),
        out: Path = typer.Option(None, "--out", "-o", help="PNG file to write (required)."),
        output_old: str | None = old_spelling("--output", "--out"),
        preset: str = typer.Option("vlp16", "--lidar-preset", help="Lidar preset: vlp16 (1800 columns) or vlp16-thesis (1024)."),
        preset_old: str | None = old_spelling("--preset", "--lidar-preset"),
        lidar_mode: str = typer.Option(
            "raycast",
            "--lidar-mode",
            help="Lidar range model: raycast (exact), depthbuffer (the thesis's, with the spherical filter), "
            "depthbuffer-legacy (without it) or depthbuffer-plane (rasterised, beam meets the pixel's plane).",
        ),
        lidar_mode_old: str | None = old_spelling("--range-model", "--lidar-mode"),
        ray_drop: float = typer.Option(
            None, "--ray-drop", help="Ray-drop probability (default: the preset's, 0.8 as in the thesis)."
        ),
        ray_drop_old: float | None = old_spelling("--drop", "--ray-drop"),
        extent: float = typer.Option(110.0, "--extent", help="Half-size of the plotted square around the ownship, in metres."),
        harbour: str = typer.Option(
            None,
            "--harbour",
            help="Override the scenario's harbour: 'default', 'ravnkloa', 'none' or a land raster .bin/.yaml.",
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """One lidar sweep seen from above over the harbour, coloured by intensity, with the vessels' outlines."""
        from seatwin.errors import ParameterError
        from seatwin.pipeline.lidar import lidar_snapshot

        time = either(offset, offset_old, 0.0, "--offset", "--time")
        output = either(out, None if output_old is None else Path(output_old), None, "--out", "--output")
        preset = either(preset, preset_old, "vlp16", "--lidar-preset", "--preset")
        range_model = either(lidar_mode, lidar_mode_old, "raycast", "--lidar-mode", "--range-model")
        drop = either(ray_drop, ray_drop_old, None, "--ray-drop", "--drop")
        if output is None:
            raise ParameterError("out", "give the PNG file to write (--out FILE.png)")
        snap = lidar_snapshot(
            scenario,
            time,
            output,
            preset=preset,
            lidar_mode=range_model,
            ray_drop=drop,
            extent=extent,
            harbour=harbour,
            overwrite=overwrite,
        )
        typer.echo(f"wrote {snap.path} ({snap.n_points} points)")
