"""``seatwin campaign``: a grid of scenarios × seeds × synthetic sensor settings × tunings against a reference, on Ray."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_HELP = (
    "Fidelity campaign: every combination of the CAMPAIGN.yaml's scenarios, seeds, synthetic sensor settings "
    "(e.g. lidar_mode, ray_drop, range_noise) and tracker tunings is simulated, tracked and compared with a "
    "reference run (the stand-in for real data, simulated with the reference settings and seed + "
    "reference_seed_offset, never the same draws). Jobs run as Ray tasks: a local Ray instance by default, a "
    "cluster with --address. Writes DIR/results.csv (one row per job, tuning and target: the fidelity score, "
    "AHED, n_common…), DIR/campaign.json (engine, grid, timings) and DIR/jobs/ (one file per finished job: a "
    "re-run skips them, so an interrupted campaign resumes; jobs that other seatwin code ran run again). DIR "
    "remembers the campaign (DIR/campaign-spec.json): a different CAMPAIGN.yaml (or a changed scenario file) "
    "is refused there, or with --overwrite starts afresh. Example: docs/examples/campaign.yaml."
)


def register(app: typer.Typer) -> None:
    @app.command("campaign", help=_HELP)
    def campaign_cmd(
        spec: Path = typer.Argument(..., metavar="CAMPAIGN.yaml", help="The campaign: scenarios, seeds, duration, synthetic, …"),
        out: Path = typer.Option(..., "--out", metavar="DIR", help="Folder for results.csv, campaign.json and jobs/."),
        address: str | None = typer.Option(
            None, "--address", metavar="RAY_ADDRESS", help="Run on this Ray cluster (e.g. ray://head:10001 or auto)."
        ),
        workers: int | None = typer.Option(
            None,
            "--workers",
            metavar="N",
            min=0,
            help="CPUs of the local Ray instance (default: all); with --address, the most jobs in flight; "
            "0 runs the jobs in this process, one by one.",
        ),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar (lines on a pipe)."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.campaign import run_campaign
        from seatwin.cli.output import progress_counter

        with progress_counter("campaign", progress, min_total=1) as advance:
            result = run_campaign(spec, out, address=address, workers=workers, progress=advance, overwrite=overwrite)
        run = result.report.describe()
        where = f"on Ray at {run['address']}" if run["address"] else ("on local Ray" if run["engine"] == "ray" else "in process")
        typer.echo(
            f"{run['jobs']} jobs {where}: {run['run']} run, {run['cached']} already done, {result.n_failed} failed; "
            f"{run['wall_s']:.1f} s"
        )
        for job in result.grid.jobs:
            record = result.report.records[job.id]
            if not record.ok:
                typer.echo(
                    f"job {job.id} ({job.params['kind']}, {job.params['scenario']}, seed {job.params['seed']}) failed: "
                    f"{record.error}",
                    err=True,
                )
        if result.summary:
            typer.echo(_summary_table(result.summary))
        wrote = [f"{result.csv_path} ({len(result.rows)} rows)", str(result.json_path)]
        typer.echo("wrote " + ", ".join([*wrote, *([str(result.png_path)] if result.png_path else [])]))
        if result.n_failed:
            raise typer.Exit(1)


def _summary_table(summary: list) -> str:  # type: ignore[type-arg]
    """Per scenario, setting and tuning: the fidelity score (mean over seeds, min–max), coverage, false tracks."""
    from seatwin.cli.output import text_table

    def num(x: float | None, spec: str = ".3f") -> str:
        return "–" if x is None else format(x, spec)

    rows = [
        [
            s.scenario,
            s.setting,
            s.tuning,
            str(s.seeds),
            num(s.score),
            "–" if s.score_min is None else f"{s.score_min:.3f}…{s.score_max:.3f}",
            num(s.coverage, ".0%"),
            f"{num(s.false_tracks_synthetic, '.1f')} / {num(s.false_tracks_real, '.1f')}",
            str(s.failed) if s.failed else "",
        ]
        for s in summary
    ]
    header = ["scenario", "setting", "tuning", "seeds", "score", "over seeds", "coverage", "false tracks s/r", "failed"]
    legend = (
        "score: overall fidelity score against the reference run (0 = indistinguishable), mean and min…max over seeds; "
        "coverage: of the instants where either run tracked a target, the share where both did; false tracks: mean per "
        "run, synthetic / reference"
    )
    return text_table(header, rows, left=3, title="Summary") + "\n" + legend
