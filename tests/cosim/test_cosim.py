"""OSP/FMI: the FMUs' wire encoding, the system structure, and a round trip through libcosim into ``seatwin serve``."""

from __future__ import annotations

import importlib.util
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from seatwin.cosim.osp import FMU_SOURCES, export_system, run_system, scenario_samples, system_structure
from seatwin.recording import open_bag
from seatwin.scenario.builtin import builtin_scenario


def _bridge_module():
    pytest.importorskip("pythonfmu")
    spec = importlib.util.spec_from_file_location("GeminiBridge", FMU_SOURCES / "GeminiBridge.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_bridge_encodes_geminis_messages_as_protobuf_does():
    from seatwin.api.proto import simulation_pb2 as pb

    b = _bridge_module()
    poses = [(12.5, -3.25, 359.0), (0.0, 0.0, 0.0), (-1e3, 2e3, 90.0)]
    ref = pb.StepRequest(VesselPoses=[pb.Pose(north=n, east=e, heading=h) for n, e, h in poses], time=12.3, stepSize=0.1)
    assert b.step_request(poses, 12.3, 0.1) == ref.SerializeToString()
    assert b.step_request([], 0.0, 0.0) == pb.StepRequest().SerializeToString()
    big = [(float(k), 0.5, 1.0) for k in range(200)]  # length prefixes past one varint byte
    assert (
        b.step_request(big, 1.0, 0.1)
        == pb.StepRequest(
            VesselPoses=[pb.Pose(north=n, east=e, heading=h) for n, e, h in big], time=1.0, stepSize=0.1
        ).SerializeToString()
    )
    assert b.start_time_request("1600171200.0") == pb.SetStartTimeRequest(time="1600171200.0").SerializeToString()
    assert b.success(pb.StepResponse(success=True).SerializeToString())
    assert not b.success(pb.StepResponse(success=False).SerializeToString())


def test_system_structure_connects_every_pose_with_a_fixed_step():
    root = ET.fromstring(system_structure(["A", "B"], 0.05))
    ns = {"o": "http://opensimulationplatform.com/MSMI/OSPSystemStructure"}
    assert root.find("o:Algorithm", ns).text == "fixedStep"
    assert float(root.find("o:BaseStepSize", ns).text) == 0.05
    conns = root.findall("o:Connections/o:VariableConnection", ns)
    assert len(conns) == 1 + 2 * 3
    names = {c.findall("o:Variable", ns)[0].get("name") for c in conns}
    assert names == {"start_time", "A.north", "A.east", "A.heading", "B.north", "B.east", "B.heading"}


def test_scenario_samples_are_the_trajectories():
    sc = builtin_scenario("ferry_crossing")
    rel, table = scenario_samples(sc)
    assert rel[0] == 0.0 and rel[-1] == pytest.approx(sc.duration, abs=0.1) and table.shape == (len(rel), 9)
    s = sc.state_at("Finn", sc.start + rel[37])
    assert table[37, 3:6] == pytest.approx([s.north, s.east, math.degrees(s.heading) % 360.0])


@pytest.mark.slow
def test_fmu_round_trip_through_libcosim(tmp_path):
    pytest.importorskip("libcosimpy")
    sc = builtin_scenario("ferry_crossing")
    paths = export_system(sc, tmp_path / "sys")
    assert {p.name for p in paths.values()} == {
        "ScenarioPlayer.fmu",
        "GeminiBridge.fmu",
        "OspSystemStructure.xml",
        "seatwin-cosim.json",
    }
    res = run_system(paths["system"], tmp_path / "run", duration=3.0, sensors=())
    assert res.completed and res.frames == {"ground_truth": 30}
    assert json.loads((tmp_path / "run" / "manifest.json").read_text())["completed"] is True
    with open_bag(tmp_path / "run") as bag:
        truth = bag.ground_truth()
    for v in sc.vessels:
        t = truth[v.name]
        assert t.time[0] == pytest.approx(sc.start, abs=1e-6)
        s = sc.state_at(v.name, t.time)
        # float32 on the wire: millimetres at these distances
        np.testing.assert_allclose(t.north, s.north, atol=2e-3)
        np.testing.assert_allclose(t.east, s.east, atol=2e-3)
        assert np.abs(np.angle(np.exp(1j * (t.heading - s.heading)))).max() < 1e-4


@pytest.mark.slow
def test_cosim_cli_one_command_and_export(tmp_path, capsys):
    pytest.importorskip("libcosimpy")
    from seatwin.cli.main import run

    assert run(["cosim", "run", "ferry_crossing", "--out", str(tmp_path / "r"), "--duration", "1.5", "--sensors", "lidar"]) == 0
    assert "'lidar': 15" in capsys.readouterr().out
    assert (tmp_path / "r" / "cosim" / "OspSystemStructure.xml").is_file()
    with open_bag(tmp_path / "r") as bag:
        assert len(list(bag.point_clouds("/lidar/points"))) == 15
    assert run(["cosim", "export", "ferry_crossing", "--out", str(tmp_path / "x"), "--step", "0"]) == 2
    assert "--step" in capsys.readouterr().err
    assert run(["cosim", "run", str(tmp_path / "nothing.xml"), "--out", str(tmp_path / "y")]) == 2


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    pytest.importorskip("pythonfmu")
    sc = builtin_scenario("ferry_crossing")
    return sc, export_system(sc, tmp_path_factory.mktemp("sys"))


def test_exported_fmus_pass_fmpy_validation(exported):
    validation = pytest.importorskip("fmpy.validation", reason="FMPy (the `test` extra) is not installed")
    _, paths = exported
    for fmu in (paths["player"], paths["bridge"]):
        assert validation.validate_fmu(str(fmu)) == [], fmu.name


def test_player_outputs_start_exactly_at_the_scenarios_first_pose(exported):
    import zipfile

    sc, paths = exported
    with zipfile.ZipFile(paths["player"]) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    start = {}
    for v in root.iter("ScalarVariable"):
        assert v.get("causality") == "output" and v.get("initial") == "exact", v.get("name")
        start[v.get("name")] = float(v.find("Real").get("start"))
    assert start["start_time"] == sc.start
    assert root.find("ModelStructure/InitialUnknowns") is None
    for v in sc.vessels:
        s = sc.state_at(v.name, sc.start)
        assert [start[f"{v.name}.{q}"] for q in ("north", "east")] == pytest.approx([s.north, s.east], abs=1e-9)
        assert start[f"{v.name}.heading"] == pytest.approx(math.degrees(s.heading) % 360.0, abs=1e-9)


def _cli_default(command: list[str], option: str):
    import click
    import typer

    from seatwin.cli.main import app

    cmd = typer.main.get_command(app)
    ctx = click.Context(cmd)
    for name in command:
        cmd = cmd.get_command(ctx, name)
    return next(p.default for p in cmd.params if option in p.opts)


def test_one_default_sensor_set_for_every_entry_point():
    import inspect

    from seatwin.api.lockstep import LockstepSettings
    from seatwin.cosim.osp import export_system
    from seatwin.defaults import DEFAULT_SENSORS
    from seatwin.sim.settings import SimulationSettings

    assert DEFAULT_SENSORS == ("lidar", "camera")  # the thesis's twin
    assert SimulationSettings().sensors == LockstepSettings().sensors == DEFAULT_SENSORS
    assert inspect.signature(export_system).parameters["sensors"].default == DEFAULT_SENSORS
    for command in (["simulate"], ["serve"], ["cosim", "export"]):
        assert _cli_default(command, "--sensors") == ",".join(DEFAULT_SENSORS), command
    assert _cli_default(["cosim", "run"], "--sensors") is None  # the exported system's (DEFAULT_SENSORS for a scenario)


def test_export_writes_the_harbour_and_sensors_that_run_serves_with(tmp_path, monkeypatch):
    pytest.importorskip("pythonfmu")
    import dataclasses

    sc = builtin_scenario("ferry_crossing")
    gemini_like = dataclasses.replace(sc, environment={**sc.environment, "harbour": "ravnkloa"})  # a Gemini CSV's harbour
    meta = json.loads(export_system(gemini_like, tmp_path / "a")["meta"].read_text())
    assert meta["harbour"] == "ravnkloa" and meta["sensors"] == ["lidar", "camera"]
    meta = json.loads(export_system(gemini_like, tmp_path / "b", harbour="none", sensors=("lidar", "radar"))["meta"].read_text())
    assert meta["harbour"] == "none" and meta["sensors"] == ["lidar", "radar"]
    from seatwin.errors import ParameterError

    with pytest.raises(ParameterError) as exc:
        export_system(sc, tmp_path / "c", sensors=("sonar",))
    assert exc.value.param == "sensors"
    with pytest.raises(ParameterError) as exc:
        export_system(sc, tmp_path / "d", harbour="atlantis")
    assert exc.value.param == "harbour"


@pytest.mark.slow
def test_cosim_plays_a_gemini_csv_in_ravnkloa_as_simulate_does(tmp_path, shared_data):
    """The issue's measurement: 510 points per cloud in the default harbour against simulate's 207 in Ravnkloa."""
    pytest.importorskip("libcosimpy")
    from seatwin.cli.main import run
    from seatwin.pipeline.simulate import simulate_run

    csv = shared_data / "gemini-scenarios" / "Scenario6.csv"
    args = ["--duration", "0.5", "--sensors", "lidar", "--seed", "3"]
    assert run(["cosim", "run", str(csv), "--out", str(tmp_path / "c"), *args]) == 0
    simulate_run(csv, tmp_path / "s", duration=0.5, sensors=("lidar",), seed=3, progress=False)
    counts = {}
    for name in ("c", "s"):
        assert json.loads((tmp_path / name / "manifest.json").read_text())["metadata"]["harbour"] == "ravnkloa"
        with open_bag(tmp_path / name) as bag:
            counts[name] = [len(c.points) for c in bag.point_clouds("/lidar/points")]
    assert len(counts["c"]) == len(counts["s"]) == 5
    # the served poses are float32 (millimetres): the clouds' sizes agree to a few points
    np.testing.assert_allclose(counts["c"], counts["s"], rtol=0.05)
