"""Harbours by name: ``default``, ``ravnkloa`` (the real land raster, found in the data folder), ``none``, a raster.

The Gemini scenarios default to Ravnkloa; a run records the harbour it was simulated in.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

import seatwin.layout.harbours as harbours
from seatwin.errors import InputError, ParameterError
from seatwin.layout import DEFAULT_LAYOUT, LandRaster, harbour_map, harbour_name
from seatwin.layout.alignment import Alignment


def _fake_data(root: Path) -> Path:
    """A data folder with a 3 × 2 'ravnkloa' raster (row 0 south; 1 = water)."""
    d = root / "ravnkloa"
    d.mkdir(parents=True)
    (d / "ravnkloa_radar_base_map.yaml").write_text(
        "map_width: 2\nmap_height: 3\ngrid_resolution: 1\norigin_x_coordinate: -1.0\norigin_y_coordinate: -1.5\n"
    )
    np.array([1, 0, 1, 1, 0, 0], dtype=np.uint8).tofile(d / "ravnkloa_radar_base_map.bin")
    return root


@pytest.fixture
def no_data(tmp_path, monkeypatch) -> Path:
    """No real data anywhere: SEATWIN_DATA unset, cwd and the repository root without shared/data."""
    monkeypatch.delenv(harbours.DATA_ENV, raising=False)
    monkeypatch.setattr(harbours, "_REPO_ROOT", tmp_path / "repo" / "checkout")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_names_and_aliases() -> None:
    assert [harbour_name(s) for s in ("default", "Ravnkloa", " NONE ", "harbour", "open", None)] == [
        "default",
        "ravnkloa",
        "none",
        "default",
        "none",
        "none",
    ]
    assert harbour_name("maps/x.yaml") is None and harbour_name(Path("x.bin")) is None
    assert harbour_map("default") is DEFAULT_LAYOUT and harbour_map("none") is None


def test_a_bad_harbour_name_is_one_clear_error() -> None:
    with pytest.raises(InputError, match=r"unknown harbour 'atlantis'; expected default, ravnkloa, none or a land raster"):
        harbour_map("atlantis")
    from seatwin.sim import SimulationSettings

    with pytest.raises(ParameterError, match="expected a harbour name .default, ravnkloa, none. or a land raster") as exc:
        SimulationSettings(harbour="atlantis")
    assert exc.value.param == "harbour"
    from seatwin.api.lockstep import LockstepSettings

    with pytest.raises(ParameterError, match="harbour"):
        LockstepSettings(harbour="atlantis")
    assert SimulationSettings(harbour="Ravnkloa").harbour == "Ravnkloa"  # names are checked, not resolved, here


def test_ravnkloa_is_found_through_seatwin_data(no_data, monkeypatch) -> None:
    data = _fake_data(no_data / "elsewhere")
    monkeypatch.setenv(harbours.DATA_ENV, str(data))
    raster = harbour_map("ravnkloa")
    assert isinstance(raster, LandRaster) and raster.water.shape == (3, 2)
    assert raster.alignment == harbours.harbour_alignment("ravnkloa")  # the shipped alignment to the Gemini frame
    cells = raster.aligned(Alignment())  # the raster's own frame
    assert cells.is_water(np.array([-1.0, -1.0, 0.0]), np.array([-0.5, 0.5, 0.5])).tolist() == [True, False, True]
    assert harbours.harbour_file("ravnkloa") == data.resolve() / harbours.RAVNKLOA_RASTER


def test_ravnkloa_is_found_in_shared_data_beside_the_cwd(no_data, monkeypatch) -> None:
    _fake_data(no_data / "shared" / "data")
    (no_data / "repo").mkdir()
    monkeypatch.chdir(no_data / "repo")  # ../shared/data from here
    assert harbours.harbour_file("ravnkloa") == (no_data / "shared" / "data" / harbours.RAVNKLOA_RASTER).resolve()


def test_a_missing_raster_names_every_place_searched(no_data, monkeypatch) -> None:
    monkeypatch.setenv(harbours.DATA_ENV, str(no_data / "nowhere"))
    with pytest.raises(InputError) as exc:
        harbour_map("ravnkloa")
    msg = str(exc.value)
    assert "Ravnkloa land raster (harbour 'ravnkloa'" in msg and "not found" in msg
    assert str(no_data / "nowhere" / harbours.RAVNKLOA_RASTER) in msg
    assert str(no_data.parent / "shared" / "data" / harbours.RAVNKLOA_RASTER) in msg  # ../shared/data from the cwd
    assert str(no_data / "repo" / "shared" / "data" / harbours.RAVNKLOA_RASTER) in msg  # beside the repository root
    assert "SEATWIN_DATA" in msg and "'default'" in msg


def test_a_scenario_yaml_names_its_harbour_and_keeps_the_name(tmp_path) -> None:
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.scenario.load import load_scenario, save_scenario

    sc = builtin_scenario("ferry_crossing")
    sc.environment["harbour"] = "ravnkloa"
    path, _ = save_scenario(sc, tmp_path / "s.yaml")
    assert yaml.safe_load(path.read_text())["environment"]["harbour"] == "ravnkloa"
    assert load_scenario(path).environment["harbour"] == "ravnkloa"  # a name, not a path beside the file
    data = yaml.safe_load(path.read_text())
    data["environment"]["harbour"] = "atlantis"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(InputError, match=r"field environment.harbour: harbour raster .* \(or use a name: default, ravnkloa"):
        load_scenario(path)


def test_a_gemini_csv_defaults_to_ravnkloa_and_sails_on_its_water(shared_data) -> None:
    from seatwin.scenario.load import load_scenario
    from seatwin.scenario.summary import scenario_summary, water_fraction
    from seatwin.world.scene import Scene

    sc = load_scenario(shared_data / "gemini-scenarios" / "Scenario6.csv")
    assert sc.environment["harbour"] == "ravnkloa"
    on = {v["name"]: v["on_water"] for v in scenario_summary(sc)["vessels"]}
    assert on == {"Havfruen": 1.0, "Finn": 1.0, "milliAmpere": 1.0}  # in the aligned raster (unaligned: 1.00, 0.96, 1.00)
    finn = next(v for v in sc.vessels if v.name == "Finn").trajectory
    assert water_fraction(finn.north, finn.east) < 0.75  # the default harbour's water: 0.73
    scene = Scene.from_scenario(sc)
    assert [o.name for o in scene.static_objects][0] == "land"  # the raster's land, not the built-in quays
    labels = [o.label for o in scene.static_objects]
    assert labels[1] == "building" and set(labels[2:]) == {"moored_boat"}  # the shore skyline and the twin's moored boats


def test_a_run_records_the_harbour_it_was_simulated_in(shared_data, tmp_path) -> None:
    from seatwin.scenario.load import load_scenario
    from seatwin.sim import simulate_scenario

    sc = load_scenario(shared_data / "gemini-scenarios" / "Scenario6.csv")
    simulate_scenario(sc, tmp_path / "r", duration=0.3, progress=False, lidar_preset="vlp16-thesis", sensors=("lidar",))
    meta = json.loads((tmp_path / "r" / "manifest.json").read_text())["metadata"]
    assert meta["harbour"] == "ravnkloa" and meta["tracking"]["map"] == "ravnkloa"  # by name: the run stays portable
    from seatwin.perception.map_mask import RasterMask
    from seatwin.pipeline.track import recording_mask

    assert isinstance(recording_mask(tmp_path / "r"), RasterMask)
    assert yaml.safe_load((tmp_path / "r" / "scenario.yaml").read_text())["environment"]["harbour"] == "ravnkloa"
    simulate_scenario(
        sc, tmp_path / "d", duration=0.3, progress=False, lidar_preset="vlp16-thesis", harbour="default", sensors=("lidar",)
    )
    meta = json.loads((tmp_path / "d" / "manifest.json").read_text())["metadata"]
    assert meta["harbour"] == "default" and meta["tracking"]["map"] == "harbour"
    assert yaml.safe_load((tmp_path / "d" / "scenario.yaml").read_text())["environment"]["harbour"] == "default"


def test_the_cli_refuses_a_bad_harbour_in_one_line(tmp_path, capsys) -> None:
    from seatwin.cli.main import run

    assert run(["simulate", "ferry_crossing", "--harbour", "atlantis", "--duration", "1", "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("seatwin: error: --harbour: expected a harbour name"), err
    assert not (tmp_path / "r").exists()
