"""``seatwin scenario``: list the built-ins, summarise, plot and export scenarios."""

from __future__ import annotations

import datetime as dt
import json
import re
from enum import Enum
from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

SPEC_HELP = "A built-in scenario name (see `seatwin scenario list`), a scenario .yaml or a Gemini .csv."
DATE_HELP = "UTC date (YYYY-MM-DD) of a CSV whose times are TimeOfDay."


class TimeFormat(str, Enum):
    posix = "posix"
    time_of_day = "time-of-day"


def _date(text: str | None) -> dt.date | None:
    from seatwin.errors import InputError

    if text is None:
        return None
    try:
        return dt.date.fromisoformat(text)
    except ValueError:
        raise InputError("--date", f"expected YYYY-MM-DD, got {text!r}") from None


def register(app: typer.Typer) -> None:
    group = typer.Typer(help="Scenarios: list the built-ins, summarise, plot and export them.", no_args_is_help=True)
    app.add_typer(group, name="scenario")

    @group.command("list")
    def list_cmd(as_json: bool = typer.Option(False, "--json", help="Print JSON instead of a table.")) -> None:
        """List the built-in scenarios."""
        from seatwin.scenario.builtin import BUILTINS

        rows = [{"name": b.name, "thesis": b.thesis, "description": b.description} for b in BUILTINS.values()]
        if as_json:
            typer.echo(json.dumps(rows, indent=2, ensure_ascii=False))
            return
        from rich.console import Console
        from rich.table import Table

        table = Table(title="Built-in scenarios (default harbour)")
        for col in ("name", "thesis", "description"):
            table.add_column(col)
        for r in rows:
            table.add_row(r["name"], r["thesis"], r["description"])
        Console().print(table)

    @group.command("info")
    def info_cmd(
        spec: str = typer.Argument(..., help=SPEC_HELP, metavar="FILE_OR_NAME"),
        as_json: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
        date: str | None = typer.Option(None, "--date", help=DATE_HELP),
    ) -> None:
        """Summarise a scenario: vessels, span, rate, speeds, closest approaches; warn of vessels on land."""
        from seatwin.scenario.load import load_scenario
        from seatwin.scenario.on_water import warn_on_land
        from seatwin.scenario.summary import scenario_summary

        sc = load_scenario(spec, date=_date(date))
        warn_on_land(sc, sc.environment.get("harbour", "default"))
        summary = scenario_summary(sc)
        if as_json:
            typer.echo(json.dumps(summary, indent=2, ensure_ascii=False))
            return
        _print_summary(summary)

    @group.command("plot")
    def plot_cmd(
        spec: str = typer.Argument(..., help=SPEC_HELP, metavar="FILE_OR_NAME"),
        out: Path = typer.Option(..., "-o", "--out", help="PNG file to write.", dir_okay=False),
        date: str | None = typer.Option(None, "--date", help=DATE_HELP),
        tick: float = typer.Option(10.0, "--tick", min=0.1, help="Mark each track every TICK seconds."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Plot the tracks (circle: start, star: end) over the harbour, like thesis Fig. 3.11."""
        from seatwin.outputs import check_output_file
        from seatwin.scenario.load import load_scenario
        from seatwin.scenario.plot import plot_scenario

        scenario = load_scenario(spec, date=_date(date))
        check_output_file(out, "out", inputs=[spec, *scenario.files], overwrite=overwrite)
        path = plot_scenario(scenario, out, tick_s=tick)
        typer.echo(f"wrote {path}")

    @group.command("export")
    def export_cmd(
        spec: str = typer.Argument(..., help=SPEC_HELP, metavar="NAME"),
        out_dir: Path = typer.Option(..., "--out", help="Directory to write NAME.yaml and NAME.csv into.", file_okay=False),
        time_format: TimeFormat = typer.Option(TimeFormat.posix, "--time-format", help="Time column of the CSV."),
        date: str | None = typer.Option(None, "--date", help=DATE_HELP),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Write a scenario as a YAML file and its Gemini CSV."""
        from seatwin.outputs import check_output_folder
        from seatwin.scenario.load import load_scenario, save_scenario

        scenario = load_scenario(spec, date=_date(date))
        fmt = "posix" if time_format == TimeFormat.posix else "time_of_day"
        stem = re.sub(r"[^\w.-]+", "_", scenario.name).strip("._") or "scenario"
        names = [f"{stem}.yaml", f"{stem}.csv"]
        check_output_folder(out_dir, "out", names, inputs=[spec, *scenario.files], overwrite=overwrite)
        yaml_path, csv_path = save_scenario(scenario, out_dir / f"{stem}.yaml", time_format=fmt)
        typer.echo(f"wrote {yaml_path}\nwrote {csv_path}")


def _print_summary(s: dict) -> None:  # type: ignore[type-arg]
    """The summary as plain text: nothing cut to the terminal's width, the environment as ``key value`` words."""
    from seatwin.cli.output import text_table

    env = s["environment"]
    environment = ", ".join(f"{k} {v}" for k, v in env.items()) if isinstance(env, dict) else str(env)
    typer.echo(f"{s['name'] or '(unnamed scenario)'}  {s['description']}".rstrip())
    typer.echo(
        f"source {s['source']}\nstart {s['start_utc']} ({s['start']:.3f}), duration {s['duration_s']:.1f} s, "
        f"{s['rate_hz']:g} Hz, environment: {environment}, rig {s['rig']}, seed {s['seed']}"
    )
    water = any(v["on_water"] is not None for v in s["vessels"])
    cols = ["name", "role", "model", "samples", "min speed", "mean", "max", "distance_m"] + (["on water"] if water else [])
    rows = []
    for v in s["vessels"]:
        sp = v["speed_mps"]
        row = [v["name"], v["role"], v["model"], str(v["samples"]), f"{sp['min']:.2f}", f"{sp['mean']:.2f}", f"{sp['max']:.2f}"]
        row.append(f"{v['distance_m']:.1f}")
        if water:
            row.append("–" if v["on_water"] is None else f"{100 * v['on_water']:.0f} %")
        rows.append(row)
    typer.echo("\n" + text_table(cols, rows, left=3, title="Vessels (speed in m/s)"))
    approach = [
        [f"{p['a']} – {p['b']}", f"{p['distance_m']:.1f}", f"{p['time_from_start_s']:.1f}"] for p in s["closest_approach"]
    ]
    title = "Closest approach (at_s: seconds from the start)"
    typer.echo("\n" + text_table(["vessels", "distance_m", "at_s"], approach, title=title))
