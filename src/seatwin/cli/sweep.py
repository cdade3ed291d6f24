"""``seatwin sweep``: does AHED rise when the sensor model is deliberately degraded? (fidelity sweep)"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import typer

from seatwin.cli.output import split_list
from seatwin.errors import ParameterError

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


def register(app: typer.Typer) -> None:
    @app.command("sweep", help=_HELP)
    def sweep_cmd(
        scenario: str = typer.Argument(
            "ferry_crossing", metavar="[SCENARIO]", help="Built-in scenario name or scenario file (default ferry_crossing)."
        ),
        out: Path = typer.Option(
            ...,
            "--out",
            metavar="DIR",
            help="Folder for sweep.csv, sweep.json, sweep.png and tracks/ (must not hold an earlier sweep).",
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
            help="Strengths per kind, e.g. 'noise=0.05,0.2;mount=1,2' (a bare list with one kind). Default: noise "
            "0.05,0.1,0.2,0.4 m; drop 0.85,0.9,0.95,0.98; dissipation 1; mount 0.5,1,2,4 deg.",
        ),
        seeds: int = typer.Option(
            3, "--seeds", metavar="N", min=1, help="Repeat every point with seeds 1…N and show the spread."
        ),
        duration: float = typer.Option(30.0, "--duration", metavar="S", help="Simulated seconds per run."),
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
        keep_recordings: bool = typer.Option(
            False, "--keep-recordings", help="Keep every simulated recording under DIR/recordings (large)."
        ),
        progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar."),
    ) -> None:
        from seatwin.cli.output import check_output_dir, progress_counter
        from seatwin.settings import validated
        from seatwin.sweep import SweepSettings, plot_sweep, run_sweep, spearman_by_kind, summarise, write_results

        chosen = split_list(kinds, "kinds") or ()
        settings = validated(
            SweepSettings,
            {
                "scenario": scenario,
                "kinds": chosen,
                "strengths": parse_strengths(strengths, chosen),
                "seeds": tuple(range(1, seeds + 1)),
                "duration": duration,
                "offset": offset,
                "tuning": tuning,
                "keep_recordings": keep_recordings,
            },
        )
        check_output_dir(out, "out")
        total, done = settings.n_steps(), 0
        with progress_counter("sweep", progress, min_total=1) as advance:

            def step(_name: str) -> None:
                nonlocal done
                done += 1
                advance(done, total)

            result = run_sweep(out, settings, step=step)
        csv_path, json_path = write_results(out, result)
        png = plot_sweep(result, out / "sweep.png")
        for kind, rho in spearman_by_kind(result).items():
            means = ", ".join(
                f"{s.strength:g}: {s.ahed_mean:.3f}" if s.ahed_mean is not None else f"{s.strength:g}: –"
                for s in summarise(result.kind_rows(kind))
            )
            r = rho.rho_points
            typer.echo(f"{kind:12s} ρ = {r:.2f}  " if r is not None else f"{kind:12s} ρ = –     ", nl=False)
            typer.echo(f"mean AHED by strength {means}")
        mean, top = result.floor_mean_max()
        if mean is not None:
            typer.echo(f"seed-to-seed AHED: mean {mean:.3f}, max {top:.3f}")
        typer.echo(f"wrote {csv_path}, {json_path}, {png}")
