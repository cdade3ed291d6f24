"""``seatwin groundtruth``: vessel ground truth (Gemini CSV) from GNSS antenna logs (thesis §3.3.2)."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_HELP = (
    "Build 3-DOF vessel ground truth from GNSS antenna logs (thesis §3.3.2).\n\n"
    "Every antenna is interpolated onto one common clock (multiples of 1/RATE over the interval all "
    "logs cover) and converted to local NED about --origin with the flat-earth formulas (eqs. 3.2–3.5). "
    "A vessel with bow and stern antennas gets the midpoint as position, heading by eq. 3.6 and the "
    "baseline error ε_gnss of eq. 3.7 (samples above --eps-threshold are flagged, never dropped); a "
    "vessel with one antenna gets its course over ground as heading.\n\n"
    "Files: .gpx, .pos (RTKLIB llh), .csv (time,lat,lon[,height]), NMEA 0183 (.nmea/.log/.txt with "
    "$GPGGA plus RMC or ZDA for the date)."
)


def register(app: typer.Typer) -> None:
    @app.command("groundtruth", help=_HELP)
    def groundtruth(
        origin: str = typer.Option(
            ...,
            "--origin",
            metavar="LAT,LON[,HEIGHT]",
            help=(
                "Geodetic origin of the local NED frame (degrees, metres), e.g. 63.4336,10.3926: Ravnkloa, the frame "
                "of the Gemini scenarios and of the Ravnkloa land raster's alignment."
            ),
        ),
        vessel: list[str] = typer.Option(
            ...,
            "--vessel",
            metavar="NAME=BOW,STERN[,BASELINE_M] | NAME=FILE",
            help=(
                "A vessel and its antenna log(s); repeat for more vessels, numbered V1, V2, … in the order given. "
                "BASELINE_M is the hand-measured antenna distance |Q_r| (default: Finn 2.93, Havfruen 2.01, else the "
                "median measured distance)."
            ),
        ),
        out: Path = typer.Option(
            ...,
            "--out",
            metavar="SCENARIO.yaml|SCENARIO.csv",
            help=(
                "The scenario to write: a scenario YAML (name, ownship, models, origin, harbour) with its Gemini CSV "
                "beside it, or a Gemini CSV alone (TimeInSecondsPosix, V{n}x, V{n}y, V{n}Heading; no name or origin)."
            ),
        ),
        rate: float = typer.Option(10.0, "--rate", metavar="HZ", help="Rate of the common clock (Hz)."),
        quality: Path | None = typer.Option(
            None,
            "--quality",
            metavar="QUALITY.json",
            help="Write the per-vessel quality report (ε_gnss statistics, flags, fix quality counts) here.",
        ),
        plots: Path | None = typer.Option(
            None, "--plots", metavar="DIR", help="Write figures like thesis Figs. 3.14–3.17 (PNG) into this folder."
        ),
        eps_threshold: float = typer.Option(
            0.5, "--eps-threshold", metavar="M", help="Flag samples whose ε_gnss (eq. 3.7) exceeds this (m)."
        ),
        meridian: str = typer.Option(
            "correct",
            "--meridian",
            metavar="correct|printed",
            help="Meridian radius R_M: the correct formula, or eq. 3.5 as printed in the thesis (to reproduce it).",
        ),
        max_gap: float = typer.Option(
            5.0, "--max-gap", metavar="S", help="Flag samples interpolated across a gap between fixes longer than this (s)."
        ),
        smooth: float = typer.Option(
            1.0,
            "--smooth",
            metavar="S",
            help=(
                "Moving-average window for the central-difference velocity (s, 0: none); the course over ground of "
                "single-antenna vessels comes from it."
            ),
        ),
        min_cog_speed: float = typer.Option(
            0.5,
            "--min-cog-speed",
            metavar="M/S",
            help="Single antenna: below this speed the course over ground is not used as heading (flagged, interpolated).",
        ),
        max_speed: float = typer.Option(
            30.0,
            "--max-speed",
            metavar="M/S",
            help="A fix further from the one before than this speed allows is an error naming its line (a teleport).",
        ),
        max_turn_rate: float = typer.Option(
            180.0,
            "--max-turn-rate",
            metavar="DEG/S",
            help="A one-sample heading spike (> 90° and back) turning faster than this is an error naming the fixes.",
        ),
        name: str | None = typer.Option(
            None,
            "--name",
            metavar="NAME",
            help="The scenario's name, with --out NAME.yaml (default: the file's stem; a Gemini CSV holds no name).",
        ),
        ownship: str | None = typer.Option(
            None,
            "--ownship",
            metavar="VESSEL",
            help="The ownship, with --out NAME.yaml (default: the last --vessel, as a Gemini CSV's highest-numbered one).",
        ),
        harbour: str | None = typer.Option(
            None,
            "--harbour",
            metavar="HARBOUR",
            help=(
                "The scenario's harbour, with --out NAME.yaml: default, ravnkloa, none or a land raster .yaml path "
                "(default: ravnkloa)."
            ),
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        from seatwin.cli.parsing import parse_origin, parse_vessel
        from seatwin.groundtruth import compute_ground_truth, write_outputs
        from seatwin.groundtruth.pipeline import check_outputs

        specs = [parse_vessel(v) for v in vessel]
        check_outputs(specs, out, quality, plots, overwrite=overwrite, name=name, ownship=ownship, harbour=harbour)
        result = compute_ground_truth(
            specs,
            parse_origin(origin),
            rate_hz=rate,
            meridian=meridian,  # type: ignore[arg-type]
            eps_threshold_m=eps_threshold,
            max_gap_s=max_gap,
            smooth_s=smooth,
            min_cog_speed=min_cog_speed,
            max_speed=max_speed,
            max_turn_rate=max_turn_rate,
        )
        written = write_outputs(result, out, quality_json=quality, plots_dir=plots, name=name, ownship=ownship, harbour=harbour)
        for v_no, v in enumerate(result.vessels, start=1):
            eps = "" if v.eps_gnss is None else f", mean ε_gnss {float(v.eps_gnss.mean()):.3f} m"
            typer.echo(
                f"V{v_no} {v.name}: {len(v.time)} samples, heading from {v.heading_source}, "
                f"{100.0 * float((v.flags != 0).mean()):.1f} % flagged{eps}"
            )
        typer.echo(f"wrote {', '.join(str(p) for p in written[:3])}{' …' if len(written) > 3 else ''}")
