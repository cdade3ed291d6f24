"""Scenario YAML: round trips (POSIX and TimeOfDay CSVs) and clear errors for bad files."""

from __future__ import annotations

import datetime as dt
from pathlib import Path

import numpy as np
import pytest
import yaml

from seatwin.errors import InputError
from seatwin.scenario import builtin_scenario, load_scenario, save_scenario
from seatwin.scenario.model import Scenario


def _assert_same(a: Scenario, b: Scenario, time_atol: float = 0.0) -> None:
    assert (a.name, a.description, a.seed, a.rig, a.origin) == (b.name, b.description, b.seed, b.rig, b.origin)
    assert a.environment == b.environment
    assert [(v.name, v.role, v.model, v.dimensions) for v in a.vessels] == [
        (v.name, v.role, v.model, v.dimensions) for v in b.vessels
    ]
    for va, vb in zip(a.vessels, b.vessels):
        np.testing.assert_allclose(va.trajectory.time, vb.trajectory.time, rtol=0, atol=time_atol)
        np.testing.assert_allclose(va.trajectory.north, vb.trajectory.north, rtol=0, atol=1e-9)
        np.testing.assert_allclose(va.trajectory.east, vb.trajectory.east, rtol=0, atol=1e-9)
        dh = np.angle(np.exp(1j * (va.trajectory.heading - vb.trajectory.heading)))
        assert np.abs(dh).max() < 1e-9


def test_yaml_round_trip_posix(tmp_path: Path):
    sc = builtin_scenario("constant_bearing")
    sc.seed = 7
    yaml_path, csv_path = save_scenario(sc, tmp_path / "cb.yaml")
    assert csv_path == tmp_path / "cb.csv" and csv_path.is_file()
    data = yaml.safe_load(yaml_path.read_text())
    assert data["trajectory"] == "cb.csv" and "date" not in data
    assert [v["column"] for v in data["vessels"]] == [1, 2, 3]
    assert data["vessels"][2]["role"] == "ownship"
    back = load_scenario(yaml_path)
    assert back.source == str(yaml_path)
    _assert_same(back, sc)


def test_yaml_round_trip_time_of_day(tmp_path: Path):
    sc = builtin_scenario("ferry_crossing")
    yaml_path, csv_path = save_scenario(sc, tmp_path / "fc.yml", time_format="time_of_day")
    data = yaml.safe_load(yaml_path.read_text())
    assert data["date"] == dt.date(2020, 9, 15)
    assert csv_path.read_text().startswith("TimeOfDay,")
    _assert_same(load_scenario(yaml_path), sc, time_atol=1e-6)
    # The CSV alone needs the date; the YAML supplies it, or the caller does.
    with pytest.raises(InputError, match="give the recording date"):
        load_scenario(csv_path)
    assert load_scenario(csv_path, date=dt.date(2020, 9, 15)).ownship.name == "milliAmpere"
    # Without the YAML's date the error points at the YAML's field.
    data.pop("date")
    yaml_path.write_text(yaml.safe_dump(data))
    with pytest.raises(InputError, match=r"fc\.yml: field date: fc\.csv has TimeOfDay"):
        load_scenario(yaml_path)
    assert load_scenario(yaml_path, date=dt.date(2020, 9, 15)).duration == pytest.approx(75.0)


def test_ownship_listed_first_is_written_last(tmp_path: Path):
    sc = builtin_scenario("targets_in_line")
    sc.vessels = sc.vessels[::-1]
    yaml_path, csv_path = save_scenario(sc, tmp_path / "r.yaml")
    data = yaml.safe_load(yaml_path.read_text())
    assert [(v["name"], v["column"]) for v in data["vessels"]] == [("Finn", 1), ("Havfruen", 2), ("milliAmpere", 3)]
    assert load_scenario(csv_path).vessel("milliAmpere").trajectory.north == pytest.approx(
        sc.vessel("milliAmpere").trajectory.north
    )


def test_raster_harbour_path_is_relative_to_the_yaml(tmp_path: Path):
    sc = builtin_scenario("ferry_crossing")
    yaml_path, _ = save_scenario(sc, tmp_path / "fc.yaml")
    (tmp_path / "maps").mkdir()
    (tmp_path / "maps" / "harbour.yaml").write_text("grid_resolution: 1\n")
    data = yaml.safe_load(yaml_path.read_text())
    data["environment"]["harbour"] = "maps/harbour.yaml"
    yaml_path.write_text(yaml.safe_dump(data))
    loaded = load_scenario(yaml_path)
    assert loaded.environment["harbour"] == str((tmp_path / "maps" / "harbour.yaml").resolve())
    out_yaml, _ = save_scenario(loaded, tmp_path / "out" / "again.yaml")
    assert yaml.safe_load(out_yaml.read_text())["environment"]["harbour"] == "../maps/harbour.yaml"
    data["environment"]["harbour"] = "maps/none.yaml"
    yaml_path.write_text(yaml.safe_dump(data))
    with pytest.raises(InputError, match="field environment.harbour: harbour raster"):
        load_scenario(yaml_path)


