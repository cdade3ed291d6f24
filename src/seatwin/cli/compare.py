"""``seatwin compare``: a real and a synthetic dataset compared through the tracker (thesis 5.2)."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_HELP = (
    "Compare a real and a synthetic dataset by the Hellinger distance of the tracker's estimates "
    "(thesis 5.2.1).\n\n"
    "Both runs are associated with the same ground truth; at every instant where both have the "
    "target (instants matched within --time-tolerance) HED (5.30) and COVDIFF (5.31) are computed, "
    "and AHED (5.34) averages HED over those instants. Instants where only one dataset has the "
    "target are counted beside AHED (AHED cannot see track loss). Beside AHED, the unpaired fidelity score "
    "(docs/fidelity-score.md: error distributions, coverage, clutter, false tracks, lidar cluster shapes; "
    "0 = the same, with a bootstrap interval). --real/--synthetic are track "
    "files (.csv) or recordings (tracked first by 'seatwin track' with each --tuning, or with the "
    "recording's suggested tuning when none is given). Several tunings give the "
    "thesis's per-tuning table: with track files, give one --real/--synthetic pair per tuning, in "
    "the same order."
)


def register(app: typer.Typer) -> None:
    @app.command("compare", help=_HELP)
    def compare_cmd(
        real: list[str] = typer.Option(
            ...,
            "--real",
            metavar="TRACKS.csv|RECORDING",
            help="The real dataset's track file or recording (repeat, paired in order with --synthetic and --tuning).",
        ),
        synthetic: list[str] = typer.Option(
            ..., "--synthetic", metavar="TRACKS.csv|RECORDING", help="The synthetic dataset's track file or recording."
        ),
        truth: str = typer.Option(
            ...,
            "--truth",
            metavar="SCENARIO_OR_RECORDING",
            help="Ground truth used to pick each dataset's track of each target (scenario or recording).",
        ),
        tuning: str = typer.Option(
            "",
            "--tuning",
            metavar="NAME[,NAME…]",
            help="Tracker tuning(s): presets (synthetic, real, joyride) or tuning files; with track files only labels.",
        ),
        json_out: Path | None = typer.Option(None, "--json", metavar="OUT.json", help="Write the AHED table as JSON here."),
        report: Path | None = typer.Option(
            None, "--report", metavar="DIR", help="Write a self-contained HTML report (figures embedded) into this folder."
        ),
        gate: float = typer.Option(
            10.0, "--gate", metavar="M", help="Track-to-truth association distance (m); the thesis uses 10."
        ),
        time_tolerance: float = typer.Option(
            0.05,
            "--time-tolerance",
            metavar="S",
            help="Largest time difference (s) at which a real and a synthetic instant are the same instant.",
        ),
        hellinger_form: str = typer.Option(
            "standard",
            "--hellinger-form",
            metavar="standard|printed",
            help=(
                "HED (5.30): the standard Gaussian Hellinger distance (mean term exp(−NEES/8)), or as printed in the "
                "thesis (exp(−NEES/16))."
            ),
        ),
        both_missing: str = typer.Option(
            "skip",
            "--both-missing",
            metavar="skip|never|zero",
            help=(
                "Instants where neither dataset has the target: 'skip' (default) skips them, so a target without "
                "common instants has AHED undefined and is left out of the means; 'never' skips them but gives AHED 0 "
                "to a target neither ever tracked (the thesis's scenario 7); 'zero' counts each as HED 0."
            ),
        ),
        all_tracks: bool = typer.Option(False, "--all-tracks", help="Also associate unconfirmed (tentative) tracks."),
        map_spec: str = typer.Option(
            "harbour",
            "--map",
            metavar="harbour|ravnkloa|none|RASTER.yaml",
            help=(
                "Land drawn under the report's track plots: the built-in harbour, none, or a land/water raster "
                "(Ravnkloa base-map format)."
            ),
        ),
        clouds_at: str | None = typer.Option(
            None,
            "--clouds-at",
            metavar="TIME|+SECONDS",
            help=(
                "Add both datasets' point clouds at this time to the report (thesis Fig. 5.10): POSIX seconds, or +S "
                "after the ground truth's start. Needs recordings for --real and --synthetic."
            ),
        ),
        clouds_sensor: str = typer.Option(
            "lidar", "--clouds-sensor", metavar="lidar|radar", help="Which point clouds --clouds-at shows."
        ),
        keep_tracks: Path | None = typer.Option(
            None, "--keep-tracks", metavar="DIR", help="Write the track files of tracked recordings into DIR."
        ),
        camera_fusion: bool = typer.Option(
            True,
            "--camera-fusion/--no-camera-fusion",
            help=(
                "Where both recordings have lidar and cameras, also report AHED with lidar alone and with lidar + camera "
                "side by side (thesis Fig. 5.3 vs 5.16) and compare their bounding boxes."
            ),
        ),
        detector: str = typer.Option(
            "label",
            "--detector",
            metavar="label|onnx",
            help="Camera detector: 'label' (the recorded labels) or 'onnx' (a YOLO-style --model on the recorded images).",
        ),
        model: Path | None = typer.Option(None, "--model", metavar="FILE.onnx", help="The onnx detector's model."),
        box_min_iou: float | None = typer.Option(
            None, "--box-min-iou", metavar="IOU", help="Smallest IoU of a matched pair of boxes in the box comparison (0.3)."
        ),
        dont_care: str | None = typer.Option(
            None,
            "--dont-care",
            metavar="FILE",
            help=(
                "Vessels without reliable ground truth (a scenario, truth CSV or recording, e.g. AIS tracks): their "
                "plots and tracks are neither clutter nor false tracks in the fidelity score. Vessels that are "
                "targets of --truth are ignored."
            ),
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        import json

        from seatwin.evaluation import CompareOptions
        from seatwin.outputs import check_output_file, check_output_folder, write_text_atomic
        from seatwin.pipeline.compare import compare_runs

        when, relative = _clouds_time(clouds_at)
        if when is not None and report is None:
            from seatwin.errors import ParameterError

            raise ParameterError("clouds_at", "the point clouds go into the report: give --report DIR as well")
        inputs = [*real, *synthetic, truth, map_spec, model, dont_care, *tuning.split(",")]
        if json_out is not None:
            check_output_file(json_out, "json_out", inputs=inputs, overwrite=overwrite, outputs=[report, keep_tracks])
        if report is not None:
            check_output_folder(report, "report", ["index.html"], inputs=inputs, overwrite=overwrite)
        if keep_tracks is not None:
            earlier = [p.name for pat in ("real_*.csv", "synthetic_*.csv") for p in sorted(keep_tracks.glob(pat))]
            check_output_folder(keep_tracks, "keep_tracks", earlier, inputs=inputs, overwrite=overwrite)
        options = CompareOptions(
            gate=gate,
            confirmed_only=not all_tracks,
            time_tolerance=time_tolerance,
            form=hellinger_form,
            both_missing=both_missing,
        )  # type: ignore[arg-type]
        result = compare_runs(
            real,
            synthetic,
            truth,
            tunings=[t.strip() for t in tuning.split(",") if t.strip()],
            options=options,
            report_dir=report,
            report_map=map_spec,
            clouds_at=when,
            clouds_relative=relative,
            clouds_sensor=clouds_sensor,
            keep_tracks=keep_tracks,
            camera_fusion=camera_fusion,
            detector=detector,
            model=None if model is None else str(model),
            box_min_iou=box_min_iou,
            dont_care=dont_care,
        )
        table = result.table
        if result.dont_care is not None:
            typer.echo(f"don't-care vessels (fidelity score): {', '.join(result.dont_care['vessels'])}")
        typer.echo(
            f"{'target':<12} {'tuning':<10} {'AHED':>9} {'common':>6} {'only_r':>6} {'only_s':>6} {'covdiff':>8} "
            f"{'score [95% CI]':>22}"
        )
        for ln in table["targets"]:
            ahed = "undefined" if ln["ahed"] is None else f"{ln['ahed']:.4f}"
            cd = "-" if ln["mean_covdiff"] is None else f"{ln['mean_covdiff']:.4f}"
            score = (
                "undefined" if ln["score"] is None else f"{ln['score']:.3f} [{ln['score_ci_low']:.3f}, {ln['score_ci_high']:.3f}]"
            )
            typer.echo(
                f"{ln['target']:<12} {ln['tuning']:<10} {ahed:>9} {ln['n_common']:>6} {ln['n_only_real']:>6} "
                f"{ln['n_only_synthetic']:>6} {cd:>8} {score:>22}"
            )
            if ln["ahed"] is None and ln["ahed_reason"]:
                typer.echo(f"  AHED of {ln['target']} undefined: {ln['ahed_reason']}")
            if ln["score"] is None and ln["score_reason"]:
                typer.echo(f"  score of {ln['target']} undefined: {ln['score_reason']}")
        mean = "undefined" if table["ahed_mean"] is None else f"{table['ahed_mean']:.4f}"
        n_all = len(table["targets"])
        typer.echo(
            f"AHED mean ({hellinger_form} HED) over the {table['ahed_n']} of {n_all} target lines where it is defined: {mean}"
        )
        for tun, sc in table["score_by_tuning"].items():
            if sc is None:
                continue
            o = sc["score"]
            value = "undefined" if o["value"] is None else f"{o['value']:.3f} [{o['ci_low']:.3f}, {o['ci_high']:.3f}]"
            why = f" ({o['reason']})" if o["reason"] else ""
            typer.echo(f"fidelity score{' (tuning ' + tun + ')' if tun else ''}: {value}{why}")
            for term in (sc.get("lidar_terms") or {}).values():  # the lidar sensor-level terms the model is off in
                if term["resolved"]:
                    typer.echo(f"  {term['sentence']}")
        for ft in table["false_tracks"]:
            for side in ("real", "synthetic"):
                f = ft[side]
                if f is not None:
                    land = "" if f["n_on_land"] is None else f", {f['n_on_land']} on land"
                    typer.echo(
                        f"false tracks, {side} dataset{' (tuning ' + ft['tuning'] + ')' if ft['tuning'] else ''}: "
                        f"{f['n_tracks']}{land}"
                    )
        if result.camera is not None:
            _print_camera(result.camera)
        for warning in result.warnings:
            typer.echo(f"seatwin: warning: {warning}", err=True)
        for path in result.track_files:
            typer.echo(f"wrote {path}")
        if json_out is not None:
            write_text_atomic(json_out, json.dumps(result.to_json(), indent=2) + "\n")
            typer.echo(f"wrote {json_out}")
        if result.report is not None:
            typer.echo(f"wrote {result.report}")


def _clouds_time(text: str | None) -> tuple[float | None, bool]:
    """``--clouds-at``: POSIX seconds, or ``+S`` seconds after the ground truth's start."""
    if text is None:
        return None, False
    from seatwin.errors import ParameterError

    try:
        value = float(text)
    except ValueError:
        raise ParameterError("clouds_at", f"expected POSIX seconds or +SECONDS, got {text!r}") from None
    return value, text.strip().startswith("+")


