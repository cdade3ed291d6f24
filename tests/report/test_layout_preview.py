"""seatwin's own picture of the Foxglove layout (docs/foxglove/layout-preview.png, linked from the README): its
preview of docs/foxglove/seatwin-layout.json filled with a tracked run, screenshot by a real (headless) browser
when one is installed. The layout in a real viewer: test_foxglove_viewer.py."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
LAYOUT = ROOT / "docs" / "foxglove" / "seatwin-layout.json"
BROWSER = next((shutil.which(b) for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)


@pytest.mark.slow
def test_layout_preview_in_a_browser(tmp_path: Path) -> None:
    from PIL import Image

    from seatwin.pipeline.simulate import simulate_run
    from seatwin.pipeline.track import track_into_run
    from seatwin.report.layout_preview import layout_preview

    run = tmp_path / "run"
    simulate_run("ferry_crossing", run, duration=2.0, start_offset=38.0, sensors=("lidar", "radar", "camera"), progress=False)
    _, tracked = track_into_run(run, tmp_path / "tracked")
    page = layout_preview(tracked.path, LAYOUT, tmp_path / "preview", at_s=1.8)
    text = page.read_text()
    for topic in ("/camera/left/image_raw", "/camera/front/image_raw", "/camera/right/image_raw", "milliAmpere/base_link"):
        assert topic in text
    pngs = sorted(p.name for p in page.parent.glob("*.png"))
    assert pngs == ["3D_scene.png", "Image_front.png", "Image_left.png", "Image_right.png"]
    for name in pngs:  # every panel has content, not a blank image
        px = np.asarray(Image.open(page.parent / name).convert("RGB"), dtype=float)
        assert px.std() > 5.0, name
    if BROWSER is None:
        pytest.skip("no chromium installed: the preview is written, not screenshot")
    shot = tmp_path / "layout.png"
    subprocess.run(
        [BROWSER, "--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", f"--screenshot={shot}",
         "--window-size=1200,900", page.as_uri()],
        check=True, capture_output=True, timeout=120,
    )  # fmt: skip
    img = np.asarray(Image.open(shot).convert("RGB"), dtype=float)
    assert img.shape == (900, 1200, 3) and img.std() > 10.0
    target = os.environ.get("SEATWIN_LAYOUT_SCREENSHOT")  # SEATWIN_LAYOUT_SCREENSHOT=docs/foxglove/layout-preview.png
    if target:
        shutil.copyfile(shot, ROOT / target)
