"""load_scenario: built-in names, YAML, Gemini CSV directly; clear errors otherwise."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.scenario import builtin_names, load_scenario
from seatwin.scenario.defaults import RAVNKLOA
from seatwin.scenario.gemini_csv import write_gemini_csv
from seatwin.scenario.model import Role, Trajectory


def _write(path: Path, count: int) -> Path:
    t = 1600171200.0 + np.arange(20) / 10.0
    trs = [Trajectory(t, 10.0 * n + 0.1 * np.arange(20), np.zeros(20), np.zeros(20)) for n in range(count)]
    write_gemini_csv(path, trs)
    return path


def test_builtin_by_name():
    for name in builtin_names():
        sc = load_scenario(name)
        assert sc.name == name and sc.source == f"built-in {name}"


def test_gemini_csv_three_vessels(tmp_path: Path):
    sc = load_scenario(_write(tmp_path / "Scenario9.csv", 3))
    assert sc.name == "Scenario9" and sc.origin == RAVNKLOA
    assert [(v.name, v.role, v.model) for v in sc.vessels] == [
        ("Havfruen", Role.TARGET, "havfruen"),
        ("Finn", Role.TARGET, "finn"),
        ("milliAmpere", Role.OWNSHIP, "milliampere"),
    ]
    assert sc.ownship.trajectory.north[0] == pytest.approx(20.0)


@pytest.mark.parametrize(
    ("count", "names"),
    [(1, ["milliAmpere"]), (2, ["Havfruen", "milliAmpere"]), (4, ["Havfruen", "Finn", "V3", "milliAmpere"])],
)
def test_gemini_csv_other_counts_highest_is_ownship(tmp_path: Path, count: int, names: list[str]):
    sc = load_scenario(_write(tmp_path / "s.csv", count))
    assert [v.name for v in sc.vessels] == names
    assert sc.ownship is sc.vessels[-1]
    assert sc.ownship.trajectory.north[0] == pytest.approx(10.0 * (count - 1))
    if count == 4:
        assert sc.vessel("V3").model == "generic" and sc.vessel("V3").role == Role.TARGET


def test_unknown_name_lists_the_builtins(tmp_path: Path):
    with pytest.raises(InputError, match="built-ins are: ferry_crossing, evasive_halted_ferry") as info:
        load_scenario("ferry_crossin")
    assert str(info.value).startswith("ferry_crossin:")
    with pytest.raises(InputError, match="no such scenario file"):
        load_scenario(tmp_path / "missing.yaml")
    with pytest.raises(InputError, match="is a directory"):
        load_scenario(tmp_path)
    (tmp_path / "s.json").write_text("{}")
    with pytest.raises(InputError, match="unknown scenario file type '.json'"):
        load_scenario(tmp_path / "s.json")
