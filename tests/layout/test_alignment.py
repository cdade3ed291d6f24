"""A raster harbour's alignment to the scenario frame: the transform, its file, its fit, and that every user of
the map (world, land mask, scenario summary, warnings) applies the same one."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.errors import InputError
from seatwin.layout import LandRaster, harbour_map
from seatwin.layout.alignment import Alignment, VesselPath, fit_alignment, read_alignment, write_alignment
from seatwin.layout.harbours import RAVNKLOA_ALIGNMENT, harbour_alignment

finite = st.floats(-500, 500, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(st.floats(-180, 180), finite, finite, st.floats(-20, 20), st.floats(-20, 20), finite, finite)
def test_from_map_inverts_to_map(rot, cn, ce, sn, se, n, e) -> None:
    al = Alignment(rot, cn, ce, sn, se)
    back = al.from_map(*al.to_map(n, e))
    np.testing.assert_allclose(back, (n, e), atol=1e-7)
    rot3, off = al.from_map_matrix()
    mn, me = al.to_map(n, e)
    np.testing.assert_allclose(rot3 @ [mn, me, 1.5] + off, [n, e, 1.5], atol=1e-7)


def test_rotation_is_compass_sense() -> None:
    # +90° (clockwise seen from above) turns a point north of the centre to its east.
    n, e = Alignment(90.0, 10.0, 0.0).to_map(20.0, 0.0)
    assert (n, e) == pytest.approx((10.0, 10.0))


def test_alignment_file_round_trip_and_bad_files(tmp_path) -> None:
    al = Alignment(-12.5, 1.0, -2.0, 0.25, 3.0)
    p = write_alignment(tmp_path / "new" / "a.yaml", al, {"sources": ["x.csv"]})  # a missing folder is made
    assert p == tmp_path / "new" / "a.yaml" and [f.name for f in p.parent.iterdir()] == ["a.yaml"]  # no temporary left
    back, prov = read_alignment(p)
    assert back == al and prov == {"sources": ["x.csv"]}
    p.write_text("rotation_deg: nine\n")
    with pytest.raises(InputError, match=r"a.yaml: rotation_deg: expected a finite number, got 'nine'"):
        read_alignment(p)
    p.write_text("rotation: 3\n")
    with pytest.raises(InputError, match=r"unknown key 'rotation'"):
        read_alignment(p)
    p.write_text("- 1\n")
    with pytest.raises(InputError, match="expected a mapping"):
        read_alignment(p)
    with pytest.raises(InputError, match="cannot open"):
        read_alignment(tmp_path / "none.yaml")


def _channel_raster(angle_deg: float) -> LandRaster:
    """A 400 m × 400 m raster (1 m cells) with a 40 m wide channel through the origin along ``angle_deg``
    (compass) in the raster's own frame; land elsewhere."""
    n, e = np.meshgrid(np.arange(-200, 200) + 0.5, np.arange(-200, 200) + 0.5, indexing="ij")
    th = np.radians(angle_deg)
    across = -n * np.sin(th) + e * np.cos(th)
    return LandRaster(np.abs(across) < 20.0, origin_north=-200.0, origin_east=-200.0)


def test_fit_recovers_a_rotated_channel_and_reports_the_interval() -> None:
    raster = _channel_raster(30.0)
    # Two vessels sailing due north in the scenario frame, 8 m either side of the channel's middle:
    # the raster's channel runs 30° clockwise of the scenario's north.
    t = np.linspace(-150, 150, 301)
    paths = [VesselPath("a", t, np.full_like(t, -8.0)), VesselPath("b", t, np.full_like(t, 8.0))]
    fit = fit_alignment(raster, paths, rotation_range_deg=(-60, 60), grid_step_deg=1.0)
    lo, hi = fit.rotation_interval_deg
    assert lo <= 30.0 <= hi and hi - lo < 20.0
    assert fit.alignment.rotation_deg == pytest.approx(30.0, abs=3.0)
    assert min(fit.on_water_before.values()) < 0.5 and fit.worst_after == 1.0
    prov = fit.provenance()
    assert prov["vessels"] == 2 and prov["worst_on_water_after"] == 1.0


