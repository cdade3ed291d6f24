"""The reports' figures as a reader sees them (issue 25, item 12): each has a title inside the figure, maths as
mathtext (no literal carets), no legend over a data point; in the page they are shown large (their width in CSS
pixels, up to the column) with little white margin, and no paragraph is printed twice (the browser half of this
is ``test_report.py::test_renders_in_headless_chromium``)."""

from __future__ import annotations

import base64
import io
import re

import numpy as np
import pytest

import seatwin.report.figures as figures
from seatwin.evaluation.compare import compare
from seatwin.evaluation.tracks_io import Tracks
from seatwin.evaluation.truth import TruthSet, TruthTrack
from seatwin.perception.map_mask import load_mask
from seatwin.report import Clouds, write_comparison_report
from seatwin.report.html import PIXELS_PER_CSS_PX, png_size


def _points(artist, ax) -> np.ndarray:  # noqa: ANN001
    """Display coordinates (n, 2) of an artist's data points (line vertices, scatter offsets, collection vertices)."""
    from matplotlib.collections import PathCollection
    from matplotlib.lines import Line2D

    if isinstance(artist, Line2D):
        xy = np.asarray(artist.get_xydata(), float).reshape(-1, 2)
        return artist.get_transform().transform(xy) if len(xy) else xy
    if isinstance(artist, PathCollection):
        off = np.asarray(artist.get_offsets(), float).reshape(-1, 2)
        return artist.get_offset_transform().transform(off) if len(off) else off
    paths = getattr(artist, "get_paths", lambda: [])()
    verts = [p.vertices for p in paths if len(p.vertices)]
    if not verts:
        return np.empty((0, 2))
    return artist.get_transform().transform(np.concatenate(verts))


def figure_problems(fig) -> list[str]:  # noqa: ANN001
    """Every problem found in ``fig`` (empty: none), each naming the figure's title and what is wrong."""
    from matplotlib.text import Text

    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    titles = [t.get_text() for t in [fig._suptitle, *(ax.title for ax in fig.axes)] if t is not None and t.get_text().strip()]
    name = (titles[0] if titles else "<untitled>").splitlines()[0][:60]
    problems = [] if titles else [f"{name}: no title"]
    box = fig.bbox
    for t in fig.findobj(Text):
        s = t.get_text()
        if not t.get_visible() or not s.strip():
            continue
        if "^" in re.sub(r"\$[^$]*\$", "", s):
            problems.append(f"{name}: literal caret in {s!r} (write maths as $…$)")
        if t in (fig._suptitle, *(ax.title for ax in fig.axes)):
            e = t.get_window_extent(renderer)
            if e.x0 < box.x0 - 1 or e.x1 > box.x1 + 1 or e.y1 > box.y1 + 1:
                problems.append(f"{name}: title {s[:40]!r} reaches outside the figure")
    for ax in fig.axes:
        leg = ax.get_legend()
        if leg is None or not leg.get_visible():
            continue
        lb = leg.get_window_extent(renderer)
        for artist in [*ax.get_lines(), *ax.collections]:
            if not artist.get_visible():
                continue
            pts = _points(artist, ax)
            pts = pts[np.isfinite(pts).all(axis=1)]
            inside = (pts[:, 0] > lb.x0) & (pts[:, 0] < lb.x1) & (pts[:, 1] > lb.y0) & (pts[:, 1] < lb.y1)
            if inside.any():
                problems.append(f"{name}: the legend covers {int(inside.sum())} data point(s) of {artist.get_label()!r}")
                break
    return problems


def _tracks(offset: float, start: int, var: float, north0: float = 0.0) -> Tracks:
    k = np.arange(start, 30)
    n = len(k)
    state = np.column_stack([k * 1.0 + offset + north0, np.ones(n), np.full(n, 10.0), np.zeros(n)])
    cov = np.tile(np.diag([var, 0.1, var, 0.1]), (n, 1, 1))
    return Tracks(1.6e9 + k, np.ones(n, int), np.full(n, 0.9), state, cov, np.ones(n, bool), 1.6e9 + np.arange(30.0))


@pytest.fixture(scope="module")
def captured(tmp_path_factory):
    """Every figure of a compare report (and the fidelity ranking and tracking figures), checked as it is saved."""
    found: list[tuple[str, list[str]]] = []
    original = figures.to_png

    def checking(fig):  # noqa: ANN001, ANN202
        found.append((fig.texts[0].get_text() if fig.texts else "", figure_problems(fig)))
        return original(fig)

    mp = pytest.MonkeyPatch()
    mp.setattr(figures, "to_png", checking)
    try:
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
        clouds = [Clouds(float(t[5]), rng.normal(size=(300, 2)) * 20, rng.normal(size=(400, 2)) * 20, (0.0, 0.0), [])]
        page = write_comparison_report(
            tmp_path_factory.mktemp("report"), comps, truth, title="quality", scenario="s", mask=load_mask("harbour"),
            clouds=clouds, notes=["“Real” dataset: simulated by seatwin. “Synthetic” dataset: another seed."],
        )  # fmt: skip
        from seatwin.fidelity.report import ranking_figure

        rows = [
            {"model": m, "score": s, "ci_low": s - 0.1, "ci_high": s + 0.1, "ahed": a}
            for m, s, a in [("fitted", 0.3, 0.2), ("no_bias", 0.35, 0.21), ("default", 0.9, 0.6)]
        ]
        ranking_figure(rows, "fidelity score by model")
        figures.tracking_figure(real, truth, load_mask("harbour"), "tracks")
    finally:
        mp.undo()
    return page, found


