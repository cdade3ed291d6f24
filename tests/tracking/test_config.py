"""Tuning presets (thesis Tables 5.1, 5.2) and tuning files."""

from __future__ import annotations

import pytest

from seatwin.errors import InputError
from seatwin.tracking import PRESETS, load_tuning


@pytest.mark.parametrize("name,q,r11,r22,rc", [("synthetic", 0.3, 56.0, 0.044, 0.09), ("real", 0.2, 150.0, 0.04, 0.0026)])
def test_thesis_tables_5_1_and_5_2(name, q, r11, r22, rc) -> None:
    cfg = load_tuning(name)
    assert (cfg.q_north, cfg.q_east) == (q, q)  # Q11, Q22
    assert (cfg.sensor("lidar").r_range, cfg.sensor("lidar").r_bearing) == (r11, r22)  # R_li,11, R_li,22
    assert cfg.sensor("camera").r_bearing == rc  # R_c,11 (Table 5.2)
    assert cfg.gate_g == 1.0 and cfg.v_max == 10.0  # thesis 5.1.3


def test_all_presets_validate() -> None:
    for name in PRESETS:
        assert load_tuning(name).name == name


def test_tuning_file_with_base(tmp_path) -> None:
    f = tmp_path / "t.yaml"
    f.write_text("base: joyride\nq_north: 2.0\nsensors:\n  radar:\n    bearing_bias: -0.03\n")
    cfg = load_tuning(f)
    assert cfg.q_north == 2.0 and cfg.q_east == 5.0 and cfg.sensor("radar").bearing_bias == -0.03
    assert cfg.sensor("radar").r_range == 100.0 and cfg.name == "t"
    f.write_text("base: real\ngate_probability: 0.99\n")
    cfg = load_tuning(f)
    assert cfg.gate_g is None and cfg.gate_probability == 0.99


@pytest.mark.parametrize(
    "text,match",
    [
        ("q_north: -1\n", "q_north"),
        ("base: nope\n", "unknown base"),
        ("- 1\n", "mapping"),
        ("base: real\nsensors:\n  radar:\n    p_detect: 1.5\n", "p_detect"),
        ("base: real\nbogus: 1\n", "bogus"),
    ],
)
def test_bad_tuning_files(tmp_path, text, match) -> None:
    f = tmp_path / "bad.yaml"
    f.write_text(text)
    with pytest.raises(InputError, match=match):
        load_tuning(f)


def test_unknown_preset() -> None:
    with pytest.raises(InputError, match="not a tuning preset"):
        load_tuning("nonexistent")
    with pytest.raises(InputError, match="no sensor"):
        load_tuning("joyride").sensor("lidar")
