"""``seatwin sweep``: does AHED rise when the sensor model is deliberately degraded? (fidelity sweep)"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

_HELP = (
    "Fidelity sweep: compare a reference synthetic dataset with copies made by deliberately degraded "
    "lidar models at increasing strength, through the tracker and AHED (thesis 5.2).\n\n"
    "Per seed, the scenario is simulated once with the reference model (VLP-16 preset, exact ray casting) "
    "and once per (kind, strength) with a degraded one; each copy is compared with the reference run of the "
    "same seed (shared random draws, so only the degradation differs). References of different seeds are "
    "compared too: the seed-to-seed band shows how large a difference random draws alone make. Kinds: "
    "noise (range σ, m), drop (ray-drop probability), dissipation (off/on), mount (yaw bias, deg; "
    "/tf_static keeps the nominal mount). Writes sweep.csv, sweep.json (with Spearman ρ per kind), "
    "sweep.png and the track files into --out."
)


def register(app: typer.Typer) -> None:
    @app.command("sweep", help=_HELP)
    def sweep_cmd(
        scenario: str = typer.Argument("ferry_crossing", metavar="[SCENARIO]", help="Built-in scenario name or scenario file (default ferry_crossing)."),
        out: Path = typer.Option(..., "--out", metavar="DIR", help="Folder for sweep.csv, sweep.json, sweep.png and tracks/ (must not hold an earlier sweep)."),
        kinds: str = typer.Option("noise,drop,dissipation,mount", "--kinds", metavar="LIST", help="Comma-separated degradations: noise, drop, dissipation, mount."),
        strengths: Optional[str] = typer.Option(None, "--strengths", metavar="KIND=S,S;…", help="Strengths per kind, e.g. 'noise=0.05,0.2;mount=1,2' (a bare list with one kind). Default: noise 0.05,0.1,0.2,0.4 m; drop 0.85,0.9,0.95,0.98; dissipation 1; mount 0.5,1,2,4 deg."),
        seeds: int = typer.Option(3, "--seeds", metavar="N", help="Repeat every point with seeds 1…N and show the spread."),
        duration: float = typer.Option(30.0, "--duration", metavar="S", help="Simulated seconds per run."),
        offset: Optional[float] = typer.Option(None, "--offset", metavar="S", help="Window start in seconds after the scenario's start (default: the window centred in the scenario)."),
        tuning: str = typer.Option("synthetic", "--tuning", metavar="NAME|FILE", help="Tracker tuning for every run (preset synthetic, real, joyride, or a file)."),
        keep_recordings: bool = typer.Option(False, "--keep-recordings", help="Keep every simulated recording under DIR/recordings (large)."),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar."),
    ) -> None:
        import sys

        from seatwin.errors import InputError
        from seatwin.sweep import SweepSettings, parse_kinds, plot_sweep, run_sweep, write_results
        from seatwin.sweep.results import result_table
        from seatwin.sweep.runner import parse_strengths

        if seeds < 1:
            raise InputError("--seeds", f"expected at least 1 seed, got {seeds}")
        chosen = parse_kinds(kinds)
        settings = SweepSettings(scenario, tuple(chosen), parse_strengths(strengths, chosen),
                                 seeds=tuple(range(1, seeds + 1)), duration=duration, offset=offset, tuning=tuning)
        settings.check()
        bar = None
        if progress and sys.stderr.isatty():
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            bar = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                           console=Console(stderr=True), transient=True)
            bar.start()
            task = bar.add_task("sweep", total=settings.n_steps())
        try:
            result = run_sweep(settings, out, step=(lambda name: bar.update(task, advance=1, description=name)) if bar else None)
        finally:
            if bar is not None:
                bar.stop()
        csv_path, json_path = write_results(out, result)
        png = plot_sweep(result, out / "sweep.png")
        table = result_table(result)
        for kind, r in table["spearman"].items():
            means = ", ".join(f"{s['strength']:g}: {s['ahed_mean']:.3f}" if s["ahed_mean"] is not None else f"{s['strength']:g}: –"
                              for s in table["summary"][kind])
            rho = r["rho_points"]
            typer.echo(f"{kind:12s} ρ = {rho:.2f}  " if rho is not None else f"{kind:12s} ρ = –     ", nl=False)
            typer.echo(f"mean AHED by strength {means}")
        floor = table["seed_to_seed_floor"]
        if floor["mean"] is not None:
            typer.echo(f"seed-to-seed AHED: mean {floor['mean']:.3f}, max {floor['max']:.3f}")
        typer.echo(f"wrote {csv_path}, {json_path}, {png}")