def test_every_report_figure_reads_well(captured):
    _, found = captured
    assert len(found) >= 8
    problems = [p for _, ps in found for p in ps]
    assert not problems, "\n".join(problems)


def test_figures_are_shown_large_with_small_margins(captured):
    from PIL import Image

    page, _ = captured
    text = page.read_text()
    imgs = re.findall(r'<img alt="[^"]*" style="width:(\d+)px" src="data:image/png;base64,([^"]+)"', text)
    assert len(imgs) >= 6 and len(imgs) == text.count("<img ")
    for css_width, data in imgs:
        png = base64.b64decode(data)
        w, h = png_size(png)
        assert int(css_width) == round(w / PIXELS_PER_CSS_PX)
        assert int(css_width) >= 600, f"a figure only {css_width} px wide"
        gray = np.asarray(Image.open(io.BytesIO(png)).convert("L"))
        ink_rows = np.flatnonzero((gray < 250).any(axis=1))
        ink_cols = np.flatnonzero((gray < 250).any(axis=0))
        margins = [ink_rows[0], h - 1 - ink_rows[-1], ink_cols[0], w - 1 - ink_cols[-1]]
        assert max(margins) <= 0.05 * max(w, h), f"white margins {margins} px of {w} × {h}"


def test_no_paragraph_twice(captured):
    """Within a section (between headings) no paragraph repeats; the same note under two targets' headings is fine."""
    page, _ = captured
    sections = re.split(r"<h[1-4][^>]*>", page.read_text())
    assert len(sections) > 5
    for sec in sections:
        paragraphs = [re.sub(r"\s+", " ", p).strip() for p in re.findall(r"<p[^>]*>(.*?)</p>", sec, flags=re.S)]
        repeated = sorted({p[:80] for p in paragraphs if paragraphs.count(p) > 1})
        assert not repeated, repeated


def test_the_checks_find_what_they_look_for():
    """A figure with each fault: no title, a literal caret, a legend over a point; and a clean one."""
    plt = figures._plt()
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.plot([0, 1, 2], [0, 1, 2], "o", label="x^v_ε")
    ax.plot([0.05], [1.95], "s", label="under the legend")
    ax.legend(loc="upper left")
    found = figure_problems(fig)
    assert any("no title" in p for p in found)
    assert any("literal caret" in p for p in found)
    assert any("legend covers" in p and "under the legend" in p for p in found)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.plot([0, 1, 2], [0, 1, 2], "o", label="$x^v_\\varepsilon$")
    ax.set_title("clean")
    ax.legend(loc="lower right")
    assert figure_problems(fig) == []
    plt.close(fig)


def test_the_figures_seatwin_writes_as_files_read_well(tmp_path, monkeypatch):
    """The same checks on the figures the verbs write as files (scenario plot, lidar sweep, GNSS quality, depth-buffer
    errors, tracking), through ``Figure.savefig``."""
    from matplotlib.figure import Figure

    from seatwin.groundtruth.examples import EXAMPLES_DIR, ORIGIN
    from seatwin.groundtruth.plots import write_plots
    from seatwin.groundtruth.vessel import VesselSpec
    from seatwin.pipeline import compute_ground_truth, lidar_snapshot, load_scenario, plot_scenario, write_error_plots

    found: list[str] = []
    saved = []
    original = Figure.savefig

    def checking(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN202
        saved.append(args[0])
        found.extend(figure_problems(self))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", checking)
    root = figures.__file__.rsplit("/src/", 1)[0]
    for spec in ("ferry_crossing", f"{root}/docs/examples/extending/my_scenario.yaml"):
        plot_scenario(load_scenario(spec), tmp_path / f"{len(saved)}.png")
    lidar_snapshot("ferry_crossing", 20, tmp_path / "sweep.png")
    e = EXAMPLES_DIR
    gt = compute_ground_truth([VesselSpec("Havfruen", (e / "havfruen_bow.pos", e / "havfruen_stern.pos"))], ORIGIN)
    write_plots(gt, tmp_path)
    write_error_plots(tmp_path / "errors")
    assert len(saved) >= 9
    assert not found, "\n".join(found)
