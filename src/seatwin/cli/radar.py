"""``seatwin radar``: fit the radar model to a real recording; simulate it along a scenario."""

from __future__ import annotations

from pathlib import Path

import typer

_FIT_HELP = (
    "Fit the radar model's parameters to a real recording's statistics, each with its uncertainty.\n\n"
    "RECORDING is joyride.mat (ground truth inside) or a seatwin recording with a radar topic "
    "(e.g. from 'seatwin import joyride'; ground truth from --truth or the recording). Fitted: range and "
    "bearing bias and noise of plots about the truth, the detection model (Swerling I, SNR ∝ area/R⁴) from "
    "the detection rate against range, and the clutter density (uniform or a world map). Uncertainty: "
    "bootstrap over scans (standard error and 95 % interval). Writes a radar YAML with the report under 'fit'."
)
_SIM_HELP = (
    "Simulate the radar along a scenario (built-in name or file) in its harbour: plots per rotation "
    "(CSV time,north,east,range_m,azimuth_rad,kind,object_id) or, with --out-bag, a recording with the "
    "plots on a radar topic. Bit-identical for the same --seed."
)


def _observations(recording: Path, truth: str | None, base, first_half: bool):  # noqa: ANN001, ANN202
    import numpy as np

    from seatwin.errors import InputError
    from seatwin.sensors.radar.fit import RadarObservations

    if recording.suffix.lower() == ".mat":
        from seatwin.fidelity.joyride import load_joyride, observations

        obs = observations(load_joyride(recording), base)
    else:
        from seatwin.evaluation import load_truth
        from seatwin.perception.from_recording import scans_from_recording
        from seatwin.recording import open_bag

        with open_bag(recording) as rec:
            scans = list(scans_from_recording(rec, ("radar",)).scans)
        if not scans:
            raise InputError(recording, "no radar scans in the recording")
        ts = load_truth(truth if truth else recording)
        times = np.array([s.time for s in scans])
        states = ts.states_at(times)  # (J, n, 4)
        obs = RadarObservations(
            times, [s.positions() for s in scans], np.array([s.sensor_position for s in scans]),
            np.transpose(states[:, :, [0, 2]], (1, 0, 2)), base.detection.area_ref_m2, str(recording),
        )
    if first_half:
        obs = obs.subset(np.arange(len(obs) // 2))
    return obs


def register(app: typer.Typer) -> None:
    group = typer.Typer(help="The marine radar model: fit it to real data, simulate it.", no_args_is_help=True)
    app.add_typer(group, name="radar")

    @group.command("fit", help=_FIT_HELP)
    def fit_cmd(
        recording: Path = typer.Argument(..., metavar="RECORDING", help="joyride.mat or a recording with radar plots."),
        out: Path = typer.Option(..., "--out", metavar="RADAR.yaml", help="Where to write the fitted radar configuration."),
        truth: str = typer.Option(None, "--truth", metavar="SCENARIO", help="Ground truth (scenario file/name or recording); default: from RECORDING."),
        base: Path = typer.Option(None, "--base", metavar="RADAR.yaml", help="Start from this radar configuration (default: the built-in one)."),
        gate: float = typer.Option(60.0, "--gate", min=1.0, help="A plot within this distance [m] of a target may be the target's."),
        boot: int = typer.Option(200, "--boot", min=0, help="Bootstrap resamples for the uncertainties (0: none)."),
        clutter: str = typer.Option("uniform", "--clutter", help="Clutter form: uniform or map (world-fixed density map)."),
        first_half: bool = typer.Option(False, "--first-half", help="Fit on the first half of the scans only."),
        seed: int = typer.Option(0, "--seed", help="Seed of the bootstrap."),
    ) -> None:
        from seatwin.errors import InputError
        from seatwin.sensors.radar.config import RadarConfig, load_radar_config, save_radar_config
        from seatwin.sensors.radar.fit import fit_radar

        if not recording.exists():
            raise InputError(recording, "no such file or directory")
        if clutter not in ("uniform", "map"):
            raise InputError("--clutter", f"expected 'uniform' or 'map', got {clutter!r}")
        cfg = load_radar_config(base) if base else RadarConfig()
        obs = _observations(recording, truth, cfg, first_half)
        res = fit_radar(obs, cfg, gate_m=gate, n_boot=boot, seed=seed, clutter=clutter)
        save_radar_config(res.config, out)
        est = res.report["estimates"]

        def line(key: str, unit: str) -> str:
            e = est[key]
            ci = e["ci95"]
            ci_txt = f" [{ci[0]:.3g}, {ci[1]:.3g}]" if ci and ci[0] == ci[0] else ""
            return f"  {key:<26} {e['estimate']:.4g} {unit} ± {e['se']:.2g}{ci_txt}"

        typer.echo(f"fitted {len(obs)} scans of {recording} → {out}")
        for key, unit in (("range_bias_m", "m"), ("range_sigma_m", "m"), ("bearing_bias_deg", "°"), ("bearing_sigma_deg", "°"),
                          ("detection_rate", ""), ("snr_ref_db", "dB"), ("pd_max", ""), ("clutter_density_per_km2", "/km²/scan")):
            typer.echo(line(key, unit))
        for note in res.report.get("notes", []):
            typer.echo(f"  note: {note}")

    @group.command("simulate", help=_SIM_HELP)
    def simulate_cmd(
        scenario: str = typer.Argument(..., metavar="SCENARIO", help="Built-in scenario name or scenario file."),
        out: Path = typer.Option(None, "--out", metavar="PLOTS.csv", help="CSV of plots to write."),
        out_bag: Path = typer.Option(None, "--out-bag", metavar="RUN_DIR", help="New run directory: a recording with the plots on /radar/detections, ground truth and tf."),
        fmt: str = typer.Option("mcap", "--format", metavar="FMT", help="Bag format of --out-bag: mcap, sqlite3 or ros1."),
        spokes_dir: Path = typer.Option(None, "--spokes-dir", metavar="DIR", help="Also write each rotation's raw spokes (Gemini RadarStreamingRequest fields) as DIR/scan_NNNNNN.npz."),
        config: Path = typer.Option(None, "--radar", metavar="RADAR.yaml", help="Radar configuration (default: built-in)."),
        seed: int = typer.Option(None, "--seed", help="Seed of the random draws (default: the scenario's)."),
        duration: float = typer.Option(None, "--duration", min=0.0, help="Simulate only the first SECONDS."),
    ) -> None:
        import contextlib
        import csv

        from seatwin.errors import InputError
        from seatwin.scenario.load import load_scenario
        from seatwin.sensors.radar.config import RadarConfig, load_radar_config
        from seatwin.sensors.radar.model import RadarModel
        from seatwin.sensors.radar.plots import KIND_NAMES
        from seatwin.sensors.radar.world import scan_scene, scan_times
        from seatwin.world.scene import Scene

        if out is None and out_bag is None and spokes_dir is None:
            raise InputError("--out", "give --out PLOTS.csv, --out-bag RUN_DIR and/or --spokes-dir DIR")
        sc = load_scenario(scenario)
        if sc.ownship is None:
            raise InputError(scenario, "the scenario has no ownship to carry the radar")
        cfg = load_radar_config(config) if config else RadarConfig()
        model = RadarModel(cfg, seed=sc.seed if seed is None else seed)
        scene = Scene.from_scenario(sc)
        end = sc.end if duration is None else min(sc.end, sc.start + duration)
        n = k = 0
        with contextlib.ExitStack() as stack:
            w = None
            if out is not None:
                out.parent.mkdir(parents=True, exist_ok=True)
                w = csv.writer(stack.enter_context(out.open("w", newline="")))
                w.writerow(["time", "north", "east", "range_m", "azimuth_rad", "kind", "object_id"])
            bag = None
            if out_bag is not None:
                from seatwin.recording import open_recording, poses_from_scenario
                from seatwin.sensors.radar.record import radar_mount, write_scan

                bag = stack.enter_context(open_recording(out_bag, fmt, seed=model.seed, origin=sc.origin,
                                                         sensors={"radar": cfg.model_dump(mode="json", exclude={"fit"})}))
                bag.write_static_transforms(sc.start, [radar_mount(cfg, sc.ownship.name)])
            for k, t in enumerate(scan_times(sc.start, end, cfg.rotation_period_s)):
                s = scan_scene(model, scene, sc.ownship.name, k, float(t), with_spokes=spokes_dir is not None)
                if spokes_dir is not None:
                    import numpy as np

                    spokes_dir.mkdir(parents=True, exist_ok=True)
                    req = s.spokes.to_request_dict()
                    req["radar_spokes"] = s.spokes.intensities
                    np.savez_compressed(spokes_dir / f"scan_{k:06d}.npz", **{key: np.asarray(v) for key, v in req.items()})
                if w is not None:
                    for i in range(len(s)):
                        w.writerow([repr(float(t)), f"{s.north[i]:.3f}", f"{s.east[i]:.3f}", f"{s.range_m[i]:.3f}",
                                    f"{s.azimuth[i]:.6f}", KIND_NAMES[int(s.kind[i])], int(s.object_id[i])])
                if bag is not None:
                    bag.write_ground_truth(float(t), poses_from_scenario(sc, float(t)))
                    write_scan(bag, s, cfg)
                n += len(s)
        typer.echo(f"simulated {k + 1} radar scans, {n} plots" + "".join(f" → {p}" for p in (out, out_bag, spokes_dir) if p))
