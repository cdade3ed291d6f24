"""``seatwin sweep``: does AHED rise when the sensor model is deliberately degraded? (fidelity sweep)"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import typer
from typer.core import TyperCommand

from seatwin.cli.output import overwrite_option, split_list
from seatwin.errors import ParameterError

_HELP = (
    "Fidelity sweep: does the fidelity score rank sensor models? A reference lidar model stands in for "
    "reality; copies made by deliberately wrong models — degraded, or cleaner than the reference — are "
    "compared with it through the tracker (fidelity score S5, its lidar sensor-level part S7 — which ranks noise, drop "
    "and sampling but hardly sees a mount error — and AHED, thesis 5.2).\n\n"
    "Per seed s, the reference model (VLP-16 ray casting; REFERENCE) is simulated "
    "with seed s + --reference-seed-offset (the 'real' run) and with seed s, and once per (kind, strength) "
    "with seed s; each is compared with the reference run of the other seed, as any real-versus-synthetic "
    "comparison is (no shared draws). The reference model's own distance is the floor. Kinds: noise "
    "(range σ, m), drop (ray-drop probability), dissipation (off/on), mount (yaw bias, deg; /tf_static keeps "
    "the nominal mount). Every run is a job of the campaign engine (in this process, or on Ray with --workers "
    "/ --address); each job's outcome is kept in --out/jobs, so re-running the command resumes (other "
    "settings in the same --out: refused, or with --overwrite started afresh). Writes "
    "sweep.csv, sweep.json (Spearman ρ of S5, S7 and AHED per kind, direction and seed) and sweep.png into --out."
)


def parse_floats(text: str, param: str) -> tuple[float, ...]:
    """``"0.1,0.2"`` → ``(0.1, 0.2)`` (a ``ParameterError`` naming ``param`` otherwise)."""
    try:
        values = tuple(float(p) for p in text.split(",") if p.strip())
    except ValueError:
        values = ()
    if not values:
        raise ParameterError(param, f"expected comma-separated numbers, got {text!r}")
    return values


def parse_strengths(text: str | None, kinds: Sequence[str]) -> dict[str, tuple[float, ...]]:
    """``"noise=0.1,0.2;mount=1,2"`` → per-kind strengths; a bare list applies to a single kind."""
    if not text:
        return {}
    out: dict[str, tuple[float, ...]] = {}
    for part in (p.strip() for p in text.split(";") if p.strip()):
        if "=" not in part:
            if len(kinds) != 1:
                raise ParameterError("strengths", "with several kinds write KIND=S1,S2;KIND=… (e.g. noise=0.1,0.2;mount=1,2)")
            out[kinds[0]] = parse_floats(part, "strengths")
            continue
        kind, values = (x.strip() for x in part.split("=", 1))
        if kind not in kinds:
            raise ParameterError("strengths", f"{kind!r} is not among the swept kinds {list(kinds)}")
        out[kind] = parse_floats(values, "strengths")
    return out


class _SweepCommand(TyperCommand):
    """``sweep``: the reference model and default strengths are filled into the help from
    :data:`seatwin.sweep.degradations.DEGRADATIONS` (their one source) when the help is shown, so that
    registering the verb does not import the simulator."""

    def format_help(self, ctx: Any, formatter: Any) -> None:
        from seatwin.cli.helptext import escape
        from seatwin.sweep.degradations import describe_reference, describe_strengths

        words = {"REFERENCE": escape(describe_reference()), "STRENGTHS": escape(describe_strengths())}
        for item in [self, *self.params]:
            for key, text in words.items():
                if item.help and key in item.help:
                    item.help = item.help.replace(key, text)
        super().format_help(ctx, formatter)


def _rho_text(r: Any) -> str:
    """A :class:`~seatwin.sweep.results.KindSpearman` as "ρ over every point (per seed min…max)"; – where undefined."""
    if r is None or r.rho_points is None:
        return "–"
    band = "–" if r.seed_min is None else f"{r.seed_min:.2f}…{r.seed_max:.2f}"
    return f"{r.rho_points:.2f} (per seed {band})"


def register(app: typer.Typer) -> None:
    @app.command("sweep", help=_HELP, cls=_SweepCommand)
    def sweep_cmd(
        scenario: str = typer.Argument(
            "ferry_crossing", metavar="SCENARIO", help="Built-in scenario name or scenario file (default ferry_crossing)."
        ),
        out: Path = typer.Option(
            ...,
            "--out",
            metavar="DIR",
            help="Folder for sweep.csv, sweep.json, sweep.png and jobs/ (the same command again resumes a sweep there).",
        ),
        kinds: str = typer.Option(
            "noise,drop,dissipation,mount",
            "--kinds",
            metavar="LIST",
            help="Comma-separated degradations: noise, drop, dissipation, mount.",
        ),
        strengths: str | None = typer.Option(
            None,
            "--strengths",
            metavar="KIND=S,S;…",
            help="Strengths per kind, e.g. 'noise=0,0.2;mount=1,2' (a bare list with one kind), on either side of the "
            "reference (REFERENCE) where the kind allows. Default: STRENGTHS.",
        ),
        seeds: int = typer.Option(
            3, "--seeds", metavar="N", min=1, help="Repeat every point with seeds 1…N and show the spread."
        ),
        duration: float = typer.Option(60.0, "--duration", metavar="S", help="Simulated seconds per run."),
        reference_seed_offset: int = typer.Option(
            1000,
            "--reference-seed-offset",
            metavar="K",
            help="The reference run of seed s uses seed s + K (0: seed-matched, sharing every random draw).",
        ),
        offset: float | None = typer.Option(
            None,
            "--offset",
            metavar="S",
            help="Window start in seconds after the scenario's start (default: the window centred in the scenario).",
        ),
        tuning: str = typer.Option(
            "synthetic",
            "--tuning",
            metavar="NAME|FILE",
            help="Tracker tuning for every run (preset synthetic, real, joyride, or a file).",
        ),
        workers: int = typer.Option(
            0,
            "--workers",
            metavar="N",
            min=0,
            help="0 (default): run in this process; N: on a local Ray instance of N CPUs, or at most N jobs in "
            "flight with --address (results identical).",
        ),
        address: str | None = typer.Option(
            None, "--address", metavar="RAY_ADDRESS", help="Run on this Ray cluster (e.g. ray://head:10001 or auto)."
        ),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.cli.output import progress_counter
        from seatwin.settings import validated
        from seatwin.sweep import SweepSettings, run_sweep, spearman_by_kind, summarise, write_sweep

        chosen = split_list(kinds, "kinds") or ()
        settings = validated(
            SweepSettings,
            {
                "scenario": scenario,
                "kinds": chosen,
                "strengths": parse_strengths(strengths, chosen),
                "seeds": tuple(range(1, seeds + 1)),
                "duration": duration,
                "reference_seed_offset": reference_seed_offset,
                "offset": offset,
                "tuning": tuning,
            },
        )
        with progress_counter("sweep", progress, min_total=1) as advance:
            result = run_sweep(out, settings, workers=workers, address=address, progress=advance, overwrite=overwrite)
        csv_path, json_path, png = write_sweep(out, result)
        sensor_rho = spearman_by_kind(result, "sensor")
        for kind, by_dir in spearman_by_kind(result, "score").items():
            means = ", ".join(
                f"{s.strength:g}: {s.mean:.3f}" if s.mean is not None else f"{s.strength:g}: –"
                for s in summarise(result.kind_rows(kind), "score")
            )
            typer.echo(f"{kind:12s} mean score by strength {means}")
            for direction, r in by_dir.items():
                sensor = _rho_text(sensor_rho[kind].get(direction))
                typer.echo(f"{'':12s} {direction:8s} ρ = {_rho_text(r)}; sensor-level part ρ = {sensor}")
        floor = result.floor("score")
        if floor:
            typer.echo(f"floor (reference model vs the reference run of another seed): mean score {sum(floor) / len(floor):.3f}")
        typer.echo(f"wrote {csv_path}, {json_path}, {png}")
