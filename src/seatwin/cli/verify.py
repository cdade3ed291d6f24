"""``seatwin verify``: an agent's safety over sampled COLREG encounters, in the closed loop, on Ray."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_HELP = (
    "Closed-loop safety verification: the agents of AGENT.yaml (reference: lidar/radar perception and JIPDA feeding "
    "COLREG velocity obstacles; perfect: the same fed ground truth; late: a deliberately late reaction; or your own "
    "agent in another process over gRPC, kind: grpc, see docs/agents.md) sail the "
    "ownship through encounters sampled from COLREG families (head-on, crossing give-way/stand-on, overtaking, "
    "multi), one job per (encounter, agent) on Ray (local by default, a cluster with --address; --workers 0 runs "
    "in this process). Writes DIR/results.csv (one row per run: the encounter, the verdict and its reasons), "
    "DIR/verify.json (failure rates with 95 % intervals, modelled − perfect, the cost), DIR/failure_map.png and "
    "DIR/worst/ (failed runs as scenarios with the sailed path: replay them with seatwin simulate). "
    "Example: docs/examples/verify.yaml."
)


def register(app: typer.Typer) -> None:
    @app.command("verify", help=_HELP)
    def verify_cmd(
        spec: Path = typer.Argument(..., metavar="AGENT.yaml", help="Agents, encounter families, samples, sensor models."),
        out: Path = typer.Option(..., "--out", metavar="DIR", help="Folder for results.csv, verify.json, failure_map.png."),
        address: str | None = typer.Option(None, "--address", metavar="RAY_ADDRESS", help="Run on this Ray cluster."),
        workers: int | None = typer.Option(
            None, "--workers", metavar="N", min=0, help="CPUs of the local Ray instance (default: all); 0 runs in this process."
        ),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar (lines on a pipe)."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.cli.output import progress_counter
        from seatwin.verification.campaign import run_verification

        with progress_counter("verify", progress, min_total=1) as advance:
            result = run_verification(spec, out, address=address, workers=workers, progress=advance, overwrite=overwrite)
        for agent, s in result.summary["agents"].items():
            lo, hi = (100 * x for x in s["interval95"])
            line = f"{agent}: {s['failed']} of {s['runs']} runs fail ({100 * s['rate']:.1f} %, 95 % [{lo:.1f}, {hi:.1f}])"
            if "minus_perfect" in s:
                d = s["minus_perfect"]
                dlo, dhi = (100 * x for x in d["interval95"])
                line += f"; − perfect {100 * d['difference']:+.1f} points [{dlo:+.1f}, {dhi:+.1f}]"
            typer.echo(line)
        cost = result.summary["cost"]
        typer.echo(f"{cost['jobs']} runs, {cost['failed_jobs']} errors, {cost['wall_s']:.1f} s; results in {result.out}")
        for row in result.rows:
            if row.get("error"):
                typer.echo(f"run {row['family']}_{row['index']:04d} ({row['agent']}) failed: {row['error']}", err=True)
