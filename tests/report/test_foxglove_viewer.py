"""A tracked seatwin run in a real Foxglove-compatible viewer: Lichtblick's web build (the open-source Foxglove
Studio fork, built from source outside the repository), served locally and opened in headless Chromium with
docs/foxglove/seatwin-layout.json (``tools/foxglove_screenshot.py``). Skips unless ``SEATWIN_VIEWER_DIST``
names the build (its folder with index.html); docs/validation.md, "Foxglove view", says how to build it."""

from __future__ import annotations

import importlib.util
import io
import json
import os
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
LAYOUT = ROOT / "docs" / "foxglove" / "seatwin-layout.json"
CAMERAS = ("left", "front", "right")


def _tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location("foxglove_screenshot", ROOT / "tools" / "foxglove_screenshot.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def _dist() -> Path:
    dist = os.environ.get("SEATWIN_VIEWER_DIST")
    if not dist:
        pytest.skip("SEATWIN_VIEWER_DIST is unset: no Lichtblick web build to serve (docs/validation.md, 'Foxglove view')")
    if not (Path(dist) / "index.html").is_file():
        pytest.skip(f"SEATWIN_VIEWER_DIST={dist} has no index.html (not a web build)")
    return Path(dist)


def _yellow(px: np.ndarray) -> np.ndarray:
    """Pixels of the label boxes' colour (seatwin.recording.foxglove.BOX_COLOR, 255/217/0), also where a thin
    line is blended with the image."""
    r, g, b = px[..., 0].astype(int), px[..., 1].astype(int), px[..., 2].astype(int)
    return (r > 150) & (g > 110) & (b < 110) & (r - b > 90)


def _box_edges(
    png: np.ndarray, canvas: list[float], size: tuple[int, int], boxes: list[list[tuple[float, float]]]
) -> tuple[list[float], list[float]]:
    """For each box (corners in image pixels) whose bottom edge is inside the image and at least 3 screen pixels
    long: the share of the edge's screen columns with a box-coloured pixel within 2 rows of it, and the same share
    5 to 8 rows below it. The image is drawn fitted into the canvas (aspect kept, centred)."""
    x, y, w, h = canvas
    s = min(w / size[0], h / size[1])
    ox, oy = x + (w - size[0] * s) / 2, y + (h - size[1] * s) / 2
    hits, below = [], []
    for corners in boxes:
        xs, ys = [c[0] for c in corners], [c[1] for c in corners]
        if max(ys) >= size[1] - 1:
            continue
        cols = np.arange(int(np.ceil(ox + min(xs) * s)) + 1, int(ox + max(xs) * s) - 1)
        if len(cols) < 3:
            continue
        row = round(oy + max(ys) * s)
        hits.append(float(_yellow(png[row - 2 : row + 3][:, cols]).any(axis=0).mean()))
        below.append(float(_yellow(png[row + 5 : row + 9][:, cols]).any(axis=0).mean()))
    return hits, below


def _channels(mcap: Path) -> dict[str, tuple[str, int]]:
    """Topic → (schema name, message count) from the MCAP's summary."""
    from mcap.reader import make_reader

    with mcap.open("rb") as f:
        summary = make_reader(f).get_summary()
    counts = summary.statistics.channel_message_counts
    return {c.topic: (summary.schemas[c.schema_id].name, counts[cid]) for cid, c in summary.channels.items()}


def test_page_server_serves_byte_ranges(tmp_path: Path) -> None:
    """The viewer reads a remote MCAP by HTTP Range requests and refuses a server without Accept-Ranges."""
    import urllib.error
    import urllib.request

    tool = _tool()
    (tmp_path / "index.html").write_text("<html>viewer</html>")
    data = bytes(range(256)) * 40
    (tmp_path / "run.mcap").write_bytes(data)
    with tool.serve(tmp_path, {"/seatwin/run.mcap": tmp_path / "run.mcap"}) as base:
        with urllib.request.urlopen(base + "/") as r:
            assert r.read() == b"<html>viewer</html>" and r.headers["Accept-Ranges"] == "bytes"
        for rng, want in (("bytes=10-19", data[10:20]), ("bytes=-8", data[-8:]), ("bytes=10230-", data[10230:])):
            with urllib.request.urlopen(urllib.request.Request(base + "/seatwin/run.mcap", headers={"Range": rng})) as r:
                assert r.status == 206 and r.read() == want, rng
                assert r.headers["Content-Range"].endswith(f"/{len(data)}")
        req = urllib.request.Request(base + "/seatwin/run.mcap", headers={"Range": f"bytes={len(data)}-"})
        with pytest.raises(urllib.error.HTTPError) as err:
            urllib.request.urlopen(req)
        assert err.value.code == 416


@pytest.fixture(scope="module")
def tracked(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A 4 s ferry_crossing run at +36 s with lidar, radar and cameras, tracked into a copy (skips first when
    there is no viewer build or browser)."""
    from seatwin.pipeline.simulate import simulate_run
    from seatwin.pipeline.track import track_into_run

    _dist()
    if _tool().find_browser() is None:
        pytest.skip("no Chromium-family browser on PATH")
    tmp = tmp_path_factory.mktemp("viewer")
    simulate_run(
        "ferry_crossing", tmp / "run", duration=4.0, start_offset=36.0, sensors=("lidar", "radar", "camera"), progress=False
    )
    _, copy = track_into_run(tmp / "run", tmp / "tracked")
    return Path(copy.path)


def _radar_pixels(scene: np.ndarray) -> int:
    """Pixels in the layout's flat radar colour #ff3b30 (255/59/48; the lidar's turbo reds are darker or yellower)."""
    scene = scene.astype(int)
    return int(((abs(scene[..., 0] - 255) <= 8) & (abs(scene[..., 1] - 59) <= 12) & (abs(scene[..., 2] - 48) <= 12)).sum())


def _crop(png: np.ndarray, p: dict) -> np.ndarray:
    x, y, w, h = (round(v) for v in p["canvas"])  # the panel below its toolbar
    assert w > 200 and h > 150, p
    return png[y : y + h, x : x + w]


def _panels(state: dict) -> tuple[list[dict], dict]:
    """The layout's places: the three image panels in the top row, left to right, and the 3-D panel below."""
    panels = state["panels"]
    assert len(panels) == len(json.loads(LAYOUT.read_text())["configById"]) == 4
    top = sorted((p for p in panels if p["rect"][1] < 100), key=lambda p: p["rect"][0])
    assert [p["title"] for p in top] == [f"/camera/{cam}/image_raw" for cam in CAMERAS]
    (scene,) = [p for p in panels if p["rect"][1] >= 100]
    assert scene["title"] == "3D"
    return top, scene


@pytest.mark.slow
def test_tracked_run_in_lichtblick(tracked: Path) -> None:
    from PIL import Image

    from seatwin.recording.reader import open_bag

    dist, tool = _dist(), _tool()
    at_s = 3.5
    # What the bag holds at the seek time: each camera's latest annotation (its boxes' corners) and image size.
    with open_bag(tracked) as rec:
        t_ns = rec.start_ns + round(at_s * 1e9)
        boxes: dict[str, list[list[tuple[float, float]]]] = {cam: [] for cam in CAMERAS}
        for m in rec.messages([f"/camera/{cam}/annotations" for cam in CAMERAS]):
            if m.log_time_ns <= t_ns:
                boxes[m.topic.split("/")[2]] = [[(q.x, q.y) for q in a.points] for a in m.msg.points]
        image = next(rec.messages("/camera/front/image_raw")).msg
        size = (image.width, image.height)
    assert sum(len(b) for b in boxes.values()) > 0
    channels = _channels(tool.run_mcap(tracked))
    assert {"/tracks/scene", "/lidar/points", "/radar/detections", "/ground_truth/markers"} <= set(channels)

    shot = tool.screenshot_run(dist, tracked, layout=LAYOUT, at_s=at_s, width=1400, height=850)
    state = shot.state
    assert "run.mcap" in state["source"]  # the data source is the served run
    # The viewer read every channel of the MCAP, with its schema and message count.
    assert tool.listed_topics(shot.topics_text) == channels
    # No error or warning (a failed Range read, layout fetch or decode); "Transform topics detected" is info.
    assert [a for a in shot.alerts if a[0] != "info"] == [], shot.alerts
    png = np.asarray(Image.open(io.BytesIO(shot.png)).convert("RGB"))
    assert png.shape == (850, 1400, 3)
    top, scene_panel = _panels(state)
    edges = 0
    for cam, p in zip(CAMERAS, top):
        assert _crop(png, p).std() > 15.0, f"{cam}: a blank image panel"
        hits, below = _box_edges(png, p["canvas"], size, boxes[cam])
        edges += len(hits)
        # Every box's bottom edge is drawn in the box colour where the bag puts it (the image fitted into the
        # panel's canvas), and the rows a few pixels below it mostly are not.
        assert all(h >= 0.8 for h in hits), f"{cam}: box edges drawn {hits} (1 = the whole edge)"
        assert not below or float(np.mean(below)) <= 0.3, f"{cam}: box colour below the edges {below}"
    assert edges >= 1, boxes
    scene = _crop(png, scene_panel)
    assert scene.std() > 8.0, "a blank 3-D panel"
    assert _radar_pixels(scene) > 30, "no radar plots drawn"
    colours = np.unique(scene.reshape(-1, 3) // 16, axis=0)
    assert len(colours) > 40, f"the 3-D panel draws few colours ({len(colours)}): no cloud, markers or grid"


@pytest.mark.slow
def test_live_run_in_lichtblick(tracked: Path) -> None:
    """The run as `seatwin view` serves it (the Foxglove SDK's WebSocket server), watched live in the viewer."""
    from PIL import Image

    dist, tool = _dist(), _tool()
    shot = tool.screenshot_live(dist, tracked, layout=LAYOUT, width=1400, height=850)
    source = "".join(shot.state["source"].split())  # the app bar wraps long names
    assert source.startswith("ws://127.0.0.1:") and f"seatwinview{tracked.name}" in source, shot.state["source"]
    listed = tool.listed_topics(shot.topics_text)
    channels = _channels(tool.run_mcap(tracked))
    # Every topic of the run is advertised with its schema; those the layout shows have messages.
    assert {t: schema for t, (schema, _) in listed.items()} == {t: schema for t, (schema, _) in channels.items()}
    shown = {"/lidar/points", "/radar/detections", "/tracks/scene", "/camera/front/image_raw", "/camera/front/annotations"}
    assert all((listed[t][1] or 0) > 0 for t in shown), {t: listed[t] for t in shown}
    assert [a for a in shot.alerts if a[0] != "info"] == [], shot.alerts
    png = np.asarray(Image.open(io.BytesIO(shot.png)).convert("RGB"))
    top, scene_panel = _panels(shot.state)
    for cam, p in zip(CAMERAS, top):
        assert _crop(png, p).std() > 15.0, f"{cam}: a blank image panel"
    assert _radar_pixels(_crop(png, scene_panel)) > 30, "no radar plots drawn"
