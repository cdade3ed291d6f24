"""``seatwin errors``: the numerical error of depth buffers, Table 4.1 of the thesis recomputed."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option

_HELP = (
    "Recompute the thesis's Table 4.1 (depth-buffer parameters, maximum numerical error ε_max by "
    "4.32 and video memory B by 4.35) for the RGB camera and the lidar.\n\n"
    "Rows 'rgb' and 'lidar' use the table's printed parameters; further rows (lidar_eq417, "
    "lidar_nc4, lidar_eq436) follow consistently from the equations 4.14–4.17 and 4.36. Each row "
    "lists what does not add up (conditions 4.33, aspect ratio 4.3, differences to the print) "
    "under 'warnings'.\n\n"
    "Below the table: the complete range-error bound of a depth-buffer lidar return (row lidar_eq417) — "
    "storage term (one depth level, 4.21) plus grazing term (the pixel-centre ray up to δ_max off the "
    "beam, at incidence i: r(cos i/cos(i+δ) − 1)) for the thesis's filter, and the bound of "
    "--lidar-mode depthbuffer-plane (beam intersected with the pixel's surface plane: storage only).\n\n"
    "With --verify, instead: the claim 4.11/4.24 checked on the default harbour — a stationary "
    "VLP-16 (1800 columns) among vessels at 8–95 m, depth-buffer points with and without the "
    "filter, and depthbuffer-plane rasterised by OpenGL (float32 view depth 'plane', 24-bit depth "
    "'plane_24bit'), against the exact points of their beams — printed as JSON (takes a few seconds)."
)


def _format_table(rows: list[dict]) -> str:
    head = (
        f"{'sensor':<12}{'VFOV_c°':>8}{'HFOV_c°':>8}{'N_c':>4}{'N_ch':>6}{'N_cw':>6}{'N_cd':>6}"
        f"{'n':>6}{'f':>7}{'ε_max [m]':>11}{'B [bytes]':>11}"
    )
    lines = [head, "-" * len(head)]
    for r in rows:
        lines.append(
            f"{r['sensor']:<12}{r['vfov_c_deg']:>8.2f}{r['hfov_c_deg']:>8.2f}{r['n_c']:>4}{r['n_ch']:>6}{r['n_cw']:>6}"
            f"{'2^' + str(int(r['n_cd']).bit_length() - 1):>6}{r['near']:>6g}{r['far']:>7g}"
            f"{r['eps_max']:>11.4g}{r['bytes']:>11.3g}"
        )
    for r in rows:
        for w in r["warnings"]:
            lines.append(f"! {r['sensor']}: {w}")
    return "\n".join(lines)


def _format_bound(bound: dict) -> str:
    """The range-error bound (storage + grazing term) as a table, in millimetres."""
    head = f"{'r [m]':>6}{'i [°]':>7}{'storage':>10}{'grazing':>10}{'filter':>10}{'plane':>10}"
    lines = [
        f"Complete range-error bound of a return on a plane, {bound['sensor']} (δ_max = "
        f"{bound['pixel_deviation_max_deg']:.4f}°), mm: filter = storage + grazing; plane = depthbuffer-plane",
        head,
        "-" * len(head),
    ]
    for b in bound["rows"]:
        lines.append(
            f"{b['range_m']:>6g}{b['incidence_deg']:>7g}{1e3 * b['storage_m']:>10.2f}{1e3 * b['grazing_m']:>10.2f}"
            f"{1e3 * b['filter_m']:>10.2f}{1e3 * b['plane_m']:>10.2f}"
        )
    return "\n".join(lines)


def register(app: typer.Typer) -> None:
    @app.command("errors", help=_HELP)
    def errors_cmd(
        as_json: bool = typer.Option(False, "--json", help='Print {"rows": [...]} as JSON instead of a table.'),
        plots: Path | None = typer.Option(
            None,
            "--plots",
            metavar="DIR",
            help="Also write Fig. 4.6 (filter mask), 4.8, 4.12 and 4.13 as PNG files into DIR (with --verify: verification.png).",
        ),
        verify: bool = typer.Option(
            False, "--verify", help="Check the claim 4.11/4.24 against exact ray casting on the default harbour; print JSON."
        ),
        overwrite: bool = overwrite_option(),
    ) -> None:
        import json

        from seatwin.errors import InputError
        from seatwin.outputs import check_output_folder
        from seatwin.sensors.depthbuffer.plots import ERROR_PLOTS
        from seatwin.sensors.depthbuffer.table import table_json

        if plots is not None:
            check_output_folder(plots, "plots_dir", ["verification.png"] if verify else ERROR_PLOTS, overwrite=overwrite)
        if verify:
            _verify(plots)
            return
        data = table_json()
        if plots is not None:
            from seatwin.sensors.depthbuffer.plots import write_error_plots

            try:
                written = write_error_plots(plots)
            except OSError as exc:
                raise InputError(plots, f"cannot write the figures: {exc.strerror or exc}", where="--plots") from exc
            if not as_json:
                for p in written:
                    typer.echo(f"wrote {p}", err=True)
        if as_json:
            typer.echo(json.dumps(data, indent=2, ensure_ascii=False))
        else:
            typer.echo(_format_table(data["rows"]) + "\n\n" + _format_bound(data["range_bound"]))


def _verify(plots: Path | None) -> None:
    import json

    from seatwin.errors import InputError
    from seatwin.sensors.depthbuffer.verify import verification_report

    plot = None
    if plots is not None:
        try:
            plots.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(plots, f"cannot create the folder: {exc.strerror or exc}", where="--plots") from exc
        plot = plots / "verification.png"
    typer.echo(json.dumps(verification_report(plot=plot)))
    if plot is not None:
        typer.echo(f"wrote {plot}", err=True)
