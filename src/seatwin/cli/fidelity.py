"""``seatwin fidelity``: the thesis's real-versus-synthetic method (ch. 5.2) on a real dataset."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_JOYRIDE_HELP = (
    "Measure the radar model's fidelity on the joyride dataset (real radar with GNSS ground truth).\n\n"
    "Builds the synthetic replica (ownship and target from the ground truth, the radar model, the same scan "
    "times), runs the same tracker with the same tuning on the real and on each synthetic recording (JIPDA "
    "and a GNN tracker, same EKF), compares them (HED, COVDIFF, AHED, instants where only one has a track) "
    "and writes DIR/fidelity.json, DIR/fidelity.md and the HTML report DIR/index.html. With "
    "--fit-on first-half the radar model is fitted on the first half only and AHED is reported on the "
    "second half (no peeking), with a block-bootstrap 95 % interval and its spread over seeds. Every model is "
    "also given the unpaired fidelity score (error distributions, coverage, clutter, false tracks; 0 = "
    "indistinguishable) and the models are ranked by it; --ablations adds deliberately wrong models derived "
    "from the fitted one (no_bias, wide_noise, low_pd, heavy_clutter, too_clean), which should rank below it. "
    "Beside the score, radar plot-level terms (plots against the GNSS truth: bearing and range bias and σ, Pd by "
    "range, clutter) give real, model and the signed difference with intervals: which parameter is off, which way, "
    "and the smallest error this recording can resolve."
)


def register(app: typer.Typer) -> None:
    group = typer.Typer(help="Real-versus-synthetic fidelity of the sensor models (thesis ch. 5.2).", no_args_is_help=True)
    app.add_typer(group, name="fidelity")

    @group.command("joyride", help=_JOYRIDE_HELP)
    def joyride_cmd(
        mat: Path = typer.Argument(..., metavar="JOYRIDE.mat", help="The joyride dataset (MATLAB v5)."),
        out: Path = typer.Option(..., "--out", metavar="DIR", help="Directory for fidelity.json, fidelity.md and index.html."),
        fit_on: str = typer.Option(
            "none",
            "--fit-on",
            metavar="WHAT",
            help="Fit the radar model on: none (default model), first-half (AHED on the second half) or all.",
        ),
        seeds: int = typer.Option(5, "--seeds", min=1, help="Synthetic recordings (seeds) to compare with the real one."),
        tuning: str = typer.Option(
            "joyride", "--tuning", metavar="NAME|FILE", help="Tracker tuning used on both datasets (preset or tuning file)."
        ),
        radar: Path = typer.Option(
            None, "--radar", metavar="RADAR.yaml", help="Radar configuration to start from (default: built-in)."
        ),
        clutter: str = typer.Option("uniform", "--clutter", help="Clutter form of the fit: uniform or map."),
        agents: str = typer.Option(
            "jipda,gnn", "--agents", metavar="A[,B]", help="Trackers: jipda and/or gnn (the first is the headline)."
        ),
        boot: int = typer.Option(1000, "--boot", min=10, help="Bootstrap resamples of the AHED interval."),
        fit_boot: int = typer.Option(200, "--fit-boot", min=0, help="Bootstrap resamples of the radar fit."),
        fit_by: str = typer.Option(
            "moments",
            "--fit-by",
            metavar="HOW",
            help="Fit the radar by: moments (plot statistics) or score (then matched in the radar sensor score's own "
            "statistics by simulation, as 'seatwin radar fit --by-score').",
        ),
        seed: int = typer.Option(0, "--seed", help="First seed (seeds are SEED … SEED+N−1)."),
        calibrate_bias: bool = typer.Option(
            False,
            "--calibrate-bias",
            help="Give the tracker (on both datasets) the fitted bearing bias as its radar calibration (needs --fit-on).",
        ),
        ablations: bool = typer.Option(
            False,
            "--ablations",
            help="Also score wrong radar models derived from the fitted one: no_bias, wide_noise, low_pd, "
            "heavy_clutter, too_clean (needs --fit-on).",
        ),
        dont_care: bool = typer.Option(
            True,
            "--dont-care/--no-dont-care",
            help="Leave plots and tracks near the boats without ground truth out of the score's clutter and false-track "
            "terms (both datasets); --no-dont-care counts them.",
        ),
        html: bool = typer.Option(True, "--html/--no-html", help="Also write the HTML report (index.html)."),
        workers: int = typer.Option(
            0,
            "--workers",
            metavar="N",
            min=0,
            help="0 (default): simulate the seeds in this process; N: on a local Ray instance of N CPUs (same results).",
        ),
        address: str | None = typer.Option(
            None, "--address", metavar="RAY_ADDRESS", help="Simulate the seeds on this Ray cluster (e.g. ray://head:10001)."
        ),
        progress: bool = typer.Option(
            True, "--progress/--no-progress", help="Progress bar (a line every 10 s when not a terminal)."
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.campaign.folder import claim_experiment_folder
        from seatwin.cli.output import progress_counter, split_list
        from seatwin.fidelity import FidelityOptions, run_fidelity, write_fidelity
        from seatwin.settings import validated

        opts = validated(
            FidelityOptions,
            {
                "tuning": tuning,
                "fit_on": fit_on,
                "seeds": seeds,
                "n_boot": boot,
                "fit_boot": fit_boot,
                "fit_by": fit_by,
                "radar": str(radar) if radar else None,
                "clutter": clutter,
                "agents": split_list(agents, "agents"),
                "seed0": seed,
                "calibrate_bias": calibrate_bias,
                "ablations": ablations,
                "dont_care": dont_care,
            },
        )
        claim_experiment_folder(
            out,
            "out",
            kind="fidelity",
            settings={**opts.model_dump(mode="json"), "html": html},
            files=[str(mat), None if radar is None else str(radar), tuning],
            source=str(mat),
            outputs=("fidelity.json", "fidelity.md", "index.html", "jobs"),
            overwrite=overwrite,
        )
        with progress_counter("fidelity (seeds × models)", progress, min_total=1) as advance:
            result = run_fidelity(str(mat), opts, jobs_in=out, workers=workers, address=address, progress=advance)
        paths = write_fidelity(out, result, html=html)

        def num(x: float | None) -> str:
            return "–" if x is None or x != x else f"{x:.3f}"

        def count(x: float) -> str:  # a mean over seeds: an integer unless the seeds differ
            return f"{x:.0f}" if float(x).is_integer() else f"{x:.1f}"

        prim = result.primary
        lo, hi = prim.ahed_ci
        typer.echo(
            f"AHED {num(prim.ahed)} [{num(lo)}, {num(hi)}] ({result.primary_model} radar model, "
            f"{result.primary_agent}, fit on {result.fit_on}, {result.seeds} seed{'s' if result.seeds != 1 else ''}; "
            f"instants per seed: common {count(prim.n_common)}, only real {count(prim.n_only_real)}, "
            f"only synthetic {count(prim.n_only_synthetic)})"
        )
        typer.echo(
            "AHED per model and tracker; floor: AHED between the model's own replicas of seeds s and s + 1 (what "
            "independent noise alone gives" + ("; needs --seeds 2 or more, – with one seed)" if result.seeds < 2 else ")")
        )
        for label, m in result.models.items():
            for agent, d in m.agents.items():
                typer.echo(f"  {label:<13} {agent:<6} AHED {num(d.ahed)}  floor {num(d.floor_ahed)}")
        typer.echo(f"ranking by fidelity score ({result.primary_agent}; lower is closer to the real data):")
        for k, r in enumerate(result.ranking(), 1):
            score = f"{num(r['score'])} [{num(r['ci_low'])}, {num(r['ci_high'])}]" if r["score"] is not None else "refused"
            why = f"  ({r['reason']})" if r["reason"] else ""
            typer.echo(f"  {k}. {r['model']:<13} score {score}  AHED {num(r['ahed'])}{why}")
        ranked = [r for r in result.ranking() if r["score"] is not None]
        if len(ranked) > 1 and ranked[0]["ci_high"] is not None and ranked[1]["score"] <= ranked[0]["ci_high"]:
            typer.echo(
                f"  {ranked[0]['model']} and {ranked[1]['model']} are not told apart: {ranked[1]['model']}'s score lies "
                f"inside {ranked[0]['model']}'s 95 % interval (more --seeds narrow the intervals)"
            )
        typer.echo("wrote " + ", ".join(str(p) for p in paths.values()))