def test_fit_refuses_no_positions() -> None:
    with pytest.raises(InputError, match="no vessel positions"):
        fit_alignment(_channel_raster(0.0), [])


def _raster_files(tmp_path, raster: LandRaster, alignment: Alignment | None):
    h, w = raster.water.shape
    (tmp_path / "m.bin").write_bytes(raster.water.astype(np.uint8).tobytes())
    meta = {
        "map_width": w,
        "map_height": h,
        "grid_resolution": 1,
        "origin_x_coordinate": raster.origin_east,
        "origin_y_coordinate": raster.origin_north,
    }
    (tmp_path / "m.yaml").write_text(yaml.safe_dump(meta))
    if alignment is not None:
        write_alignment(tmp_path / "m.alignment.yaml", alignment)
    return tmp_path / "m.yaml"


def test_world_and_land_mask_apply_the_same_alignment(tmp_path) -> None:
    """A ray straight down hits the world's land exactly where the tracker's land mask says land."""
    from seatwin.engine import MeshData, make_caster
    from seatwin.perception.map_mask import load_mask
    from seatwin.world.harbour import build_harbour

    al = Alignment(25.0, 10.0, -5.0, 4.0, -3.0)
    path = _raster_files(tmp_path, _channel_raster(0.0), al)
    assert harbour_alignment(str(path)) == al
    mask = load_mask(str(path))
    objs = build_harbour(str(path))
    caster = make_caster([MeshData.from_trimesh(o.mesh, i) for i, o in enumerate(objs)])
    rng = np.random.default_rng(1)
    pts = rng.uniform(-120, 120, size=(2000, 2))
    # keep away from cell edges, where a float32 ray and the mask may round differently
    mn, me = al.to_map(pts[:, 0], pts[:, 1])
    pts = pts[(np.abs(mn - np.round(mn)) > 0.02) & (np.abs(me - np.round(me)) > 0.02)]
    hits = caster.cast(np.c_[pts, np.full(len(pts), -10.0)], np.tile([0.0, 0.0, 1.0], (len(pts), 1)), 20.0)
    land_in_world = hits.object_id >= 0
    water_in_mask = mask.is_water(pts[:, 0], pts[:, 1])
    assert (land_in_world == ~water_in_mask).all()
    assert 0.1 < water_in_mask.mean() < 0.5
    unaligned = mask.raster.aligned(Alignment()).is_water(pts[:, 0], pts[:, 1], outside=False)
    assert (land_in_world == unaligned).mean() > 0.05  # the test would see a missing alignment
    # Without the file beside the raster the map is used as is.
    (tmp_path / "m.alignment.yaml").unlink()
    assert harbour_alignment(str(path)).is_identity


def test_shipped_ravnkloa_alignment_has_provenance() -> None:
    al, prov = read_alignment(RAVNKLOA_ALIGNMENT)
    lo, hi = prov["rotation_interval_deg"]
    assert lo <= al.rotation_deg <= hi
    assert prov["sources"] == ["Scenario3.csv", "Scenario4.csv", "Scenario5.csv", "Scenario6.csv"]


def test_every_gemini_vessel_is_on_water_after_alignment(shared_data) -> None:
    """The done-when figure: every vessel of the four shipped scenarios on the aligned Ravnkloa raster's water in
    ≥ 99.5 % of its samples, none starting on land (before: 69–100 %)."""
    from seatwin.scenario.load import load_scenario
    from seatwin.scenario.on_water import land_samples, warn_on_land

    raster = harbour_map("ravnkloa")
    assert isinstance(raster, LandRaster) and not raster.alignment.is_identity
    worst_before = 1.0
    for k in (3, 4, 5, 6):
        sc = load_scenario(shared_data / "gemini-scenarios" / f"Scenario{k}.csv")
        for v in sc.vessels:
            tr = v.trajectory
            on = raster.is_water(tr.north, tr.east, outside=False)
            assert on.mean() >= 0.995, (sc.name, v.name, on.mean())
            assert on[0], (sc.name, v.name)
            worst_before = min(worst_before, float(raster.aligned(Alignment()).is_water(tr.north, tr.east, outside=False).mean()))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert warn_on_land(sc, "ravnkloa") == []
        assert land_samples(sc, raster.aligned(Alignment())) != []  # unaligned, the targets cross land
    assert worst_before < 0.75


