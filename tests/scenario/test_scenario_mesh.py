"""A vessel mesh from a scenario YAML: path relative to the file (cwd only as a fallback), scale, yaw, offset, axes."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.errors import InputError
from seatwin.mesh_placement import MeshPlacement
from seatwin.scenario.load import load_scenario, save_scenario
from seatwin.world.vessels import vessel_model

CSV = "TimeInSecondsPosix,V1x,V1y,V1Heading,V2x,V2y,V2Heading\n" + "".join(
    f"{1600164000 + t},{t:.1f},0,0,-20,0,0\n" for t in range(5)
)
# A 4 × 2 × 1 box in file units, bow (the longer side) along +y, z up from 0.
OBJ = "".join(f"v {x} {y} {z}\n" for x in (-1, 1) for y in (-2, 2) for z in (0, 1)) + "".join(
    f"f {a} {b} {c}\n"
    for a, b, c in [(1, 3, 4), (1, 4, 2), (5, 6, 8), (5, 8, 7), (1, 2, 6), (1, 6, 5)]
    + [(3, 7, 8), (3, 8, 4), (1, 5, 7), (1, 7, 3), (2, 4, 8), (2, 8, 6)]
)


def _write(folder: Path, model: str = "box.obj", mesh: str | None = "{scale: 2.0, yaw_deg: 90, offset: [0.5, 0, 0.3]}") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "t.csv").write_text(CSV)
    extra = "" if mesh is None else f", mesh: {mesh}"
    (folder / "s.yaml").write_text(
        "name: s\ntrajectory: t.csv\nvessels:\n"
        f"  - {{name: Box, role: target, column: 1, model: {model}{extra}}}\n"
        "  - {name: milliAmpere, role: ownship, column: 2, model: milliampere}\n"
    )
    return folder / "s.yaml"


def test_mesh_beside_the_scenario_is_found_from_any_folder_and_placed(tmp_path, monkeypatch):
    path = _write(tmp_path / "sc")
    (tmp_path / "sc" / "box.obj").write_text(OBJ)
    monkeypatch.chdir(tmp_path)  # not the scenario's folder
    v = load_scenario(path).vessel("Box")
    assert Path(v.model) == (tmp_path / "sc" / "box.obj").resolve()
    assert v.mesh == MeshPlacement(2.0, 90.0, (0.5, 0.0, 0.3), True)
    m = vessel_model(v.model, v.dimensions, str(path), v.mesh)
    lo, hi = m.mesh.bounds
    # scale 2: 8 × 4 × 2; yaw 90°: the bow (+y in the file, port after z-up → z-down) points forward; offset moves it.
    assert (lo[0], hi[0]) == pytest.approx((-4.0 + 0.5, 4.0 + 0.5))
    assert (lo[1], hi[1]) == pytest.approx((-2.0, 2.0))
    assert (lo[2], hi[2]) == pytest.approx((-2.0 + 0.3, 0.3))


def test_yaml_relative_wins_over_cwd_and_cwd_is_the_fallback(tmp_path, monkeypatch):
    path = _write(tmp_path / "sc", mesh=None)
    (tmp_path / "box.obj").write_text(OBJ)  # only relative to the current folder
    monkeypatch.chdir(tmp_path)
    assert Path(load_scenario(path).vessel("Box").model) == (tmp_path / "box.obj").resolve()
    (tmp_path / "sc" / "box.obj").write_text(OBJ)  # now one beside the scenario as well: that one
    assert Path(load_scenario(path).vessel("Box").model) == (tmp_path / "sc" / "box.obj").resolve()


def test_missing_mesh_names_the_field_and_both_places(tmp_path, monkeypatch):
    path = _write(tmp_path / "sc")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError) as err:
        load_scenario(path)
    msg = str(err.value)
    assert "vessels[0].model" in msg and str(tmp_path / "sc" / "box.obj") in msg and str(tmp_path / "box.obj") in msg


@pytest.mark.parametrize(
    ("model", "mesh", "words"),
    [
        ("generic", "{scale: 2}", "needs a mesh file model"),  # names vessels[0].mesh
        ("box.obj", "{scale: 0}", "greater than 0"),
        ("box.obj", "{yaw_deg: .nan}", "finite"),
        ("box.obj", "{offset: [1, 2]}", "offset"),
        ("box.obj", "{scael: 2}", "scael"),
    ],
)
def test_bad_mesh_fields_are_refused_naming_the_field(tmp_path, model, mesh, words):
    path = _write(tmp_path, model=model, mesh=mesh)
    (tmp_path / "box.obj").write_text(OBJ)
    with pytest.raises(InputError, match=r"vessels\[0\]\.mesh|line 4") as err:
        load_scenario(path)
    assert words in str(err.value), str(err.value)


def test_a_scenario_with_a_mesh_round_trips_from_another_folder(tmp_path):
    path = _write(tmp_path / "sc")
    (tmp_path / "sc" / "box.obj").write_text(OBJ)
    sc = load_scenario(path)
    yaml_path, _ = save_scenario(sc, tmp_path / "elsewhere" / "deep" / "copy.yaml")
    back = load_scenario(yaml_path).vessel("Box")
    assert Path(back.model) == (tmp_path / "sc" / "box.obj").resolve() and back.mesh == sc.vessel("Box").mesh
    assert not os.path.isabs(next(line for line in yaml_path.read_text().splitlines() if "box.obj" in line).split(": ")[1])


@settings(max_examples=25, deadline=None)
@given(
    scale=st.floats(0.01, 100.0),
    yaw=st.floats(-360.0, 360.0),
    offset=st.tuples(*[st.floats(-10.0, 10.0)] * 3),
)
def test_placement_keeps_the_mesh_rigid_up_to_its_scale(tmp_path_factory, scale, yaw, offset):
    folder = tmp_path_factory.mktemp("mesh")
    (folder / "box.obj").write_text(OBJ)
    plain = vessel_model(str(folder / "box.obj")).mesh.vertices
    placed = vessel_model(str(folder / "box.obj"), mesh=MeshPlacement(scale, yaw, offset)).mesh.vertices
    d0 = np.linalg.norm(plain[:, None] - plain[None], axis=-1)
    d1 = np.linalg.norm(placed[:, None] - placed[None], axis=-1)
    assert d1 == pytest.approx(scale * d0, rel=1e-9, abs=1e-9)
    assert placed[:, 2].max() == pytest.approx(scale * plain[:, 2].max() + offset[2])  # yaw keeps heights
