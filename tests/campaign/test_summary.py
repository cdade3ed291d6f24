"""The campaign summary: per scenario, setting and tuning over seeds (issue 25, item 11)."""

from __future__ import annotations

from pathlib import Path

import pytest

from seatwin.campaign.summary import plot_campaign, summarise_campaign


def _row(job: str, scenario: str, mode: str, target: str, score: float | None, common: int, one: int, ft: int) -> dict:
    return {
        "job_id": job,
        "scenario": scenario,
        "lidar_mode": mode,
        "tuning": "synthetic",
        "target": target,
        "score_overall": score,
        "n_common": common,
        "n_only_real": one,
        "n_only_synthetic": 0,
        "false_tracks_synthetic": ft,
        "false_tracks_real": 2,
        "error": None,
    }


def test_hand_values() -> None:
    rows = [
        _row("a", "ferry", "raycast", "Finn", 0.2, 8, 2, 4),
        _row("a", "ferry", "raycast", "Havfruen", 0.2, 10, 0, 4),
        _row("b", "ferry", "raycast", "Finn", 0.4, 6, 4, 6),
        _row("c", "ferry", "depthbuffer", "Finn", None, 0, 5, 1),
        {"job_id": "d", "scenario": "ferry", "lidar_mode": "depthbuffer", "error": "boom"},
    ]
    raycast, depth = summarise_campaign(rows, ("lidar_mode",))
    assert (raycast.scenario, raycast.setting, raycast.tuning, raycast.seeds) == ("ferry", "lidar_mode raycast", "synthetic", 2)
    assert raycast.score == pytest.approx(0.3) and (raycast.score_min, raycast.score_max) == (0.2, 0.4)
    assert raycast.coverage == pytest.approx(24 / 30)
    assert raycast.false_tracks_synthetic == pytest.approx(5.0) and raycast.false_tracks_real == pytest.approx(2.0)
    assert raycast.failed == 0
    assert depth.score is None and depth.coverage == 0.0 and depth.seeds == 2 and depth.failed == 1


def test_plot_writes_a_png(tmp_path: Path) -> None:
    rows = [_row(str(k), sc, m, "Finn", 0.1 * (k + 1), 5, 1, 1) for k, (sc, m) in enumerate([("a", "x"), ("a", "y"), ("b", "x")])]
    path = plot_campaign(summarise_campaign(rows, ("lidar_mode",)), tmp_path / "c.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
