"""``seatwin cosim``: the OSP co-simulation — export a scenario as FMUs + OspSystemStructure.xml, run it with libcosim."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import compression_option, image_format_option, overwrite_option
from seatwin.cli.simulate import BagFormat, LidarMode
from seatwin.defaults import DEFAULT_SENSORS

HARBOUR_HELP = (
    "Harbour instead of the scenario's own (a Gemini CSV's: ravnkloa; a built-in's: default), as `simulate`: 'default', "
    "'ravnkloa', 'none' or a land raster .bin/.yaml."
)
SENSORS_HELP = "Comma-separated ownship sensors: lidar, radar, camera; 'none' for ground truth only."


def _sensors(text: str | None) -> tuple[str, ...] | None:
    from seatwin.cli.output import split_list

    names = split_list(text, "sensors")
    return () if names == ("none",) else names


def register(app: typer.Typer) -> None:
    cosim_app = typer.Typer(
        help="OSP/FMI co-simulation: a ScenarioPlayer FMU drives seatwin's Gemini Simulation server.", no_args_is_help=True
    )
    app.add_typer(cosim_app, name="cosim")

    @cosim_app.command("export")
    def export_cmd(
        scenario: str = typer.Argument(
            ..., metavar="SCENARIO", help="A built-in scenario name, a scenario .yaml, or a Gemini .csv."
        ),
        out: Path = typer.Option(..., "--out", help="Folder for the FMUs, OspSystemStructure.xml and seatwin-cosim.json."),
        step: float = typer.Option(0.1, "--step", help="Fixed co-simulation step [s]."),
        date: str | None = typer.Option(None, "--date", help="UTC date YYYY-MM-DD of a TimeOfDay CSV."),
        harbour: str | None = typer.Option(None, "--harbour", help=HARBOUR_HELP),
        sensors: str = typer.Option(",".join(DEFAULT_SENSORS), "--sensors", metavar="LIST", help=SENSORS_HELP),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Write ScenarioPlayer.fmu (the scenario, embedded), GeminiBridge.fmu and a ready OspSystemStructure.xml.

        The harbour and sensors go into seatwin-cosim.json: `cosim run` serves with them unless told otherwise.
        """
        from seatwin.cli.scenario import _date
        from seatwin.cosim.osp import EXPORT_FILES, export_system
        from seatwin.outputs import check_output_folder
        from seatwin.scenario.load import load_scenario

        sc = load_scenario(scenario, date=_date(date))
        check_output_folder(out, "out", EXPORT_FILES, inputs=[scenario, *sc.files], overwrite=overwrite)
        paths = export_system(sc, out, step_size=step, harbour=harbour, sensors=_sensors(sensors) or ())
        typer.echo(f"wrote {', '.join(p.name for p in paths.values())} into {out}")

    @cosim_app.command("run")
    def run_cmd(
        system: str = typer.Argument(
            ...,
            metavar="SYSTEM|SCENARIO",
            help="An OspSystemStructure.xml written by `seatwin cosim export`, or a scenario (exported into RUN/cosim first).",
        ),
        out: Path = typer.Option(..., "--out", help="New run directory to record into."),
        duration: float | None = typer.Option(None, "--duration", help="Simulated seconds (default: the scenario's)."),
        seed: int | None = typer.Option(None, "--seed", help="Seed of every random draw (default: the scenario's)."),
        sensors: str | None = typer.Option(
            None,
            "--sensors",
            metavar="LIST",
            help=SENSORS_HELP + f" Default: the exported system's ({','.join(DEFAULT_SENSORS)} for a scenario).",
        ),
        harbour: str | None = typer.Option(None, "--harbour", help=HARBOUR_HELP + " Default: the exported system's."),
        lidar_mode: LidarMode = typer.Option(LidarMode.raycast, "--lidar-mode", help="Lidar range model."),
        fmt: BagFormat = typer.Option(BagFormat.mcap, "--format", help="Bag format."),
        compression: str | None = compression_option(),
        image_format: str = image_format_option(),
        step: float = typer.Option(0.1, "--step", help="Fixed step [s] when given a scenario."),
        date: str | None = typer.Option(None, "--date", help="UTC date YYYY-MM-DD of a TimeOfDay CSV scenario."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Run the OSP system with libcosim (fixed step) against seatwin's Simulation server; record a ROS bag.

        Given a scenario instead of a system, export it first (the one command: scenario → FMUs → libcosim → bag).
        """
        from seatwin.cli.scenario import _date
        from seatwin.cosim.osp import export_system, run_system
        from seatwin.outputs import remove_outputs
        from seatwin.recording.manifest import check_new_run
        from seatwin.scenario.load import load_scenario

        names = _sensors(sensors)
        path = Path(system)
        remove_outputs(check_new_run(out, "out", inputs=[system], overwrite=overwrite, extra=("cosim",)))
        if path.suffix.lower() != ".xml":
            sc = load_scenario(system, date=_date(date))
            kw = {} if names is None else {"sensors": names}
            path = export_system(sc, out / "cosim", step_size=step, harbour=harbour, **kw)["system"]
            names, harbour = None, None  # as exported (the harbour resolved against the scenario)
        result = run_system(
            path,
            out,
            duration=duration,
            seed=seed,
            sensors=names,
            harbour=harbour,
            lidar_mode=lidar_mode.value,
            fmt=fmt.value,
            compression=compression,
            image_format=image_format,
        )
        typer.echo(
            f"completed: {result.simulated_s:.1f} s simulated in {result.wall_s:.1f} s; frames {result.frames}; "
            f"recording in {result.run_dir}"
        )
