"""The HTML report: self-contained, and renders in headless Chromium with every figure decoded and shown large."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from seatwin.evaluation.compare import compare
from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet, TruthTrack
from seatwin.perception.map_mask import load_mask
from seatwin.report import Clouds, write_comparison_report


def _tracks(offset: float, start: int, var: float) -> Tracks:
    k = np.arange(start, 30)
    n = len(k)
    state = np.column_stack([k * 1.0 + offset, np.ones(n), np.full(n, 10.0), np.zeros(n)])
    cov = np.tile(np.diag([var, 0.1, var, 0.1]), (n, 1, 1))
    return Tracks(1.6e9 + k, np.ones(n, int), np.full(n, 0.9), state, cov, np.ones(n, bool), 1.6e9 + np.arange(30.0))


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> Path:
    t = 1.6e9 + np.arange(0.0, 30.0)
    truth = TruthSet(
        {
            "Havfruen": TruthTrack("Havfruen", t, t - t[0], np.full(30, 10.0)),
            "Finn": TruthTrack("Finn", t, np.zeros(30), np.full(30, -40.0)),
        }
    )
    real, synt = _tracks(0.5, 0, 1.0), _tracks(-0.5, 3, 2.0)
    comps = [compare(real, synt, truth, "synthetic"), compare(real, real, truth, "real")]
    rng = np.random.default_rng(0)
    clouds = [
        Clouds(float(t[5]), rng.normal(size=(500, 2)) * 20, rng.normal(size=(800, 2)) * 20, (0.0, 0.0), [("Havfruen", 5.0, 10.0)])
    ]
    return write_comparison_report(
        tmp_path_factory.mktemp("report"),
        comps,
        truth,
        title="test <report>",
        scenario="s3",
        mask=load_mask("harbour"),
        clouds=clouds,
    )


@pytest.mark.slow
def test_page_is_self_contained(page: Path) -> None:
    text = page.read_text()
    assert text.startswith("<!DOCTYPE html>")
    assert "test &lt;report&gt;" in text  # escaped
    assert not re.search(r'(src|href)="(?!data:)', text), "every resource must be embedded"
    assert text.count('src="data:image/png;base64,') >= 6
    for needle in (
        "AHED (standard)",
        "AHED (printed)",
        "Average, all tunings",
        "upper bound",
        "Point clouds at",
        "Neither dataset has a track",
    ):
        assert needle in text


def _chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    pytest.skip("headless Chromium is not installed (Debian: apt-get update && apt-get install -y chromium)")


@pytest.mark.slow
def test_renders_in_headless_chromium(page: Path, tmp_path: Path) -> None:
    exe = _chromium()
    flags = [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        f"--user-data-dir={tmp_path / 'profile'}",
        "--virtual-time-budget=10000",
    ]
    dom = subprocess.run(
        [exe, *flags, "--window-size=1200,2000", "--dump-dom", page.as_uri()], capture_output=True, text=True, timeout=120
    )
    assert dom.returncode == 0, dom.stderr[-2000:]
    m = re.search(r'data-figures="(\d+)/(\d+)"', dom.stdout)
    assert m, "the page's load check did not run"
    assert m.group(1) == m.group(2) and int(m.group(2)) >= 6, f"figures decoded: {m.group(0)}"
    # Shown large: each figure as wide as the page asks (its pixels / PIXELS_PER_CSS_PX), or the whole column.
    from seatwin.report.html import PIXELS_PER_CSS_PX

    widths = re.search(r'data-figure-widths="([^"]*)"', dom.stdout)
    column = re.search(r'data-content-width="(\d+)"', dom.stdout)
    assert widths and column, "the page's size check did not run"
    for pair in widths.group(1).split(","):
        shown, natural = (int(x) for x in pair.split(":"))
        assert abs(shown - min(natural / PIXELS_PER_CSS_PX, int(column.group(1)))) <= 2, (pair, column.group(1))
        assert shown >= 500, f"a figure shown only {shown} px wide"
    shot = tmp_path / "shot.png"
    run = subprocess.run(
        [exe, *flags, f"--screenshot={shot}", "--window-size=1200,2000", page.as_uri()],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0 and shot.stat().st_size > 10_000, run.stderr[-2000:]
