"""``seatwin cosim``: the OSP co-simulation — export a scenario as FMUs + OspSystemStructure.xml, run it with libcosim."""

from __future__ import annotations

from pathlib import Path

import typer

from seatwin.cli.output import overwrite_option
from seatwin.cli.simulate import BagFormat, LidarMode


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
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Write ScenarioPlayer.fmu (the scenario, embedded), GeminiBridge.fmu and a ready OspSystemStructure.xml."""
        from seatwin.cli.scenario import _date
        from seatwin.cosim.osp import EXPORT_FILES, export_system
        from seatwin.outputs import check_output_folder
        from seatwin.scenario.load import load_scenario

        sc = load_scenario(scenario, date=_date(date))
        check_output_folder(out, "out", EXPORT_FILES, inputs=[scenario, *sc.files], overwrite=overwrite)
        paths = export_system(sc, out, step_size=step)
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
        sensors: str = typer.Option("lidar", "--sensors", metavar="LIST", help="Ownship sensors: lidar, radar; 'none'."),
        lidar_mode: LidarMode = typer.Option(LidarMode.raycast, "--lidar-mode", help="Lidar range model."),
        fmt: BagFormat = typer.Option(BagFormat.mcap, "--format", help="Bag format."),
        step: float = typer.Option(0.1, "--step", help="Fixed step [s] when given a scenario."),
        date: str | None = typer.Option(None, "--date", help="UTC date YYYY-MM-DD of a TimeOfDay CSV scenario."),
        overwrite: bool = overwrite_option(),
    ) -> None:
        """Run the OSP system with libcosim (fixed step) against seatwin's Simulation server; record a ROS bag.

        Given a scenario instead of a system, export it first (the one command: scenario → FMUs → libcosim → bag).
        """
        from seatwin.cli.output import split_list
        from seatwin.cli.scenario import _date
        from seatwin.cosim.osp import export_system, run_system
        from seatwin.outputs import remove_outputs
        from seatwin.recording.manifest import check_new_run
        from seatwin.scenario.load import load_scenario

        names = split_list(sensors, "sensors") or ()
        path = Path(system)
        remove_outputs(check_new_run(out, "out", inputs=[system], overwrite=overwrite, extra=("cosim",)))
        if path.suffix.lower() != ".xml":
            path = export_system(load_scenario(system, date=_date(date)), out / "cosim", step_size=step)["system"]
        result = run_system(
            path,
            out,
            duration=duration,
            seed=seed,
            sensors=() if names == ("none",) else names,
            lidar_mode=lidar_mode.value,
            fmt=fmt.value,
        )
        typer.echo(
            f"completed: {result.simulated_s:.1f} s simulated in {result.wall_s:.1f} s; frames {result.frames}; "
            f"recording in {result.run_dir}"
        )
