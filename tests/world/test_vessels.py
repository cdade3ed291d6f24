"""Vessel models from dimensions and user meshes."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from seatwin.errors import InputError
from seatwin.scenario.model import Dimensions
from seatwin.world.vessels import MILLIAMPERE_LIDAR_HEIGHT, finn, havfruen, load_mesh, milliampere, vessel_model


@pytest.mark.parametrize(
    ("factory", "length", "beam"),
    [(milliampere, 5.0, 2.8), (havfruen, 8.0, 2.8), (finn, 4.6, 1.8)],
)
def test_builtin_models_have_their_documented_size(factory, length, beam) -> None:
    m = factory()
    assert m.length == pytest.approx(length, abs=0.01)
    assert m.beam == pytest.approx(beam, abs=0.01)
    assert m.mesh.vertices[:, 2].min() < 0  # something above the water (z down)
    assert 0 < m.reflectivity <= 1
    assert len(m.mesh.faces) < 500


def test_lidar_sits_above_milliamperes_rig() -> None:
    assert milliampere().height < MILLIAMPERE_LIDAR_HEIGHT


def test_vessel_model_names_and_generic_dimensions() -> None:
    assert vessel_model("MilliAmpere").name == "milliampere"
    g = vessel_model("generic", Dimensions(length=12.0, beam=4.0, height=3.0))
    assert g.length == pytest.approx(12.0) and g.beam == pytest.approx(4.0) and g.height == pytest.approx(3.0)
    with pytest.raises(InputError, match="unknown vessel model"):
        vessel_model("submarine", source="x.yaml")


def test_user_mesh_scale_pose_and_axes(tmp_path) -> None:
    box = trimesh.creation.box(extents=[2.0, 1.0, 0.5])
    box.apply_translation([0, 0, 0.25])  # z up: sits on z = 0, top at 0.5
    path = tmp_path / "boat.stl"
    box.export(path)
    mesh = load_mesh(path, scale=2.0, offset=(1.0, 0.0, 0.0))
    lo, hi = mesh.bounds
    np.testing.assert_allclose(lo, [-1.0, -1.0, -1.0], atol=1e-6)
    np.testing.assert_allclose(hi, [3.0, 1.0, 0.0], atol=1e-6)
    assert mesh.volume > 0  # winding kept outward after the axis flip
    model = vessel_model(str(path))
    assert model.height == pytest.approx(0.5)
    with pytest.raises(InputError, match="not found"):
        load_mesh(tmp_path / "missing.obj")
