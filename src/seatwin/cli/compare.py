"""``seatwin compare``: a real and a synthetic dataset compared through the tracker (thesis 5.2)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

_HELP = (
    "Compare a real and a synthetic dataset by the Hellinger distance of the tracker's estimates "
    "(thesis 5.2.1).\n\n"
    "Both runs are associated with the same ground truth; at every instant where both have the "
    "target (instants matched within --time-tolerance) HED (5.30) and COVDIFF (5.31) are computed, "
    "and AHED (5.34) averages HED over those instants. Instants where only one dataset has the "
    "target are counted beside AHED (AHED cannot see track loss). --real/--synthetic are track "
    "files (.csv) or recordings (tracked first by 'seatwin track' with each --tuning, or with the "
    "recording's suggested tuning when none is given). Several tunings give the "
    "thesis's per-tuning table: with track files, give one --real/--synthetic pair per tuning, in "
    "the same order."
)


def _pairs(real: list[str], synthetic: list[str], tunings: list[str]) -> list[tuple[str, str, str | None, str]]:
    """(real, synthetic, tuning, label) per comparison; track files are used as given, recordings tracked per tuning."""
    from seatwin.errors import InputError
    from seatwin.evaluation.runs import TRACK_FILE_SUFFIXES

    if len(real) != len(synthetic):
        raise InputError("--real/--synthetic", f"give as many --real as --synthetic, got {len(real)} and {len(synthetic)}")
    is_file = [Path(p).suffix.lower() in TRACK_FILE_SUFFIXES for p in real + synthetic]
    if len(real) == 1 and len(tunings) > 1:
        if any(is_file):
            raise InputError("--tuning", f"{len(tunings)} tunings but a track file was already tracked with one tuning; "
                                         "give one --real/--synthetic pair per tuning, or recordings")
        return [(real[0], synthetic[0], t, t) for t in tunings]
    if tunings and len(tunings) != len(real):
        raise InputError("--tuning", f"{len(tunings)} tunings for {len(real)} --real/--synthetic pairs")
    if tunings:
        return [(r, s, t, t) for r, s, t in zip(real, synthetic, tunings)]
    labels = [""] if len(real) == 1 else [f"pair{i + 1}" for i in range(len(real))]
    return [(r, s, None, label) for r, s, label in zip(real, synthetic, labels)]


def load_run(spec: str, tuning: str | None):  # noqa: ANN201
    """A track file as is, or a recording tracked by ``seatwin track`` with ``tuning`` (its defaults otherwise)."""
    import tempfile

    from seatwin.errors import InputError
    from seatwin.evaluation import read_tracks
    from seatwin.evaluation.runs import TRACK_FILE_SUFFIXES

    path = Path(spec)
    if path.suffix.lower() in TRACK_FILE_SUFFIXES:
        return read_tracks(path)
    if not path.exists():
        raise InputError(path, "no such track file (.csv) or recording")
    from seatwin.cli.main import app

    with tempfile.TemporaryDirectory(prefix="seatwin-compare-") as tmp:
        out = Path(tmp) / "tracks.csv"
        args = ["track", str(path), "--out", str(out), "--no-progress"] + (["--tuning", tuning] if tuning else [])
        typer.main.get_command(app).main(args, prog_name="seatwin", standalone_mode=False)
        tracks = read_tracks(out)
    tracks.source = f"{path} (tracked, tuning {tuning or 'the recording default'})"
    return tracks


def _clouds(real: str, synthetic: str, when: str, sensor: str, truth):  # noqa: ANN001, ANN202
    """Fig. 5.10 input: both recordings' clouds nearest ``when`` (POSIX seconds or ``+S`` after the truth's start)."""
    from seatwin.errors import InputError
    from seatwin.evaluation.runs import TRACK_FILE_SUFFIXES
    from seatwin.report import Clouds
    from seatwin.report.clouds import cloud_at

    for spec in (real, synthetic):
        if Path(spec).suffix.lower() in TRACK_FILE_SUFFIXES:
            raise InputError("--clouds-at", f"{spec} is a track file; point clouds need recordings for --real and --synthetic")
    try:
        t = float(when)
    except ValueError:
        raise InputError("--clouds-at", f"expected POSIX seconds or +SECONDS, got {when!r}") from None
    if when.strip().startswith("+"):
        t += min(tr.start for tr in truth.targets.values())
    r, s = cloud_at(real, t, sensor), cloud_at(synthetic, t, sensor)
    return Clouds(r.time, r.points, s.points, r.ownship, r.targets)


def register(app: typer.Typer) -> None:
    @app.command("compare", help=_HELP)
    def compare_cmd(
        real: list[str] = typer.Option(..., "--real", metavar="TRACKS.csv|RECORDING", help="The real dataset's track file or recording (repeat, paired in order with --synthetic and --tuning)."),
        synthetic: list[str] = typer.Option(..., "--synthetic", metavar="TRACKS.csv|RECORDING", help="The synthetic dataset's track file or recording."),
        truth: str = typer.Option(..., "--truth", metavar="SCENARIO_OR_RECORDING", help="Ground truth used to pick each dataset's track of each target (scenario or recording)."),
        tuning: str = typer.Option("", "--tuning", metavar="NAME[,NAME…]", help="Tracker tuning(s): presets (synthetic, real, joyride) or tuning files; with track files only labels."),
        json_out: Optional[Path] = typer.Option(None, "--json", metavar="OUT.json", help="Write the AHED table as JSON here."),
        report: Optional[Path] = typer.Option(None, "--report", metavar="DIR", help="Write a self-contained HTML report (figures embedded) into this folder."),
        gate: float = typer.Option(10.0, "--gate", metavar="M", help="Track-to-truth association distance (m); the thesis uses 10."),
        time_tolerance: float = typer.Option(0.05, "--time-tolerance", metavar="S", help="Largest time difference (s) at which a real and a synthetic instant are the same instant."),
        hellinger_form: str = typer.Option("standard", "--hellinger-form", metavar="standard|printed", help="HED (5.30): the standard Gaussian Hellinger distance (mean term exp(−NEES/8)), or as printed in the thesis (exp(−NEES/16))."),
        both_missing: str = typer.Option("never", "--both-missing", metavar="never|zero|skip", help="Instants where neither dataset has the target: 'never' skips them but gives AHED 0 to a target neither ever tracked (thesis scenario 7); 'zero' counts each as HED 0; 'skip' always skips."),
        all_tracks: bool = typer.Option(False, "--all-tracks", help="Also associate unconfirmed (tentative) tracks."),
        map_spec: str = typer.Option("harbour", "--map", metavar="harbour|none|RASTER.yaml", help="Land drawn under the report's track plots: the built-in harbour, none, or a land/water raster (Ravnkloa base-map format)."),
        clouds_at: Optional[str] = typer.Option(None, "--clouds-at", metavar="TIME|+SECONDS", help="Add both datasets' point clouds at this time to the report (thesis Fig. 5.10): POSIX seconds, or +S after the ground truth's start. Needs recordings for --real and --synthetic."),
        clouds_sensor: str = typer.Option("lidar", "--clouds-sensor", metavar="lidar|radar", help="Which point clouds --clouds-at shows."),
    ) -> None:
        import json

        from seatwin.cli.evaluate import check_overlap
        from seatwin.errors import InputError
        from seatwin.evaluation import CompareOptions, compare, comparison_table, load_truth

        if hellinger_form not in ("standard", "printed"):
            raise InputError("--hellinger-form", f"expected 'standard' or 'printed', got {hellinger_form!r}")
        if both_missing not in ("never", "zero", "skip"):
            raise InputError("--both-missing", f"expected 'never', 'zero' or 'skip', got {both_missing!r}")
        if not gate > 0:
            raise InputError("--gate", f"must be positive, got {gate}")
        if not time_tolerance >= 0:
            raise InputError("--time-tolerance", f"must be >= 0, got {time_tolerance}")
        if clouds_at is not None and report is None:
            raise InputError("--clouds-at", "the point clouds go into the report: give --report DIR as well")
        if clouds_sensor not in ("lidar", "radar"):
            raise InputError("--clouds-sensor", f"expected 'lidar' or 'radar', got {clouds_sensor!r}")
        tunings = [t.strip() for t in tuning.split(",") if t.strip()]
        options = CompareOptions(gate=gate, confirmed_only=not all_tracks, time_tolerance=time_tolerance,
                                 form=hellinger_form, both_missing=both_missing)  # type: ignore[arg-type]
        truth_set = load_truth(truth)
        comparisons = []
        cache: dict[tuple[str, str | None], object] = {}

        def run_of(spec: str, tun: str | None):  # noqa: ANN202 - a recording used twice is tracked once per tuning
            if (spec, tun) not in cache:
                cache[(spec, tun)] = load_run(spec, tun)
            return cache[(spec, tun)]

        for r, s, t, label in _pairs(real, synthetic, tunings):
            run_r, run_s = run_of(r, t), run_of(s, t)
            check_overlap(run_r, truth_set, r)
            check_overlap(run_s, truth_set, s)
            comparisons.append(compare(run_r, run_s, truth_set, tuning=label, options=options))
        table = comparison_table(comparisons)
        typer.echo(f"{'target':<12} {'tuning':<10} {'AHED':>7} {'common':>6} {'only_r':>6} {'only_s':>6} {'covdiff':>8}")
        for ln in table["targets"]:
            ahed = "-" if ln["ahed"] is None else f"{ln['ahed']:.4f}"
            cd = "-" if ln["mean_covdiff"] is None else f"{ln['mean_covdiff']:.4f}"
            typer.echo(f"{ln['target']:<12} {ln['tuning']:<10} {ahed:>7} {ln['n_common']:>6} {ln['n_only_real']:>6} "
                       f"{ln['n_only_synthetic']:>6} {cd:>8}")
        mean = "-" if table["ahed_mean"] is None else f"{table['ahed_mean']:.4f}"
        typer.echo(f"AHED mean ({hellinger_form} HED): {mean}")
        if json_out is not None:
            json_out.parent.mkdir(parents=True, exist_ok=True)
            json_out.write_text(json.dumps({"real": real, "synthetic": synthetic, "truth": truth, **table}, indent=2) + "\n")
            typer.echo(f"wrote {json_out}")
        if report is not None:
            from seatwin.perception.map_mask import load_mask
            from seatwin.report import write_comparison_report

            clouds = [] if clouds_at is None else [_clouds(real[0], synthetic[0], clouds_at, clouds_sensor, truth_set)]
            page = write_comparison_report(report, comparisons, truth_set, title=f"seatwin compare — {Path(truth).name}",
                                           scenario=Path(truth).stem, mask=load_mask(map_spec), clouds=clouds)
            typer.echo(f"wrote {page}")
