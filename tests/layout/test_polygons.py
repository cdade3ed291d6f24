"""A harbour from GeoJSON land polygons: read about an origin, rasterised, written, read back."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.errors import InputError, ParameterError
from seatwin.geo import GeodeticOrigin, ned_to_llh_flat
from seatwin.layout.polygons import LandPolygon, land_raster_from_geojson, rasterize_land, read_land_geojson
from seatwin.layout.raster import read_land_raster, write_land_raster

ORIGIN = GeodeticOrigin(63.4336, 10.3926, 0.0)


def _lonlat(ring_ne):
    n = np.array([p[0] for p in ring_ne], float)
    e = np.array([p[1] for p in ring_ne], float)
    lat, lon, _ = ned_to_llh_flat(n, e, np.zeros_like(n), ORIGIN)
    return [[float(a), float(b)] for a, b in zip(lon, lat, strict=True)]


def _square(n0, e0, size):
    return [(n0, e0), (n0, e0 + size), (n0 + size, e0 + size), (n0 + size, e0), (n0, e0)]


def _write(tmp_path, obj) -> object:
    path = tmp_path / "land.geojson"
    path.write_text(json.dumps(obj))
    return path


def test_a_square_with_a_hole_becomes_its_cells(tmp_path):
    outer, hole = _square(0, 0, 20), _square(5, 5, 10)
    path = _write(tmp_path, {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [_lonlat(outer), _lonlat(hole)]}})
    raster = land_raster_from_geojson(path, ORIGIN, resolution=1.0, margin=5.0)
    land = ~raster.water
    assert land.sum() == 20 * 20 - 10 * 10
    assert not raster.is_water(np.array([2.5]), np.array([2.5]))[0]
    assert raster.is_water(np.array([10.5]), np.array([10.5]))[0]  # the hole is water
    assert raster.is_water(np.array([-3.0]), np.array([-3.0]))[0]  # the margin is water
    meta, data = write_land_raster(raster, tmp_path / "out" / "h.yaml")
    back = read_land_raster(meta)
    assert np.array_equal(back.water, raster.water) and (back.origin_north, back.origin_east) == (-5.0, -5.0)


def test_multipolygons_and_collections_are_read(tmp_path):
    multi = {"type": "MultiPolygon", "coordinates": [[_lonlat(_square(0, 0, 4))], [_lonlat(_square(10, 10, 4))]]}
    coll = {"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, "geometry": multi}]}
    polys = read_land_geojson(_write(tmp_path, coll), ORIGIN)
    assert len(polys) == 2 and polys[1].outer[:, 0].min() == pytest.approx(10.0, abs=0.01)


@pytest.mark.parametrize(
    ("obj", "words"),
    [
        ({"type": "Point", "coordinates": [10, 63]}, "type"),
        ({"type": "Polygon", "coordinates": [[[10.39, 63.43], [10.4, 63.43]]]}, "coordinates[0]"),
        ({"type": "Polygon", "coordinates": [[[63.4, 100.3], [63.4, 100.4], [63.5, 100.4], [63.4, 100.3]]]}, "longitude first"),
        ({"type": "FeatureCollection", "features": [{"type": "Feature"}]}, "features[0]"),
        ({"type": "FeatureCollection", "features": []}, "no land polygon"),
    ],
)
def test_bad_geojson_names_what_and_where(tmp_path, obj, words):
    with pytest.raises(InputError) as err:
        read_land_geojson(_write(tmp_path, obj), ORIGIN)
    assert words in str(err.value)


def test_not_json_and_bad_sizes_are_refused(tmp_path):
    path = tmp_path / "x.geojson"
    path.write_text("{nope")
    with pytest.raises(InputError, match="not JSON"):
        read_land_geojson(path, ORIGIN)
    square = [LandPolygon(np.array(_square(0, 0, 5), float))]
    with pytest.raises(ParameterError, match="resolution"):
        rasterize_land(square, resolution=0.0)
    with pytest.raises(ParameterError, match="cells"):
        rasterize_land([LandPolygon(np.array(_square(0, 0, 1e5), float))], resolution=1.0)


@settings(max_examples=30, deadline=None)
@given(n0=st.integers(-50, 50), e0=st.integers(-50, 50), size=st.integers(1, 30), res=st.sampled_from([0.5, 1.0, 2.0]))
def test_an_axis_aligned_square_on_the_grid_is_exactly_its_cells(n0, e0, size, res):
    raster = rasterize_land([LandPolygon(np.array(_square(n0 * res, e0 * res, size * res), float))], resolution=res)
    assert int((~raster.water).sum()) == size * size


def test_cli_refuses_a_wrong_out_and_an_existing_raster(tmp_path, capsys):
    from seatwin.cli.main import run

    path = _write(tmp_path, {"type": "Polygon", "coordinates": [_lonlat(_square(0, 0, 10))]})
    assert run(["harbour", "rasterize", str(path), "--out", str(tmp_path / "h.bin")]) == 2
    assert "--out" in capsys.readouterr().err and not (tmp_path / "h.bin").exists()
    assert run(["harbour", "rasterize", str(path), "--out", str(tmp_path / "h.yaml")]) == 0
    assert "% land" in capsys.readouterr().out
    assert run(["harbour", "rasterize", str(path), "--out", str(tmp_path / "h.yaml")]) == 2
    assert "--overwrite" in capsys.readouterr().err
