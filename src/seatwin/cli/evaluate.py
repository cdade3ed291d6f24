"""``seatwin evaluate``: a tracker run against ground truth (thesis 5.1.4)."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_HELP = (
    "Evaluate a track file against ground truth (thesis 5.1.4).\n\n"
    "Each track subscribes to the closest ground truth within --gate metres; per target the "
    "closest subscribed track is the target, and an instant without one is a track loss. Per "
    "target: coverage, first/last associated time, track switches and losses, RMSE (5.25), ANEES "
    "(5.27) of NEES (5.26) over the valid instants with its χ² bounds (5.28). Ground-truth "
    "velocities come from numerical differentiation of the positions."
)


def _fmt(value: object, spec: str = ".3f") -> str:
    return "-" if value is None else format(value, spec) if isinstance(value, float) else str(value)


def _clock(t: float | None) -> str:
    import datetime as dt

    if t is None:
        return "-"
    return dt.datetime.fromtimestamp(t, dt.UTC).strftime("%H:%M:%S.%f")[:-4]


def register(app: typer.Typer) -> None:
    @app.command("evaluate", help=_HELP)
    def evaluate_cmd(
        tracks: Path = typer.Argument(
            ..., metavar="TRACKS.csv", help="Track file (time,track_id,existence,north,v_north,east,v_east,P00…P33,confirmed)."
        ),
        truth: str = typer.Option(
            ...,
            "--truth",
            metavar="SCENARIO_OR_RECORDING",
            help="Ground truth: a scenario (built-in name, .yaml or Gemini .csv) or a recording; the ownship is excluded.",
        ),
        json_out: Path | None = typer.Option(
            None, "--json", metavar="OUT.json", help="Write the per-target metrics as JSON here."
        ),
        gate: float = typer.Option(
            10.0, "--gate", metavar="M", help="Track-to-truth association distance (m); the thesis uses 10."
        ),
        all_tracks: bool = typer.Option(False, "--all-tracks", help="Also associate unconfirmed (tentative) tracks."),
        confidence: float = typer.Option(
            0.95, "--confidence", metavar="P", help="Confidence of the two-sided ANEES bounds (5.28)."
        ),
        map_spec: str | None = typer.Option(
            None,
            "--map",
            metavar="harbour|ravnkloa|none|RASTER",
            help="Water mask to count false tracks on land (default: the recording's harbour, when --truth is a recording).",
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        import json

        from seatwin.outputs import check_output_file, write_text_atomic
        from seatwin.pipeline.evaluate import evaluate_run

        if json_out is not None:
            check_output_file(json_out, "json_out", inputs=[tracks, truth, map_spec], overwrite=overwrite)
        result = evaluate_run(tracks, truth, gate=gate, confirmed_only=not all_tracks, confidence=confidence, map_spec=map_spec)
        typer.echo(
            f"{'target':<12} {'coverage':>8} {'first (UTC)':>14} {'last (UTC)':>14} {'switch':>6} {'RMSE':>8} {'RMSEpos':>8} "
            f"{'ANEES':>9} {'bounds':>15}  verdict"
        )
        for s in result.summaries:
            bounds = "-" if s.anees_lower is None else f"[{s.anees_lower:.3f},{s.anees_upper:.3f}]"
            typer.echo(
                f"{s.target:<12} {_fmt(s.coverage):>8} {_clock(s.first_time):>14} {_clock(s.last_time):>14} "
                f"{s.track_switches:>6} {_fmt(s.rmse):>8} {_fmt(s.rmse_position):>8} {_fmt(s.anees):>9} {bounds:>15}  "
                f"{s.anees_verdict}"
            )
        ft = result.false_tracks
        if ft is not None:
            land = "" if ft.n_on_land is None else f", {ft.n_on_land} on land"
            fastest = "" if ft.max_speed_mps is None else f"; fastest {ft.max_speed_mps:.1f} m/s"
            typer.echo(f"false tracks (never a target's): {ft.n_tracks}{land}, {ft.n_instants} track-instants{fastest}")
        if json_out is not None:
            data = {
                "tracks": str(tracks),
                "truth": str(truth),
                "confirmed_only": not all_tracks,
                "confidence": confidence,
                **result.to_dict(),
            }
            write_text_atomic(json_out, json.dumps(data, indent=2) + "\n")
            typer.echo(f"wrote {json_out}")
