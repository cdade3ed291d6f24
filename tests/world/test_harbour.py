"""Harbour geometry from the default layout and from land/water rasters."""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from seatwin.engine import MeshData, make_caster
from seatwin.errors import InputError
from seatwin.layout import DEFAULT_LAYOUT, read_land_raster
from seatwin.world.harbour import build_harbour, harbour_from_layout, harbour_from_raster, merge_cells


def caster_of(objs):
    return make_caster([MeshData.from_trimesh(o.mesh, i) for i, o in enumerate(objs)])


def test_layout_harbour_objects_and_quay_height() -> None:
    objs = harbour_from_layout(DEFAULT_LAYOUT)
    labels = {o.label for o in objs}
    assert labels == {"quay", "pier", "building", "moored_boat"}
    assert len(objs) == 2 + len(DEFAULT_LAYOUT.piers) + len(DEFAULT_LAYOUT.buildings) + len(DEFAULT_LAYOUT.moored_boats)
    c = caster_of(objs)
    # Straight down onto the west quay from 10 m up: hits its top at quay height.
    h = c.cast([[0.0, -DEFAULT_LAYOUT.half_width - 5.0, -10.0]], [[0.0, 0.0, 1.0]])
    assert h.range[0] == pytest.approx(10.0 - DEFAULT_LAYOUT.quay_height, abs=1e-4)
    assert objs[h.object_id[0]].name == "quay_west"
    # Across the channel at 1 m above water: the east quay face at half_width.
    h = c.cast([[-300.0, 0.0, -1.0]], [[0.0, 1.0, 0.0]])
    assert h.range[0] == pytest.approx(DEFAULT_LAYOUT.half_width, abs=1e-4)
    np.testing.assert_allclose(h.normal[0], [0, -1, 0], atol=1e-6)


def test_merge_cells_covers_exactly() -> None:
    rng = np.random.default_rng(3)
    mask = rng.random((40, 30)) < 0.6
    mask[5:20, 3:25] = True
    cover = np.zeros(mask.shape, int)
    rects = merge_cells(mask)
    for r0, r1, c0, c1 in rects:
        cover[r0:r1, c0:c1] += 1
    np.testing.assert_array_equal(cover, mask.astype(int))
    assert len(rects) < mask.sum() / 2


def write_raster(tmp_path, water: np.ndarray, ox: float, oy: float):
    h, w = water.shape
    water.astype(np.uint8).tofile(tmp_path / "map.bin")
    (tmp_path / "map.yaml").write_text(
        yaml.safe_dump(
            {"map_width": w, "map_height": h, "grid_resolution": 1, "origin_x_coordinate": ox, "origin_y_coordinate": oy}
        )
    )
    return tmp_path / "map.bin"


def test_raster_harbour_from_a_generated_raster(tmp_path) -> None:
    water = np.ones((50, 40), bool)
    water[:, :10] = False  # land west of east = -20 + 10 = -10
    water[30:35, 10:20] = False  # a pier
    path = write_raster(tmp_path, water, ox=-20.0, oy=-25.0)
    raster = read_land_raster(path)
    assert raster.water.shape == (50, 40)
    assert raster.is_water(np.array([0.0]), np.array([0.0]))[0]
    assert not raster.is_water(np.array([0.0]), np.array([-15.0]))[0]
    objs = harbour_from_raster(raster, quay_height=1.5, building_setback=5.0, building_height=8.0)
    assert [o.label for o in objs] == ["quay", "building"]
    c = caster_of(objs)
    h = c.cast([[-20.0, 0.0, -1.0]], [[0.0, -1.0, 0.0]])  # west at 1 m above water: the land edge
    assert h.range[0] == pytest.approx(10.0, abs=1e-4)
    # Westwards from east 6, 1 m above the water: the pier (rows 30–34 = north 5 … 10, east −10 … 0)
    # shows its east face at east 0 (range 6); just south and north of it the land edge at −10 (16).
    for north, expected in ((4.9, 16.0), (5.1, 6.0), (7.0, 6.0), (9.9, 6.0), (10.1, 16.0)):
        h = c.cast([[north, 6.0, -1.0]], [[0.0, -1.0, 0.0]])
        assert h.range[0] == pytest.approx(expected, abs=1e-4), north
        np.testing.assert_allclose(h.normal[0], [0.0, 1.0, 0.0], atol=1e-6)
        assert objs[h.object_id[0]].label == "quay"
    h = c.cast([[0.0, -12.0, -20.0]], [[0.0, 0.0, 1.0]])  # down onto the quay top
    assert h.range[0] == pytest.approx(18.5, abs=1e-4)
    h = c.cast([[0.0, -19.5, -20.0]], [[0.0, 0.0, 1.0]])  # ≥ 5 m from water: a building
    assert h.range[0] == pytest.approx(12.0, abs=1e-4) and objs[h.object_id[0]].label == "building"
    assert build_harbour(str(path))[0].label == "quay"


