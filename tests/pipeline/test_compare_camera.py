"""``compare`` with cameras: AHED with lidar alone and with lidar + camera side by side, and the box comparison."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from seatwin.cli.main import run
from seatwin.errors import ParameterError
from seatwin.pipeline import compare_runs, simulate_run

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """Two 3 s runs of the ferry crossing (35 s in: both targets seen by lidar and cameras), different seeds."""
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario("ferry_crossing")
    base = tmp_path_factory.mktemp("camcmp")
    out = []
    for seed in (1, 2):
        path = base / f"run{seed}"
        simulate_run(sc, path, start=sc.start + 35.0, duration=3.0, seed=seed, progress=False, sensors=("lidar", "camera"))
        out.append(path)
    return out[0], out[1]


def test_a_run_against_itself_agrees_exactly(runs: tuple[Path, Path]) -> None:
    a, _ = runs
    res = compare_runs([a], [a], a, tunings=("synthetic",))
    cam = res.camera
    assert cam is not None and cam["detector"] == "label" and cam["skipped"] == []
    rows = cam["fusion"]["targets"]
    assert {r["target"] for r in rows} == {"Finn", "Havfruen"}
    for r in rows:  # the same tracks on both sides: HED 0 at every common instant
        assert r["ahed_lidar"] == 0.0 and r["ahed_lidar_camera"] == 0.0 and r["n_common_lidar_camera"] > 0
    (boxes,) = cam["boxes"]
    assert [c["camera"] for c in boxes["cameras"]] == ["/camera/front", "/camera/left", "/camera/right"]
    o = boxes["overall"]
    assert o["n_images_real"] == o["n_images_synthetic"] == o["n_paired_images"] == 45  # 3 cameras × 5 Hz × 3 s
    assert o["n_boxes_real"] == o["n_boxes_synthetic"] == o["n_matched"] > 0
    assert o["iou_mean"] == 1.0 and o["centre_offset_mean_px"] == 0.0 and o["centre_offset_p95_px"] == 0.0
    assert o["detection_rate_real"] == o["detection_rate_synthetic"] == 1.0 and o["detection_rate_difference"] == 0.0
    assert res.to_json()["camera"] == cam


def test_two_seeds_side_by_side_in_json_terminal_and_report(runs: tuple[Path, Path], tmp_path: Path, capsys) -> None:
    a, b = runs
    js, report = tmp_path / "c.json", tmp_path / "rep"
    args = ["compare", "--real", str(a), "--synthetic", str(b), "--truth", str(a), "--tuning", "synthetic"]
    assert run([*args, "--json", str(js), "--report", str(report), "--keep-tracks", str(tmp_path / "kept")]) == 0
    out = capsys.readouterr().out
    assert "lidar alone vs lidar + camera" in out and "bounding boxes, real vs synthetic" in out
    cam = json.loads(js.read_text())["camera"]
    fusion = cam["fusion"]
    assert fusion["ahed_n_lidar"] == fusion["ahed_n_lidar_camera"] == 2
    assert 0.0 < fusion["ahed_mean_lidar"] < 1.0 and 0.0 < fusion["ahed_mean_lidar_camera"] < 1.0
    # the lidar-only side equals the plain comparison (these runs have no radar)
    table = json.loads(js.read_text())["targets"]
    assert [r["ahed_lidar"] for r in fusion["targets"]] == [r["ahed"] for r in table]
    o = cam["boxes"][0]["overall"]
    assert o["n_paired_images"] == 45 and 0 < o["n_matched"] <= min(o["n_boxes_real"], o["n_boxes_synthetic"])
    assert 0.5 < o["iou_mean"] < 1.0 and o["centre_offset_mean_px"] > 0.0  # different seeds: box noise differs
    rates = o["detection_rate_real"], o["detection_rate_synthetic"]
    assert o["detection_rate_difference"] == pytest.approx(rates[1] - rates[0])
    page = (report / "index.html").read_text()
    assert "Cameras — ferry_crossing: lidar alone and lidar + camera" in page and "Bounding boxes:" in page
    kept = sorted(p.name for p in (tmp_path / "kept").iterdir())
    assert "real_run1_synthetic_lidar_camera.csv" in kept and "synthetic_run2_synthetic_lidar.csv" in kept


def test_no_camera_block_when_switched_off_or_without_cameras(runs: tuple[Path, Path], tmp_path: Path) -> None:
    a, _ = runs
    assert compare_runs([a], [a], a, tunings=("synthetic",), camera_fusion=False).camera is None
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario("ferry_crossing")
    lidar_only = tmp_path / "lidar"
    simulate_run(sc, lidar_only, start=sc.start + 35.0, duration=1.0, progress=False, sensors=("lidar",))
    res = compare_runs([lidar_only], [lidar_only], lidar_only, tunings=("synthetic",))
    assert res.camera is None and "camera" not in res.to_json()
    with pytest.raises(ParameterError) as err:
        compare_runs([a], [a], a, detector="onnx")
    assert err.value.param == "model"
    with pytest.raises(ParameterError) as err:
        compare_runs([a], [a], a, box_min_iou=0.0)
    assert err.value.param == "box_min_iou"
