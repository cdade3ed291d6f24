"""``seatwin demo``: the whole loop on built-in data, end to end.

1. the built-in scenarios and their plots;
2. a built-in scenario simulated twice: the exact ray-cast lidar with realistic degradations
   (range noise, range dissipation) as the stand-in for reality, and the thesis's depth-buffer
   lidar as the simulator;
3. the same JIPDA tracker on both, with both thesis tunings;
4. the real-vs-synthetic comparison (AHED, COVDIFF) and the HTML report.
"""

from __future__ import annotations

from pathlib import Path

import typer


def register(app: typer.Typer) -> None:
    @app.command("demo")
    def demo_cmd(
        out: Path = typer.Option(Path("runs/demo"), "--out", help="Folder for everything the demo writes (must not hold an earlier demo)."),
        scenario: str = typer.Option("ferry_crossing", "--scenario", help="Built-in scenario to simulate."),
        duration: float = typer.Option(30.0, "--duration", help="Simulated seconds."),
        seed: int = typer.Option(1, "--seed", help="Seed of every random draw."),
    ) -> None:
        """Run the whole seatwin loop on built-in data and print where the results are."""
        from seatwin.cli.main import run
        from seatwin.errors import InputError
        from seatwin.scenario.builtin import builtin_names

        if (out / "reality").exists() or (out / "simulator").exists():
            raise InputError(out, "an earlier demo is here; remove it or give another --out")
        figures = out / "scenarios"
        figures.mkdir(parents=True, exist_ok=True)
        steps: list[tuple[str, list[str]]] = [
            (f"plot {name}", ["scenario", "plot", name, "-o", str(figures / f"{name}.png")]) for name in builtin_names()
        ]
        common = ["--duration", str(duration), "--seed", str(seed), "--quiet"]
        steps += [
            ("simulate the stand-in for reality (exact ray casting, range noise, range dissipation)",
             ["simulate", scenario, "--out", str(out / "reality"), "--range-noise", "0.05", "--dissipation", *common]),
            ("simulate with the thesis's depth-buffer lidar",
             ["simulate", scenario, "--out", str(out / "simulator"), "--lidar-mode", "depthbuffer", *common]),
            ("track both with the thesis tunings and compare",
             ["compare", "--real", str(out / "reality"), "--synthetic", str(out / "simulator"),
              "--truth", str(out / "reality"), "--tuning", "synthetic,real",
              "--json", str(out / "comparison.json"), "--report", str(out / "report")]),
        ]
        for title, argv in steps:
            typer.secho(f"▶ {title}", bold=True)
            code = run(argv)
            if code != 0:
                raise typer.Exit(code)
        typer.echo("")
        typer.echo(f"scenario plots:  {figures}/")
        typer.echo(f"recordings:      {out / 'reality'}  {out / 'simulator'}  (open with Foxglove, or `seatwin bag info`)")
        typer.echo(f"comparison:      {out / 'comparison.json'}")
        typer.echo(f"report:          {out / 'report' / 'index.html'}")
