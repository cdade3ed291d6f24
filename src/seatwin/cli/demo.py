"""``seatwin demo``: the whole loop on built-in data, end to end (:func:`seatwin.pipeline.run_demo`)."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option
from seatwin.pipeline.demo import DEMO_OFFSET_S


def register(app: typer.Typer) -> None:
    @app.command("demo")
    def demo_cmd(
        out: Path = typer.Option(
            Path("runs/demo"), "--out", help="Folder for everything the demo writes (an earlier demo there: --overwrite)."
        ),
        scenario: str = typer.Option("ferry_crossing", "--scenario", help="Built-in scenario to simulate."),
        offset: float = typer.Option(
            DEMO_OFFSET_S, "--offset", help="Start this many seconds after the scenario's start (both targets in range)."
        ),
        duration: float = typer.Option(30.0, "--duration", help="Simulated seconds."),
        seed: int = typer.Option(1, "--seed", help="Seed of the stand-in for reality; the simulator uses seed + 1."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Run the whole seatwin loop on built-in data and print where the results are.

        Simulates a built-in scenario twice (seeds N and N + 1) — exact ray casting with range noise and dissipation as the
        stand-in for reality, the thesis's depth-buffer lidar as the simulator — tracks both with both
        thesis tunings, compares them (AHED, COVDIFF, the fidelity score) and writes the HTML report.
        """
        from seatwin.pipeline.demo import run_demo

        result = run_demo(
            out,
            scenario=scenario,
            offset=offset,
            duration=duration,
            seed=seed,
            step=lambda title: typer.secho(f"▶ {title}", bold=True),
            overwrite=overwrite,
        )
        for comparison in result.comparison.comparisons:
            for ln in comparison.targets:
                ahed = "undefined" if ln.ahed is None else f"{ln.ahed:.3f}"
                score = "undefined" if ln.score is None else f"{ln.score:.3f}"
                typer.echo(
                    f"  {ln.target:<12} tuning {ln.tuning:<10} AHED {ahed}  fidelity score {score}  "
                    f"(common instants {ln.n_common})"
                )
                for what, why in (("AHED", ln.ahed_reason), ("fidelity score", ln.score_reason)):
                    if why:
                        typer.echo(f"    {what} undefined: {why}")
        for tuning, sc in result.comparison.table["score_by_tuning"].items():
            o = sc and sc["score"]
            if o and o["value"] is not None:
                typer.echo(f"  overall fidelity score, tuning {tuning}: {o['value']:.3f} [{o['ci_low']:.3f}, {o['ci_high']:.3f}]")
        typer.echo("")
        typer.echo(f"scenario plots:  {result.figures}/")
        typer.echo(f"recordings:      {result.reality}  {result.simulator}  (open with Foxglove, or `seatwin bag info`)")
        typer.echo(f"comparison:      {result.comparison_json}")
        typer.echo(f"report:          {result.report}")