def test_bad_rasters_are_named(tmp_path) -> None:
    path = write_raster(tmp_path, np.ones((4, 4), bool), 0.0, 0.0)
    path.write_bytes(b"\x01" * 15)
    with pytest.raises(InputError, match="expected map_width"):
        read_land_raster(path)
    path.write_bytes(b"\x02" * 16)
    with pytest.raises(InputError, match="0 \\(land\\) or 1"):
        read_land_raster(path)
    with pytest.raises(InputError, match="not found"):
        read_land_raster(tmp_path / "nothing.bin")
    with pytest.raises(InputError, match="unknown harbour"):
        build_harbour("atlantis")


def test_real_ravnkloa_raster(shared_data) -> None:
    path = shared_data / "ravnkloa" / "ravnkloa_radar_base_map.bin"
    if not path.is_file():
        pytest.skip(f"{path} is absent")
    raster = read_land_raster(path)
    assert raster.water.shape == (825, 617)
    assert 0.2 < raster.water.mean() < 0.8
    objs = harbour_from_raster(raster)
    tris = sum(len(o.mesh.faces) for o in objs)
    assert tris < 12 * (~raster.water).sum() / 10  # merging saves ≥ 10× over one box per cell
    # The land cells' footprint is kept: a ray down onto a land cell centre hits at quay height.
    r, c = np.argwhere(~raster.water)[len(np.argwhere(~raster.water)) // 2]
    n, e = raster.origin_north + r + 0.5, raster.origin_east + c + 0.5
    h = caster_of(objs).cast([[n, e, -10.0]], [[0.0, 0.0, 1.0]])
    assert h.range[0] == pytest.approx(10.0 - 1.8, abs=1e-3)


def test_blocks_builds_the_same_triangles_as_one_block_each() -> None:
    from seatwin.world.shapes import block, blocks, merge

    ext = np.array([[0.0, 1.0, 0.0, 2.0], [5.0, 7.0, -3.0, -1.0], [1.5, 9.0, 2.0, 3.0]])
    a, b = merge([block(*e, 3.0, -2.0) for e in ext]), blocks(ext, 3.0, -2.0)
    assert np.array_equal(a.vertices, b.vertices) and np.array_equal(a.faces, b.faces)
    with pytest.raises(ValueError, match="empty blocks"):
        blocks(np.array([[0.0, 0.0, 0.0, 1.0]]), 1.0)


def test_a_raster_harbour_has_a_skyline_behind_its_quay_walls(tmp_path) -> None:
    from seatwin.world.harbour import SHORE_SKYLINE, Skyline

    water = np.ones((200, 200), bool)
    water[:, :120] = False  # land west of east = 20 (origin −100, −100)
    raster = read_land_raster(write_raster(tmp_path, water, ox=-100.0, oy=-100.0))
    objs = build_harbour(str(tmp_path / "map.yaml"))
    assert [o.label for o in objs] == ["quay", "building"]
    c = caster_of(objs)
    sk = SHORE_SKYLINE
    # Westwards 1 m above the water: the quay wall at the water's edge (east 20).
    h = c.cast([[0.5, 60.0, -1.0]], [[0.0, -1.0, 0.0]])
    assert h.range[0] == pytest.approx(40.0, abs=1e-3) and objs[h.object_id[0]].label == "quay"
    # Westwards 5 m above the water, along many norths: building fronts one setback behind the quay,
    # except where a street runs inland.
    norths = np.arange(-95.0, 95.0, 0.5) + 0.25
    hits = c.cast(
        np.c_[norths, np.full_like(norths, 60.0), np.full_like(norths, -5.0)], np.tile([0.0, -1.0, 0.0], (len(norths), 1))
    )
    front = np.abs(hits.range - (40.0 + sk.setback_m)) < 1e-3
    assert 0.6 < front.mean() < 0.95  # blocks and streets
    # Down onto the blocks: their tops are the skyline's heights, several of them.
    east = 20.0 - sk.setback_m - 5.0
    down = c.cast(
        np.c_[norths, np.full_like(norths, east), np.full_like(norths, -50.0)], np.tile([0.0, 0.0, 1.0], (len(norths), 1))
    )
    tops = {round(float(x), 3) for x in 50.0 - down.range[np.isfinite(down.range)]}
    assert DEFAULT_LAYOUT.quay_height in tops and len(tops & set(sk.heights_m)) >= 3
    # No buildings deeper than the band; the same raster gives the same skyline.
    deep = c.cast([[0.25, 20.0 - sk.setback_m - sk.depth_m - 3.0, -50.0]], [[0.0, 0.0, 1.0]])
    assert 50.0 - deep.range[0] == pytest.approx(DEFAULT_LAYOUT.quay_height, abs=1e-3)
    again = build_harbour(str(tmp_path / "map.yaml"))
    assert np.array_equal(again[1].mesh.vertices, objs[1].mesh.vertices)
    assert harbour_from_raster(raster, skyline=Skyline(heights_m=(5.0,)))[1].mesh.vertices[:, 2].min() == pytest.approx(-5.0)
