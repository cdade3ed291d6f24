"""``seatwin lidar``: simulate the ownship's lidar (VLP-16 on milliAmpere's rig) along a scenario; fit it to a recording."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.flags import either, old_spelling
from seatwin.cli.output import overwrite_option


def register(app: typer.Typer) -> None:
    lidar_app = typer.Typer(
        help="Simulate the ownship's lidar along a scenario; fit its model to a recording.", no_args_is_help=True
    )
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

    register_fit(lidar_app)


_FIT_HELP = (
    "Fit the lidar model's range noise σ, ray-drop probability and range dissipation to a recording with ground truth, "
    "each with a 95 % interval, by the lidar sensor-level distance of the fidelity score (S7: Pd, points per return, "
    "depth, width and thickness of each target's returns per range band).\n\n"
    "RECORDING is a run directory or bag with a lidar PointCloud2 topic and the ownship's ground truth; SCENARIO the "
    "scenario that made it (default: the one beside it). Candidate models are simulated along it at the recording's "
    "sweep instants and clustered as the recording is; the fit is the candidate nearest to the recording (a coarse "
    "grid, then a refinement of each parameter, and of drop and dissipation together). Intervals: block bootstrap "
    "of the terms. Writes a lidar YAML that 'seatwin simulate --lidar' reads, with the report under 'fit'."
)


def register_fit(lidar_app: typer.Typer) -> None:
    @lidar_app.command("fit", help=_FIT_HELP)
    def fit_cmd(
        recording: Path = typer.Argument(..., metavar="RECORDING", help="Run directory or bag with a lidar topic."),
        out: Path = typer.Option(..., "--out", metavar="LIDAR.yaml", help="Where to write the fitted lidar configuration."),
        scenario: str = typer.Option(
            None, "--scenario", metavar="SCENARIO", help="The scenario that made RECORDING (default: the one beside it)."
        ),
        base: Path = typer.Option(
            None, "--base", metavar="LIDAR.yaml", help="Start from this lidar configuration (default: the VLP-16 preset)."
        ),
        map_spec: str = typer.Option(
            None, "--map", help="Water mask for land returns: 'harbour', 'none' or a raster (default: the recording's)."
        ),
        lidar_mode: str = typer.Option("raycast", "--lidar-mode", help="Range model of the candidates."),
        offset: float = typer.Option(0.0, "--offset", help="Fit from this many seconds after the first sweep."),
        duration: float = typer.Option(20.0, "--duration", help="Fit this many seconds of sweeps."),
        every: int = typer.Option(1, "--every", min=1, help="Use every n-th sweep (a longer span at the same cost)."),
        seeds: int = typer.Option(2, "--seeds", min=1, help="Seeds each candidate is simulated with."),
        rounds: int = typer.Option(2, "--rounds", min=0, help="Rounds of refinement after the coarse grid."),
        boot: int = typer.Option(200, "--boot", min=0, help="Bootstrap resamples for the intervals (0: none)."),
        seed: int = typer.Option(0, "--seed", help="First seed of the candidates and seed of the bootstrap."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.fidelity.lidar_fit import fit_lidar_to_recording
        from seatwin.outputs import check_output_file
        from seatwin.sensors.lidar_config import save_lidar_config

        check_output_file(out, "out", inputs=[recording, scenario, base], overwrite=overwrite)
        fit = fit_lidar_to_recording(
            recording,
            scenario,
            base=base,
            map_spec=map_spec,
            lidar_mode=lidar_mode,
            start_offset=offset,
            duration=duration,
            every=every,
            seeds=seeds,
            rounds=rounds,
            n_boot=boot,
            seed=seed,
        )
        save_lidar_config(fit.config, out, fit.report())
        typer.echo(
            f"fitted {fit.n_sweeps} sweeps of {recording} ({len(fit.candidates)} candidates, lidar distance "
            f"{fit.distance:.3f}) → {out}"
        )
        for key, p in fit.parameters.items():
            ci = p["ci95"]
            typer.echo(f"  {key:<26} {p['estimate']:.4g}" + (f" [{ci[0]:.3g}, {ci[1]:.3g}]" if ci else ""))
