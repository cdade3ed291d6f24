"""The Embree ray caster: ranges, normals, ids, limits, and threads giving identical results."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from seatwin.engine import EmbreeCaster, MeshData, RayCaster, make_caster
from seatwin.engine.embree import MIN_CHUNK


def box(center, extents, oid) -> MeshData:
    m = trimesh.creation.box(extents=extents)
    m.apply_translation(center)
    return MeshData.from_trimesh(m, oid)


def test_hits_a_known_box_at_the_right_range_normal_and_id() -> None:
    caster = make_caster([box([10, 0, 0], [2, 2, 2], 7)])
    assert isinstance(caster, RayCaster)
    o = np.zeros((4, 3))
    d = np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [np.cos(0.05), np.sin(0.05), 0]])
    h = caster.cast(o, d)
    assert h.range.dtype == np.float32 and h.object_id.dtype == np.int32 and h.normal.dtype == np.float32
    assert h.range[0] == pytest.approx(9.0, abs=1e-5)
    assert h.object_id.tolist() == [7, -1, -1, 7]
    np.testing.assert_allclose(h.normal[0], [-1, 0, 0], atol=1e-6)
    np.testing.assert_allclose(h.normal[1], [0, 0, 0])
    assert np.isinf(h.range[1]) and np.isinf(h.range[2])
    assert h.range[3] == pytest.approx(9.0 / np.cos(0.05), rel=1e-5)


def test_max_range_scalar_and_per_ray() -> None:
    caster = make_caster([box([10, 0, 0], [2, 2, 2], 0)])
    o, d = np.zeros((3, 3)), np.tile([1.0, 0, 0], (3, 1))
    assert np.isinf(caster.cast(o, d, max_range=8.0).range).all()
    h = caster.cast(o, d, max_range=np.array([8.0, 9.5, np.inf]))
    assert np.isinf(h.range[0]) and h.range[1] == pytest.approx(9.0) and h.range[2] == pytest.approx(9.0)
    with pytest.raises(ValueError):
        caster.cast(o, d, max_range=np.ones(2))


def test_object_ids_map_through_skipped_empty_meshes() -> None:
    empty = MeshData(np.zeros((0, 3)), np.zeros((0, 3), int), 3)
    caster = EmbreeCaster([empty, box([0, 5, 0], [1, 1, 1], 11), box([0, -5, 0], [1, 1, 1], 4)])
    h = caster.cast(np.zeros((2, 3)), [[0, 1, 0], [0, -1, 0]])
    assert h.object_id.tolist() == [11, 4]


def test_empty_scene_and_no_rays() -> None:
    h = make_caster([]).cast(np.zeros((2, 3)), [[1, 0, 0], [0, 1, 0]])
    assert h.object_id.tolist() == [-1, -1] and np.isinf(h.range).all()
    h = make_caster([box([0, 0, 0], [1, 1, 1], 0)]).cast(np.zeros((0, 3)), np.zeros((0, 3)))
    assert len(h) == 0


def test_multithreaded_result_is_identical_to_single_thread() -> None:
    sphere = trimesh.creation.icosphere(3, radius=3.0)
    sphere.apply_translation([0, 0, 12])
    meshes = [box([0, 0, 0], [20, 20, 20], 0), MeshData.from_trimesh(sphere, 1)]
    one, many = EmbreeCaster(meshes, threads=1), EmbreeCaster(meshes, threads=4)
    n = 4 * MIN_CHUNK + 123
    rng = np.random.default_rng(1)
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    o = np.tile([0.5, -0.2, 0.3], (n, 1))
    limit = rng.uniform(5, 20, n)
    a, b = one.cast(o, d, limit), many.cast(o, d, limit)
    np.testing.assert_array_equal(a.range, b.range)
    np.testing.assert_array_equal(a.object_id, b.object_id)
    np.testing.assert_array_equal(a.geometric_normal, b.geometric_normal)
    assert (a.object_id >= 0).mean() > 0.3


def test_mesh_validation_and_unknown_backend() -> None:
    with pytest.raises(ValueError):
        MeshData(np.zeros((3, 2)), np.zeros((1, 3), int), 0)
    with pytest.raises(ValueError):
        MeshData(np.zeros((3, 3)), np.array([[0, 1, 5]]), 0)
    with pytest.raises(ValueError):
        make_caster([], backend="nope")