@pytest.mark.slow
def test_refit_on_the_gemini_scenarios_reproduces_the_shipped_alignment(shared_data) -> None:
    from seatwin.scenario.on_water import fit_harbour_alignment

    fit = fit_harbour_alignment([shared_data / "gemini-scenarios" / f"Scenario{k}.csv" for k in (3, 4, 5, 6)])
    shipped, _ = read_alignment(RAVNKLOA_ALIGNMENT)
    assert fit.alignment.rotation_deg == pytest.approx(shipped.rotation_deg, abs=0.3)
    assert fit.alignment.shift_north == pytest.approx(shipped.shift_north, abs=0.5)
    assert fit.alignment.shift_east == pytest.approx(shipped.shift_east, abs=0.5)
    assert fit.worst_after >= 0.995


def test_a_vessel_on_land_is_warned_about_by_name_and_time(tmp_path) -> None:
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.scenario.on_water import OnLandWarning, warn_on_land

    sc = builtin_scenario("ferry_crossing")
    raster = _channel_raster(0.0)  # water only for |east| < 20 m
    with pytest.warns(OnLandWarning) as caught:
        bad = warn_on_land(sc, raster)
    assert bad and {b.vessel for b in bad} <= {v.name for v in sc.vessels}
    text = str(caught[0].message)
    assert f"vessel {bad[0].vessel!r} is on land" in text and "first at t = " in text
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert warn_on_land(sc, "default") == []  # the built-ins keep to the built-in harbour's water
        assert warn_on_land(sc, "atlantis") == []  # an unknown harbour: simulating it says so


@pytest.mark.slow
def test_cli_fit_alignment_writes_a_file_the_harbour_then_uses(tmp_path, capsys) -> None:
    from seatwin.cli.main import run
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.scenario.load import save_scenario

    # A crossing in the built-in harbour's frame against a raster whose channel runs 20° off north.
    sc = builtin_scenario("ferry_crossing")
    scen, _ = save_scenario(sc, tmp_path / "s.yaml")
    n, e = np.meshgrid(np.arange(-600, 600) + 0.5, np.arange(-600, 600) + 0.5, indexing="ij")
    th = np.radians(20.0)
    raster = LandRaster(np.abs(-n * np.sin(th) + e * np.cos(th)) < 75.0, -600.0, -600.0)
    path = _raster_files(tmp_path, raster, None)
    out = tmp_path / "m.alignment.yaml"
    assert run(["harbour", "fit-alignment", str(scen), "--harbour", str(path), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "rotation" in printed and "on water" in printed
    al = harbour_alignment(str(path))
    assert al.rotation_deg == read_alignment(out)[0].rotation_deg and not al.is_identity
    for v in sc.vessels:
        assert harbour_map(str(path)).is_water(v.trajectory.north, v.trajectory.east).mean() >= 0.995
    assert run(["harbour", "fit-alignment", str(scen), "--harbour", "default"]) == 2
    assert "not a land raster" in capsys.readouterr().err


def test_scenario_info_warns_of_a_vessel_on_land_in_one_line(tmp_path, capsys) -> None:
    from seatwin.cli.main import run
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.scenario.load import save_scenario

    sc = builtin_scenario("ferry_crossing")
    _raster_files(tmp_path, _channel_raster(0.0), None)  # water only for |east| < 20 m
    sc.environment["harbour"] = str(tmp_path / "m.yaml")
    path, _ = save_scenario(sc, tmp_path / "s.yaml")
    assert run(["scenario", "info", str(path)]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err and all(line.startswith("seatwin: warning: ") and "is on land in harbour" in line for line in err)
    assert any("'milliAmpere'" in line or "'Havfruen'" in line or "'Finn'" in line for line in err)
