"""``compare`` warns when both runs were simulated from the same scenario with the same seed (issue 25, item 1)."""

from __future__ import annotations

from pathlib import Path

import pytest

from seatwin.cli.main import run
from seatwin.pipeline import simulate_run
from seatwin.pipeline.compare import shared_draws


def _sim(out: Path, seed: int, **changes: object) -> Path:
    simulate_run("ferry_crossing", out, start_offset=35.0, duration=2.0, seed=seed, progress=False, sensors=("lidar",), **changes)
    return out


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    root = tmp_path_factory.mktemp("seeds")
    return {
        "a1": _sim(root / "a1", 1),
        "b1": _sim(root / "b1", 1, lidar_mode="depthbuffer"),
        "a1_again": _sim(root / "a1_again", 1),
        "b2": _sim(root / "b2", 2, lidar_mode="depthbuffer"),
    }


def test_same_seed_other_settings_share_draws(runs: dict[str, Path]) -> None:
    why = shared_draws(runs["a1"], runs["b1"])
    assert why is not None and "seed 1" in why and "share their random draws" in why


def test_same_seed_same_settings_is_the_same_run(runs: dict[str, Path]) -> None:
    why = shared_draws(runs["a1"], runs["a1_again"])
    assert why is not None and "the same run" in why


def test_other_seeds_and_track_files_are_independent(runs: dict[str, Path], tmp_path: Path) -> None:
    assert shared_draws(runs["a1"], runs["b2"]) is None
    assert shared_draws(tmp_path / "tracks.csv", runs["a1"]) is None


def test_compare_prints_the_warning(runs: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    js = tmp_path / "c.json"
    argv = ["compare", "--real", str(runs["a1"]), "--synthetic", str(runs["b1"]), "--truth", str(runs["a1"]), "--json", str(js)]
    assert run(argv) == 0
    err = capsys.readouterr().err
    assert "seatwin: warning: both runs were simulated from ferry_crossing with seed 1" in err
    assert run([*argv[:4], str(runs["b2"]), *argv[5:], "--overwrite"]) == 0
    assert "warning" not in capsys.readouterr().err


def test_ahed_reason_says_who_tracked_the_target() -> None:
    from dataclasses import replace

    from seatwin.evaluation.compare import TargetComparison

    none = dict.fromkeys(("fraction_only_one", "mean_covdiff", "nees_difference_rms", "rmse_difference_rms"))
    line = TargetComparison(
        "Finn", "synthetic", None, "ahed", None, None, "skip", 10, 0, 0, 0, 10, **none, anees_real=None, anees_synthetic=None
    )
    assert line.ahed_reason == "neither dataset tracked the target"
    assert line.to_dict()["ahed_reason"] == line.ahed_reason  # in compare's table and JSON, printed by the CLI
    assert "only the real dataset" in (replace(line, n_only_real=4).ahed_reason or "")
    assert "only the synthetic dataset" in (replace(line, n_only_synthetic=4).ahed_reason or "")
    assert replace(line, ahed=0.1, n_common=3).ahed_reason is None
