"""The one YAML loader: aliases, depth, huge integers and non-finite numbers are refused with file and line."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from seatwin.errors import InputError
from seatwin.safe_yaml import INT_RANGE, MAX_BYTES, MAX_DEPTH, load_yaml, parse_yaml

BILLION_LAUGHS = (
    'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\n'
    "b: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]\n"
    "c: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]\n"
    "d: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]\n"
    "e: &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]\n"
    "f: &f [*e,*e,*e,*e,*e,*e,*e,*e,*e]\n"
    "g: &g [*f,*f,*f,*f,*f,*f,*f,*f,*f]\n"
    "h: &h [*g,*g,*g,*g,*g,*g,*g,*g,*g]\n"
    "i: &i [*h,*h,*h,*h,*h,*h,*h,*h,*h]\n"
)


def _refused(text: str, match: str) -> InputError:
    with pytest.raises(InputError, match=match) as info:
        parse_yaml(text, "in.yaml")
    assert str(info.value).startswith("in.yaml: line ")
    return info.value


def test_billion_laughs_refused_at_the_first_anchor() -> None:
    assert len(BILLION_LAUGHS) < 450
    err = _refused(BILLION_LAUGHS, r"anchor &a: YAML anchors and aliases are not accepted")
    assert err.where == "line 1, column 4"


@pytest.mark.parametrize(
    ("text", "line", "match"),
    [
        ("x: *nowhere\n", 1, r"alias \*nowhere"),
        ("base: {a: 1}\nother:\n  <<: *base\n", 3, r"alias \*base"),
        ("a: 1\nb: &x [1]\n", 2, r"anchor &x"),
    ],
)
def test_aliases_and_anchors_refused(text: str, line: int, match: str) -> None:
    assert _refused(text, match).where.startswith(f"line {line},")


@pytest.mark.parametrize("flow", [True, False])
def test_deep_nesting_refused_without_recursion_error(flow: bool) -> None:
    depth = 1000
    text = "[" * depth + "]" * depth if flow else "".join(" " * i + "-\n" for i in range(depth))
    _refused(text, rf"nested deeper than {MAX_DEPTH} levels")


def test_nesting_up_to_the_limit_accepted() -> None:
    data = parse_yaml("[" * MAX_DEPTH + "]" * MAX_DEPTH, "in.yaml")
    for _ in range(MAX_DEPTH - 1):
        data = data[0]
    assert data == []


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("x: " + "9" * 5000, r"integer of 5000 characters is too large"),
        (f"x: {INT_RANGE[1] + 1}", r"integer 18446744073709551616 is too large"),
        (f"x: {INT_RANGE[0] - 1}", r"integer -9223372036854775809 is too large"),
        ("x: 0x1" + "0" * 20, r"too large"),
        ("x: .inf", r"expected a finite number, got \.inf"),
        ("x: -.Inf", r"expected a finite number"),
        ("x: .nan", r"expected a finite number, got \.nan"),
        ("x: 1.0e+999", r"expected a finite number, got 1\.0e\+999"),
        ("x: [1.5, 2.5]\ny: [.NaN]", r"expected a finite number"),
    ],
)
def test_huge_and_non_finite_numbers_refused(text: str, match: str) -> None:
    _refused(text, match)


def test_ordinary_yaml_accepted() -> None:
    text = "name: x\nseeds: [1, 2]\nlimits: {lo: -9223372036854775808, hi: 18446744073709551615}\nrate: 1.5e+3\n"
    assert parse_yaml(text, "in.yaml") == {
        "name": "x",
        "seeds": [1, 2],
        "limits": {"lo": INT_RANGE[0], "hi": INT_RANGE[1]},
        "rate": 1500.0,
    }


def test_syntax_errors_and_unsafe_tags_name_the_line() -> None:
    assert _refused("a: 1\nb: x\x1a\n", r"not valid YAML: character 0x001a is not allowed").where == "line 2"
    assert _refused("a: [1, 2\nb: 3\n", r"not valid YAML").where.startswith("line ")
    _refused("a: 1\nx: !!python/object/apply:os.system [ls]\n", r"could not determine a constructor")
    for tagged in ("!!int ''", "!!int x", "!!float x", "!!bool maybe", "!!timestamp 2020-02-30", "!!timestamp x"):
        _refused(f"a: 1\nx: {tagged}\n", r"is not a valid !!(int|float|bool|timestamp)")


def test_load_yaml_names_the_file(tmp_path: Path) -> None:
    p = tmp_path / "bomb.yaml"
    p.write_text(BILLION_LAUGHS)
    with pytest.raises(InputError, match=rf"^{p}: line 1, column 4: anchor &a"):
        load_yaml(p, "a test file")
    big = tmp_path / "big.yaml"
    with big.open("w") as f:
        f.truncate(MAX_BYTES + 1)
    with pytest.raises(InputError, match=r"too large for a test file"):
        load_yaml(big, "a test file")
    with pytest.raises(InputError, match=r"cannot open"):
        load_yaml(tmp_path / "missing.yaml", "a test file")


_scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(INT_RANGE[0], INT_RANGE[1]),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(max_size=20),
)
_data = st.recursive(_scalars, lambda kids: st.lists(kids, max_size=4) | st.dictionaries(st.text(max_size=8), kids, max_size=4))


@settings(max_examples=200, deadline=None)
@given(_data)
def test_round_trip_of_plain_data(data: object) -> None:
    """Data without aliases, within the limits, reads back as it was written."""
    assert parse_yaml(yaml.safe_dump(data), "in.yaml") == data


_pieces = st.sampled_from(
    [
        "&a ",
        "*a",
        "[",
        "]",
        "{",
        "}",
        "- ",
        ": ",
        ", ",
        "\n",
        "  ",
        "x",
        "1",
        "9" * 30,
        ".inf",
        ".nan",
        "1e999",
        "<<",
        "!!int ",
        "!!float ",
        "!!bool ",
        "!!timestamp ",
        "!!binary ",
        "!!set ",
        "'",
        '"',
    ]
)


@settings(max_examples=300, deadline=None)
@given(st.lists(_pieces, max_size=60).map("".join))
def test_hostile_text_is_data_or_one_input_error(text: str) -> None:
    """Any mix of anchors, aliases, brackets and odd numbers: data with no alias expanded, or an InputError naming the line."""
    try:
        data = parse_yaml(text, "in.yaml")
    except InputError as exc:
        assert exc.source == "in.yaml"
        return

    def finite(x: object) -> bool:
        if isinstance(x, float):
            return math.isfinite(x)
        if isinstance(x, list):
            return all(finite(v) for v in x)
        if isinstance(x, dict):
            return all(finite(k) and finite(v) for k, v in x.items())
        return True

    assert finite(data)


def test_plain_values_with_a_no_break_space_are_refused() -> None:
    """A number followed by U+00A0 would be read as the number by the settings; a name would hide it."""
    _refused("ray_drop: 0.05\u00a0\n", r"value '0\.05\\xa0' starts or ends with the space character U\+00A0")
    _refused("a: {b: 1\u2003}\n", r"U\+2003")
    assert parse_yaml('name: "x\u00a0"\nboat: Havfruen\u00a0II\n', "in.yaml") == {"name": "x\u00a0", "boat": "Havfruen\u00a0II"}


def test_every_user_yaml_goes_through_the_loader(tmp_path: Path) -> None:
    """Tuning, radar, lidar and raster YAML files refuse the bomb like scenario and campaign files do."""
    from seatwin.layout import read_land_raster
    from seatwin.sensors.lidar_config import load_lidar_config
    from seatwin.sensors.radar.config import load_radar_config
    from seatwin.tracking import load_tuning

    bomb = tmp_path / "bomb.yaml"
    bomb.write_text(BILLION_LAUGHS)
    (tmp_path / "bomb.bin").write_bytes(b"\x01")
    for load in (load_tuning, load_radar_config, load_lidar_config, read_land_raster):
        with pytest.raises(InputError, match=r"line 1, column 4: anchor &a"):
            load(bomb)
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100_000 + "]" * 100_000)
    with pytest.raises(InputError, match="cannot parse tuning file"):
        load_tuning(deep)
    raster = tmp_path / "map.yaml"
    (tmp_path / "map.bin").write_bytes(b"\x01\x00")
    good = "map_width: 2\nmap_height: 1\norigin_x_coordinate: 0\norigin_y_coordinate: 0\n"
    for text, match in (
        (good.replace("map_width: 2", "map_width: '2'"), r"map_width: expected a positive integer"),
        (good.replace("origin_x_coordinate: 0", "origin_x_coordinate: x"), r"origin_x_coordinate: expected a number"),
        (good + "grid_resolution: 0\n", r"grid_resolution: expected a positive number"),
    ):
        raster.write_text(text)
        with pytest.raises(InputError, match=match):
            read_land_raster(raster)
    raster.write_text(good)
    assert read_land_raster(raster).water.shape == (1, 2)
