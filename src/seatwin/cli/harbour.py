"""``seatwin harbour``: a raster harbour's alignment to the scenario frame (fit it to recordings); a raster harbour
from GeoJSON land polygons."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option


def register(app: typer.Typer) -> None:
    group = typer.Typer(
        help="Harbours: a land raster from GeoJSON land polygons; fit a land raster's alignment to scenarios' vessels.",
        no_args_is_help=True,
    )
    app.add_typer(group, name="harbour")

    @group.command("fit-alignment")
    def fit_cmd(
        scenarios: list[str] = typer.Argument(..., help="Scenario files (Gemini .csv, .yaml) whose vessels sail on water."),
        harbour: str = typer.Option("ravnkloa", "--harbour", help="The raster harbour: 'ravnkloa' or a land raster .yaml/.bin."),
        out: Path | None = typer.Option(
            None, "--out", metavar="FILE", help="Write the alignment and its provenance as YAML (e.g. NAME.alignment.yaml)."
        ),
        as_json: bool = typer.Option(False, "--json", help="Print the fit as JSON."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Fit the harbour raster's rotation and shift so that every vessel of SCENARIO… is on water.

        The alignment of a raster NAME.yaml is read from NAME.alignment.yaml beside it; the 'ravnkloa'
        harbour's is shipped with seatwin (seatwin/layout/ravnkloa_alignment.yaml).
        """
        from seatwin.layout.alignment import write_alignment
        from seatwin.outputs import check_output_file
        from seatwin.scenario.on_water import fit_harbour_alignment

        if out is not None:
            check_output_file(out, "out", inputs=scenarios, overwrite=overwrite)
        fit = fit_harbour_alignment(scenarios, harbour)
        al = fit.alignment
        if out is not None:
            write_alignment(out, al, fit.provenance())
        if as_json:
            payload = {
                "alignment": vars(al),
                "rotation_interval_deg": list(fit.rotation_interval_deg),
                "on_water_before": fit.on_water_before,
                "on_water_after": fit.on_water_after,
                "provenance": fit.provenance(),
            }
            typer.echo(json.dumps(payload, indent=2))
            return
        lo, hi = fit.rotation_interval_deg
        typer.echo(
            f"rotation {al.rotation_deg:+.2f}° about ({al.centre_north:.1f}, {al.centre_east:.1f}) m "
            f"(consistent: {lo:+.2f}° … {hi:+.2f}°, worst vessel within {100 * fit.tolerance:.1f} % of its best), "
            f"shift north {al.shift_north:+.2f} m, east {al.shift_east:+.2f} m"
        )
        for name, before in fit.on_water_before.items():
            typer.echo(f"  {name}: on water {100 * before:.1f} % → {100 * fit.on_water_after[name]:.1f} %")
        if out is not None:
            typer.echo(f"written {out}")

    @group.command("rasterize")
    def rasterize_cmd(
        geojson: Path = typer.Argument(..., metavar="LAND.geojson", help="GeoJSON land polygons ([longitude, latitude])."),
        out: Path = typer.Option(
            ..., "--out", metavar="NAME.yaml", help="The raster harbour to write: NAME.yaml and NAME.bin beside it."
        ),
        origin: str = typer.Option(
            "63.4336,10.3926",
            "--origin",
            metavar="LAT,LON[,HEIGHT]",
            help="The scenario's origin (its YAML's origin; default Ravnkloa's, as a scenario that gives none).",
        ),
        resolution: float = typer.Option(1.0, "--resolution", metavar="M", help="Cell size [m]."),
        margin: float = typer.Option(20.0, "--margin", metavar="M", help="Water around the polygons' extent [m]."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Make a raster harbour from GeoJSON land polygons, for a scenario's environment.harbour (NAME.yaml)."""
        from seatwin.cli.parsing import parse_origin
        from seatwin.errors import ParameterError
        from seatwin.layout.polygons import land_raster_from_geojson
        from seatwin.layout.raster import write_land_raster
        from seatwin.outputs import check_output_file

        if out.suffix.lower() not in (".yaml", ".yml"):
            raise ParameterError("out", f"expected NAME.yaml (NAME.bin is written beside it), got {str(out)!r}")
        bin_path = out.with_suffix(".bin")
        check_output_file(out, "out", inputs=[geojson], overwrite=overwrite)
        check_output_file(bin_path, "out", inputs=[geojson], overwrite=overwrite, outputs=[out])
        raster = land_raster_from_geojson(geojson, parse_origin(origin), resolution, margin)
        rows, cols = raster.water.shape
        meta, data = write_land_raster(raster, out)
        land = 100.0 * float(1.0 - raster.water.mean())
        typer.echo(
            f"{cols} × {rows} cells of {raster.resolution:g} m (north {raster.origin_north:.0f} … "
            f"{raster.origin_north + rows * raster.resolution:.0f} m, east {raster.origin_east:.0f} … "
            f"{raster.origin_east + cols * raster.resolution:.0f} m), {land:.0f} % land; written {meta}, {data}"
        )
