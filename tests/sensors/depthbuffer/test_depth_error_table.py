"""Table 4.1 recomputed (``seatwin errors``), with the thesis's inconsistencies as documented expectations."""

from __future__ import annotations

import json
import math

import pytest

from seatwin.cli.main import run
from seatwin.sensors.depthbuffer.table import agrees_with_print, table_json

KEYS = {"sensor", "vfov_c_deg", "hfov_c_deg", "n_c", "n_ch", "n_cw", "n_cd", "near", "far", "eps_max", "bytes", "warnings"}


@pytest.fixture(scope="module")
def rows() -> dict[str, dict]:
    return {r["sensor"]: r for r in table_json()["rows"]}


def test_rgb_row(rows: dict[str, dict]) -> None:
    r = rows["rgb"]
    assert (r["vfov_c_deg"], r["hfov_c_deg"], r["n_c"], r["n_ch"], r["n_cw"], r["n_cd"]) == (65.4, 75.0, 1, 512, 612, 2**24)
    assert (r["near"], r["far"]) == (0.08, 1e4)
    assert r["eps_max"] == pytest.approx(133.78, abs=0.01)  # thesis prints 140 ("ca. 140 m")
    assert r["bytes"] == 940_032  # thesis prints 9.4·10^4: a factor 10 off
    text = " ".join(r["warnings"])
    assert "140" in text and "factor 10" in text and "4.33" in text


def test_lidar_row_from_the_printed_parameters(rows: dict[str, dict]) -> None:
    r = rows["lidar"]
    assert (r["vfov_c_deg"], r["hfov_c_deg"], r["n_c"], r["n_ch"], r["n_cd"]) == (41.5, 45.0, 8, 3104, 2**24)
    assert r["eps_max"] == pytest.approx(0.0429, abs=5e-5)  # thesis 0.04
    assert r["n_cw"] == 4433  # from 4.16; the printed 32768 does not follow
    assert r["bytes"] == pytest.approx(3.30e8, rel=2e-3)  # thesis 3.3·10^8 (matches N_cw = 4433)
    text = " ".join(r["warnings"])
    assert "32768" in text and "32.3°" in text and "N_c = 4" in text and "0.0345" in text


def test_rows_consistent_with_the_equations(rows: dict[str, dict]) -> None:
    r = rows["lidar_eq417"]
    assert r["vfov_c_deg"] == pytest.approx(32.347, abs=1e-3)
    assert r["eps_max"] == pytest.approx(0.0345, abs=5e-5)
    assert r["n_cw"] == 4433 and r["bytes"] == 330_240_768
    assert r["warnings"] == []  # everything follows from 4.14–4.17: nothing to flag
    nc4 = rows["lidar_nc4"]
    assert nc4["vfov_c_deg"] == pytest.approx(41.5, abs=0.01) and nc4["hfov_c_deg"] == pytest.approx(90.0)
    assert nc4["n_cw"] == 8191
    b = rows["lidar_eq436"]
    assert b["n_ch"] == 3103 and b["bytes"] == pytest.approx(3.3e8, rel=1e-3)


def test_agrees_with_print_uses_the_printed_precision() -> None:
    assert agrees_with_print(0.0429, 0.04) and agrees_with_print(3.3024e8, 3.3e8)
    assert not agrees_with_print(133.8, 140) and not agrees_with_print(940_032, 9.4e4)


def test_cli_json_shape(capsys: pytest.CaptureFixture[str]) -> None:
    assert run(["errors", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) == {"rows", "range_bound"}
    assert [r["sensor"] for r in data["rows"]][:2] == ["rgb", "lidar"]
    for r in data["rows"]:
        assert set(r) == KEYS
        assert isinstance(r["warnings"], list) and all(isinstance(w, str) for w in r["warnings"])
        assert math.isfinite(r["eps_max"]) and r["eps_max"] > 0


def test_cli_table_and_plots(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:  # noqa: ANN001
    assert run(["errors", "--plots", str(tmp_path / "figs")]) == 0
    out = capsys.readouterr().out
    assert "lidar_eq417" in out and "0.0345" in out
    names = sorted(p.name for p in (tmp_path / "figs").iterdir())
    assert names == ["fig4_12_rgb_error.png", "fig4_13_lidar_error.png", "fig4_6_filter_mask.png", "fig4_8_camera_gain.png"]
    assert all((tmp_path / "figs" / n).stat().st_size > 5000 for n in names)


def test_cli_bad_plots_folder(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:  # noqa: ANN001
    f = tmp_path / "file.txt"
    f.write_text("x")
    assert run(["errors", "--plots", str(f)]) == 2
    err = capsys.readouterr().err
    assert "--plots" in err and "folder" in err and len(err.strip().splitlines()) == 1
