"""``seatwin radar``: fit the radar model to a real recording; simulate it along a scenario."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_FIT_HELP = (
    "Fit the radar model's parameters to a real recording's statistics, each with its uncertainty.\n\n"
    "RECORDING is joyride.mat (ground truth inside) or a seatwin recording with a radar topic "
    "(e.g. from 'seatwin import joyride'; ground truth from --truth or the recording). Fitted: range and "
    "bearing bias and noise of plots about the truth, the detection model (Swerling I, SNR ∝ area/R⁴) from "
    "the detection rate against range, and the clutter density (uniform or a world map). Uncertainty: "
    "bootstrap over scans (standard error and 95 % interval). Writes a radar YAML with the report under 'fit'."
)
_SIM_HELP = (
    "Simulate the radar along a scenario (built-in name or file) in its harbour, in the same simulation loop as "
    "'seatwin simulate --sensors radar': plots per rotation "
    "(CSV time,north,east,range_m,azimuth_rad,kind,object_id) or, with --out-bag, a recording with the "
    "plots on a radar topic. Bit-identical for the same --seed."
)


def register(app: typer.Typer) -> None:
    group = typer.Typer(help="The marine radar model: fit it to real data, simulate it.", no_args_is_help=True)
    app.add_typer(group, name="radar")

    @group.command("fit", help=_FIT_HELP)
    def fit_cmd(
        recording: Path = typer.Argument(..., metavar="RECORDING", help="joyride.mat or a recording with radar plots."),
        out: Path = typer.Option(..., "--out", metavar="RADAR.yaml", help="Where to write the fitted radar configuration."),
        truth: str = typer.Option(
            None, "--truth", metavar="SCENARIO", help="Ground truth (scenario file/name or recording); default: from RECORDING."
        ),
        base: Path = typer.Option(
            None, "--base", metavar="RADAR.yaml", help="Start from this radar configuration (default: the built-in one)."
        ),
        gate: float = typer.Option(
            60.0, "--gate", min=1.0, help="A plot within this distance [m] of a target may be the target's."
        ),
        boot: int = typer.Option(200, "--boot", min=0, help="Bootstrap resamples for the uncertainties (0: none)."),
        clutter: str = typer.Option("uniform", "--clutter", help="Clutter form: uniform or map (world-fixed density map)."),
        first_half: bool = typer.Option(False, "--first-half", help="Fit on the first half of the scans only."),
        seed: int = typer.Option(0, "--seed", help="Seed of the bootstrap."),
        by_score: bool = typer.Option(
            False,
            "--by-score",
            help="joyride.mat only: then match the replica's plots to the real ones in the radar sensor score's own "
            "statistics (bias, σ, detection share, clutter per scan), by simulation; parameters with 95 % intervals.",
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.fidelity.radar_fit import fit_radar_to_recording
        from seatwin.outputs import check_output_file
        from seatwin.sensors.radar.config import save_radar_config

        check_output_file(out, "out", inputs=[recording, truth, base], overwrite=overwrite)

        res, obs = fit_radar_to_recording(
            recording,
            truth=truth,
            base=base,
            first_half=first_half,
            gate=gate,
            boot=boot,
            clutter=clutter,
            seed=seed,
            by_score=by_score,
        )
        save_radar_config(res.config, out)
        est = res.report["estimates"]

        def line(key: str, unit: str) -> str:
            e = est[key]
            ci = e["ci95"]
            ci_txt = f" [{ci[0]:.3g}, {ci[1]:.3g}]" if ci and ci[0] == ci[0] else ""
            return f"  {key:<26} {e['estimate']:.4g} {unit} ± {e['se']:.2g}{ci_txt}"

        typer.echo(f"fitted {len(obs)} scans of {recording} → {out}")
        for key, unit in (
            ("range_bias_m", "m"),
            ("range_sigma_m", "m"),
            ("bearing_bias_deg", "°"),
            ("bearing_sigma_deg", "°"),
            ("detection_rate", ""),
            ("snr_ref_db", "dB"),
            ("pd_max", ""),
            ("clutter_density_per_km2", "/km²/scan"),
        ):
            typer.echo(line(key, unit))
        for note in res.report.get("notes", []):
            typer.echo(f"  note: {note}")
        if "score_fit" in res.report:
            sf = res.report["score_fit"]
            typer.echo(f"fitted by the radar sensor score (its value {sf['sensor_score']['score']['value']:.3f}); written:")
            for key, p in sf["parameters"].items():
                ci = p["ci95"]
                ci_txt = f" [{ci[0]:.3g}, {ci[1]:.3g}]" if ci else ""
                typer.echo(f"  {key:<26} {p['estimate']:.4g}{ci_txt}")

    @group.command("simulate", help=_SIM_HELP)
    def simulate_cmd(
        scenario: str = typer.Argument(..., metavar="SCENARIO", help="Built-in scenario name or scenario file."),
        out: Path = typer.Option(None, "--out", metavar="PLOTS.csv", help="CSV of plots to write."),
        out_bag: Path = typer.Option(
            None,
            "--out-bag",
            metavar="RUN_DIR",
            help="New run directory: a recording with the plots on /radar/detections, ground truth and tf.",
        ),
        fmt: str = typer.Option("mcap", "--format", metavar="FMT", help="Bag format of --out-bag: mcap, sqlite3 or ros1."),
        spokes_dir: Path = typer.Option(
            None,
            "--spokes-dir",
            metavar="DIR",
            help="Also write each rotation's raw spokes (Gemini RadarStreamingRequest fields) as DIR/scan_NNNNNN.npz.",
        ),
        config: Path = typer.Option(None, "--radar", metavar="RADAR.yaml", help="Radar configuration (default: built-in)."),
        seed: int = typer.Option(None, "--seed", help="Seed of the random draws (default: the scenario's)."),
        duration: float = typer.Option(
            None, "--duration", help="Simulate only the first SECONDS, more than 0 (rotations in [start, start + SECONDS))."
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.pipeline.radar import simulate_radar

        result = simulate_radar(
            scenario,
            plots_csv=out,
            run_dir=out_bag,
            spokes_dir=spokes_dir,
            radar_config=str(config) if config else None,
            seed=seed,
            duration=duration,
            fmt=fmt,
            overwrite=overwrite,
        )
        typer.echo(f"simulated {result.n_scans} radar scans, {result.n_plots} plots" + "".join(f" → {p}" for p in result.outputs))