@pytest.fixture
def saved(tmp_path: Path) -> tuple[Path, dict]:
    yaml_path, _ = save_scenario(builtin_scenario("emerging_target"), tmp_path / "em.yaml")
    return yaml_path, yaml.safe_load(yaml_path.read_text())


def _edit(saved: tuple[Path, dict], change) -> Path:  # type: ignore[no-untyped-def]
    path, data = saved
    change(data)
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


@pytest.mark.parametrize(
    ("change", "pattern"),
    [
        (lambda d: d["vessels"][1].update(role="boss"), r"field vessels\[1\]\.role: Input should be 'ownship' or 'target'"),
        (lambda d: d.pop("name"), r"field name: Field required"),
        (lambda d: d.update(colour="red"), r"field colour: Extra inputs are not permitted"),
        (lambda d: d["vessels"][0].update(column=3), r"field vessels: .*vessel columns must be unique, repeated: \[3\]"),
        (lambda d: d["vessels"][0].update(role="ownship"), r"at most one ownship"),
        (lambda d: d["vessels"][0].update(column=7), r"field vessels\[0\]\.column: column 7 is not in em\.csv"),
        (lambda d: d["vessels"].pop(1), r"field vessels: em\.csv has vessel\(s\) \[2\] not listed"),
        (
            lambda d: d["vessels"][2]["dimensions"].update(beam=-1),
            r"field vessels\[2\]\.dimensions\.beam: Input should be greater than 0",
        ),
        (lambda d: d["origin"].update(lat=123.0), r"field origin\.lat: Input should be less than or equal to 90"),
        (lambda d: d.update(trajectory="gone.csv"), r"field trajectory: trajectory file .*gone\.csv' does not exist"),
        (lambda d: d.update(seed="many"), r"field seed: Input should be a valid integer"),
        (lambda d: d["environment"].update(water="waves"), r"field environment\.water: Input should be 'flat'"),
        (lambda d: d.update(vessels=[]), r"field vessels: List should have at least 1 item"),
    ],
)
def test_bad_yaml_fields_are_named(saved, change, pattern):  # type: ignore[no-untyped-def]
    path = _edit(saved, change)
    with pytest.raises(InputError, match=pattern) as info:
        load_scenario(path)
    assert str(info.value).startswith(str(path))


def test_yaml_syntax_error_names_the_line(tmp_path: Path):
    path = tmp_path / "broken.yaml"
    path.write_text("name: x\nvessels: [\n  {name: a, role: target\ntrajectory: a.csv\n")
    with pytest.raises(InputError, match=r"broken\.yaml: line \d+, column \d+: not valid YAML"):
        load_scenario(path)
    path.write_text("- just\n- a list\n")
    with pytest.raises(InputError, match="expected a mapping"):
        load_scenario(path)
    path.write_bytes(b"name: \xff\xfe\n")
    with pytest.raises(InputError, match="not UTF-8"):
        load_scenario(path)


def test_writer_refuses_other_suffixes(tmp_path: Path):
    with pytest.raises(InputError, match=r"\.yaml or \.yml"):
        save_scenario(builtin_scenario("ferry_crossing"), tmp_path / "x.txt")


@pytest.mark.parametrize(
    ("extra", "pattern"),
    [
        ("description: &d x\nname2: *d\n", r"line \d+, column 14: anchor &d: YAML anchors and aliases are not accepted"),
        ("description: " + "[" * 100 + "]" * 100 + "\n", r"line \d+, column 77: nested deeper than 64 levels"),
        ("seed: " + "1" * 5000 + "\n", r"line \d+, column 7: integer of 5000 characters is too large"),
        ("seed: 99999999999999999999\n", r"line \d+, column 7: integer 99999999999999999999 is too large"),
        ("origin: {lat: .nan, lon: 10.0}\n", r"line \d+, column 15: expected a finite number, got \.nan"),
        ("origin: {lat: 63.0, lon: nan}\n", r"line 1, field origin\.lon: Input should be a finite number"),
        ("origin: {lat: 63.0, lon: 10.0, height: 1.0e+400}\n", r"line \d+, column 40: expected a finite number"),
    ],
)
def test_hostile_yaml_is_refused_with_the_line(saved, extra, pattern):  # type: ignore[no-untyped-def]
    path, data = saved
    text = yaml.safe_dump({k: v for k, v in data.items() if k not in ("description", "seed", "origin")}, sort_keys=False)
    path.write_text(extra + text)
    with pytest.raises(InputError, match=pattern) as info:
        load_scenario(path)
    assert str(info.value).startswith(f"{path}: ")