def _num(x: float | None, spec: str = ".4f") -> str:
    return "undefined" if x is None else format(x, spec)


def _print_camera(camera: dict) -> None:
    """The camera block: AHED with lidar alone and with lidar + camera per target, then the box comparison."""
    fusion = camera["fusion"]
    typer.echo(f"lidar alone vs lidar + camera (thesis Fig. 5.3 vs 5.16; camera detector {camera['detector']}):")
    if fusion["targets"]:
        typer.echo(f"{'target':<12} {'tuning':<10} {'AHED lidar':>10} {'AHED l+c':>10} {'common':>6} {'common l+c':>10}")
        for ln in fusion["targets"]:
            typer.echo(
                f"{ln['target']:<12} {ln['tuning']:<10} {_num(ln['ahed_lidar']):>10} {_num(ln['ahed_lidar_camera']):>10} "
                f"{ln['n_common_lidar']:>6} {ln['n_common_lidar_camera']:>10}"
            )
        typer.echo(
            f"AHED mean: lidar {_num(fusion['ahed_mean_lidar'])} (n = {fusion['ahed_n_lidar']}), lidar + camera "
            f"{_num(fusion['ahed_mean_lidar_camera'])} (n = {fusion['ahed_n_lidar_camera']})"
        )
    for why in camera["skipped"]:
        typer.echo(f"  not compared: {why}")
    for boxes in camera["boxes"]:
        typer.echo(f"bounding boxes, real vs synthetic (matched at IoU >= {boxes['min_iou']:g}):")
        typer.echo(
            f"{'camera':<16} {'images r/s':>11} {'matched':>7} {'IoU mean':>8} {'IoU med':>8} {'offset px':>9} "
            f"{'p95 px':>7} {'rate r':>7} {'rate s':>7} {'s-r':>7}"
        )
        for b in [*boxes["cameras"], boxes["overall"]]:
            typer.echo(
                f"{b['camera']:<16} {str(b['n_images_real']) + '/' + str(b['n_images_synthetic']):>11} {b['n_matched']:>7} "
                f"{_num(b['iou_mean'], '.3f'):>8} {_num(b['iou_median'], '.3f'):>8} "
                f"{_num(b['centre_offset_mean_px'], '.2f'):>9} {_num(b['centre_offset_p95_px'], '.2f'):>7} "
                f"{_num(b['detection_rate_real'], '.1%'):>7} {_num(b['detection_rate_synthetic'], '.1%'):>7} "
                f"{_num(b['detection_rate_difference'], '+.1%'):>7}"
            )
