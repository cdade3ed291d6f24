"""The comparison report: one self-contained HTML page (no external resources, figures as base64 PNG)."""

from __future__ import annotations

import base64
import datetime as dt
import html
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from seatwin.evaluation.compare import Comparison
from seatwin.evaluation.truth import TruthSet
from seatwin.report import figures

if TYPE_CHECKING:
    from seatwin.perception.map_mask import WaterMask

_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:2em auto;max-width:1150px;color:#222;padding:0 1em}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}h3{margin-top:1.5em}
table{border-collapse:collapse;margin:.8em 0;font-size:.9em}th,td{border:1px solid #ccc;padding:.25em .6em;text-align:right}
th{background:#f3f3f3}td.l,th.l{text-align:left}tr.avg td{font-weight:bold;background:#fafafa}
img{max-width:100%;height:auto;display:block;margin:.5em 0}.note{color:#555;font-size:.9em}code{background:#f5f5f5;padding:0 .2em}
"""

# Marks the page as rendered once every embedded figure has decoded (read by tests in a headless browser).
_CHECK = """
<script>
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  var ok = imgs.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  document.body.setAttribute('data-figures', ok + '/' + imgs.length);
  document.body.setAttribute('data-figure-widths', imgs.map(function (i) {
    return Math.round(i.getBoundingClientRect().width) + ':' + i.naturalWidth;
  }).join(','));
  document.body.setAttribute('data-content-width', Math.round(parseFloat(getComputedStyle(document.body).width)));
});
</script>
"""


@dataclass
class Clouds:
    """Optional Fig. 5.10 input: both datasets' points (north, east) at one ``time``, ownship and targets marked."""

    time: float
    real: NDArray[np.float64]
    synthetic: NDArray[np.float64]
    ownship: tuple[float, float] | None = None
    targets: list[tuple[str, float, float]] = field(default_factory=list)


@dataclass
class ScenarioResult:
    """The comparisons of one scenario (one per tuning) and its ground truth."""

    name: str
    comparisons: list[Comparison]
    truth: TruthSet
    clouds: list[Clouds] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    """What the compared datasets are (e.g. that the "real" side is itself simulated)."""
    camera: dict | None = None
    """The ``camera`` block of ``seatwin compare`` (lidar vs lidar + camera, boxes); see :func:`camera_section`."""


PIXELS_PER_CSS_PX = 1.2
"""A figure's PNG pixels per CSS pixel on the page (the page narrows a wider one to its column)."""


def png_size(png: bytes) -> tuple[int, int]:
    """(width, height) in pixels from a PNG's IHDR chunk."""
    if png[:8] != b"\x89PNG\r\n\x1a\n" or png[12:16] != b"IHDR":
        raise ValueError("not a PNG")
    return int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")


def _img(png: bytes, alt: str) -> str:
    width = round(png_size(png)[0] / PIXELS_PER_CSS_PX)
    data = base64.b64encode(png).decode("ascii")
    return f'<img alt="{html.escape(alt)}" style="width:{width}px" src="data:image/png;base64,{data}">'


def _f(x: object, spec: str = ".4f") -> str:
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "–"
    return format(x, spec) if isinstance(x, float) else html.escape(str(x))


def _table(header: list[str], rows: list[list[str]], left: int = 1, avg_rows: int = 0) -> str:
    th = "".join(f'<th class="{"l" if i < left else ""}">{html.escape(h)}</th>' for i, h in enumerate(header))
    body = []
    for k, r in enumerate(rows):
        cls = ' class="avg"' if k >= len(rows) - avg_rows else ""
        body.append(f"<tr{cls}>" + "".join(f'<td class="{"l" if i < left else ""}">{c}</td>' for i, c in enumerate(r)) + "</tr>")
    return f"<table><thead><tr>{th}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _ahed_rows(results: list[ScenarioResult]) -> list[dict]:
    return [{"scenario": r.name, **t.to_dict()} for r in results for c in r.comparisons for t in c.targets]


def _ahed_section(results: list[ScenarioResult]) -> str:
    rows = _ahed_rows(results)
    if not rows:
        return "<p>No comparison.</p>"
    form = rows[0]["hellinger_form"]
    other = "printed" if form == "standard" else "standard"
    table = [
        [
            _f(r["scenario"]),
            _f(r["target"]),
            _f(r["tuning"] or "–"),
            "undefined" if r["ahed"] is None else _f(r["ahed"]),
            "undefined" if r[f"ahed_{other}"] is None else _f(r[f"ahed_{other}"]),
            _f(r["n_common"]),
            _f(r["n_only_real"]),
            _f(r["n_only_synthetic"]),
            _f(r["n_both_missing"]),
            _f(r["fraction_only_one"], ".1%"),
            _f(r["mean_covdiff"]),
            _score_cell(r),
        ]
        for r in rows
    ]
    tunings = sorted({r["tuning"] for r in rows})
    for tun in tunings + [None]:
        sel = [r for r in rows if tun is None or r["tuning"] == tun]
        vals = [r["ahed"] for r in sel if r["ahed"] is not None]
        label = "Average, all tunings" if tun is None else f"Average, tuning {tun or '–'}"
        label += f" (n = {len(vals)} of {len(sel)} defined)"
        table.append([label, "", "", "undefined" if not vals else _f(float(np.mean(vals)))] + [""] * 8)
    header = [
        "scenario",
        "target",
        "tracker tuning",
        f"AHED ({form})",
        f"AHED ({other})",
        "common",
        "only real",
        "only synthetic",
        "both missing",
        "only one",
        "mean COVDIFF",
        "fidelity score [95 % CI]",
    ]
    fig = figures.ahed_figure(rows, "AHED per scenario and target (cf. thesis Fig. 5.3)")
    return (
        _table(header, table, left=3, avg_rows=len(tunings) + 1)
        + _img(fig, "AHED bar chart")
        + '<p class="note">AHED averages HED over the instants where both datasets have the target; it cannot see '
        'track loss, so the instants where only one dataset has it are counted beside it ("only one": their '
        "share of the instants where either has it). AHED is undefined for a target without a common instant; "
        "averages leave it out and state over how many targets they are taken. The fidelity score (0 = the same "
        "error distribution and coverage; docs/fidelity-score.md) compares the two datasets' distributions of "
        "tracker errors without pairing instants, so independent noise does not reward a too-clean model; "
        "it is refused (with the reason) when too few instants support it.</p>" + _score_overall(results)
    )


def _score_cell(row: dict) -> str:
    if row.get("score") is None:
        return f"undefined ({_f(row.get('score_reason') or 'not computed')})"
    return f"{_f(row['score'])} [{_f(row['score_ci_low'])}, {_f(row['score_ci_high'])}]"


def _score_overall(results: list[ScenarioResult]) -> str:
    """One line per comparison: the overall score (S5) with its parts."""
    items = []
    for r in results:
        for c in r.comparisons:
            if c.score is None:
                continue
            o = c.score.overall
            value = "undefined" if o.value is None else f"{_f(o.value)} [{_f(o.ci_low)}, {_f(o.ci_high)}]"
            parts = [
                f"{name} {'undefined (' + _f(v.reason) + ')' if v.value is None else _f(v.value)}"
                for name, v in ((k.replace("_", " "), v) for k, v in c.score.plots.items())
            ]
            note = f" — {_f(o.reason)}" if o.reason and o.value is not None else ""
            tuning = f", tuning {_f(c.tuning)}" if c.tuning else ""
            items.append(f"<li>{_f(r.name)}{tuning}: overall fidelity score {value}; {', '.join(parts)}{note}</li>")
    return f"<ul>{''.join(items)}</ul>" if items else ""


def _anees_table(comp: Comparison, target: str) -> str:
    rows = []
    for name, ev in (("Synthetic dataset", comp.synthetic), ("Real dataset", comp.real)):
        s = next(x for x in ev.summaries if x.target == target)
        rows.append(
            [
                name,
                _f(s.anees),
                _f(s.anees_upper),
                _f(s.anees_lower),
                _f(s.n_valid),
                _f(s.anees_verdict),
                _f(s.coverage, ".1%"),
                _f(s.track_switches),
                _f(s.rmse_position, ".2f"),
            ]
        )
    return _table(["", "ANEES", "upper bound", "lower bound", "N_k", "verdict", "coverage", "switches", "RMSE pos [m]"], rows)


def _target_section(result: ScenarioResult, comp: Comparison, target: str, mask) -> str:  # noqa: ANN001
    label = f"{result.name} — {target}" + (f" — tracker tuning “{comp.tuning}”" if comp.tuning else "")
    line = next(t for t in comp.targets if t.target == target)
    parts = [
        f"<h3>{html.escape(label)}</h3>",
        f"<p>AHED {_f(line.ahed)} over {line.n_common} common instants; only real {line.n_only_real}, "
        f"only synthetic {line.n_only_synthetic}, both missing {line.n_both_missing}.</p>",
    ]
    series = comp.series[target]
    if series.common.any():
        parts.append(_img(figures.hellinger_figure(series, f"{label}: HED, COVDIFF, NEES and RMSE differences"), f"HED {label}"))
    parts.append(_anees_table(comp, target))
    ev_valid = comp.real.series[target].valid.any() or comp.synthetic.series[target].valid.any()
    if ev_valid:
        parts.append(_img(figures.metrics_figure(comp, target, f"{label}: tuning metrics"), f"NEES RMSE {label}"))
        parts.append(_img(figures.tracks_figure(comp, result.truth, target, label, mask), f"tracks {label}"))
    else:
        parts.append('<p class="note">Neither dataset has a track on this target: every metric is undefined.</p>')
    return "\n".join(parts)


def _box_rows(boxes: dict) -> list[list[str]]:
    rows = []
    for b in [*boxes["cameras"], boxes["overall"]]:
        rows.append(
            [
                _f(b["camera"]),
                f"{b['n_images_real']} / {b['n_images_synthetic']}",
                _f(b["n_paired_images"]),
                f"{b['n_boxes_real']} / {b['n_boxes_synthetic']}",
                _f(b["n_matched"]),
                _f(b["iou_mean"], ".3f"),
                _f(b["iou_median"], ".3f"),
                _f(b["centre_offset_mean_px"], ".2f"),
                _f(b["centre_offset_p95_px"], ".2f"),
                _f(b["detection_rate_real"], ".1%"),
                _f(b["detection_rate_synthetic"], ".1%"),
                _f(b["detection_rate_difference"], "+.1%"),
            ]
        )
    return rows


def camera_section(result: ScenarioResult) -> str:
    """Lidar alone against lidar + camera (thesis Fig. 5.3 against Fig. 5.16) and the bounding-box comparison."""
    cam = result.camera or {}
    fusion = cam.get("fusion") or {"targets": []}
    detector = _f(cam.get("detector")) + (f" (<code>{_f(cam['model'])}</code>)" if cam.get("model") else "")
    parts = [
        f"<h2>Cameras — {html.escape(result.name)}: lidar alone and lidar + camera</h2>",
        f'<p class="note">Camera detector: {detector}. Each recording is tracked twice, with the lidar alone and with '
        "lidar clusters and camera bearings (thesis Table 5.2's R<sub>c</sub>), and each pair of runs is compared as "
        "above (cf. thesis Fig. 5.3 against Fig. 5.16).</p>",
    ]
    rows = fusion["targets"]
    if rows:
        table = [
            [
                _f(r["target"]),
                _f(r["tuning"] or "–"),
                "undefined" if r["ahed_lidar"] is None else _f(r["ahed_lidar"]),
                "undefined" if r["ahed_lidar_camera"] is None else _f(r["ahed_lidar_camera"]),
                _f(r["n_common_lidar"]),
                _f(r["n_common_lidar_camera"]),
                _f(r["fraction_only_one_lidar"], ".1%"),
                _f(r["fraction_only_one_lidar_camera"], ".1%"),
            ]
            for r in rows
        ]
        n = len(rows)
        table.append(
            [
                f"Average (n = {fusion['ahed_n_lidar']} / {fusion['ahed_n_lidar_camera']} of {n} defined)",
                "",
                "undefined" if fusion["ahed_mean_lidar"] is None else _f(fusion["ahed_mean_lidar"]),
                "undefined" if fusion["ahed_mean_lidar_camera"] is None else _f(fusion["ahed_mean_lidar_camera"]),
            ]
            + [""] * 4
        )
        header = ["target", "tracker tuning", "AHED lidar", "AHED lidar + camera", "common", "common (+ camera)"]
        header += ["only one", "only one (+ camera)"]
        bars = [
            {
                "scenario": f"tuning {r['tuning']}" if r["tuning"] else result.name,
                "target": r["target"],
                "tuning": name,
                "ahed": r[key],
            }
            for r in rows
            for name, key in (("lidar", "ahed_lidar"), ("lidar + camera", "ahed_lidar_camera"))
        ]
        fig = figures.ahed_figure(bars, "AHED with lidar alone and with lidar + camera (cf. thesis Fig. 5.3, 5.16)")
        parts += [_table(header, table, left=2, avg_rows=1), _img(fig, "AHED lidar and lidar + camera")]
    parts.extend(f'<p class="note">{_f(why)}</p>' for why in cam.get("skipped", []))
    for boxes in cam.get("boxes", []):
        parts.append(f"<h3>Bounding boxes: {_f(boxes['real'])} against {_f(boxes['synthetic'])}</h3>")
        header = ["camera", "images r / s", "paired", "boxes r / s", "matched", "IoU mean", "IoU median"]
        header += ["centre offset mean [px]", "centre offset p95 [px]", "detection rate r", "detection rate s", "s − r"]
        parts.append(_table(header, _box_rows(boxes), avg_rows=1))
        parts.append(
            f'<p class="note">Images of a camera paired within {boxes["time_tolerance_s"]:g} s; boxes matched one to '
            f"one by the Hungarian method on IoU, a pair counting at IoU ≥ {boxes['min_iou']:g}. Detection rate: the "
            "share of the objects seen in either run (matched pairs plus each side's unmatched boxes) that this run "
            "has.</p>"
        )
    return "\n".join(parts)


def render_report(results: list[ScenarioResult], title: str = "seatwin comparison report", mask=None) -> str:  # noqa: ANN001
    """The report page as a string (see :func:`write_report`)."""
    opts = results[0].comparisons[0].options if results and results[0].comparisons else None
    conv = ""
    if opts is not None:
        conv = (
            f'<p class="note">Conventions: HED form <code>{opts.form}</code> (standard: mean term exp(−NEES/8); '
            f"printed (5.30): exp(−NEES/16)); both datasets without a track: <code>{opts.both_missing}</code>; "
            f"instants matched within {opts.time_tolerance:g} s; track-to-truth gate {opts.gate:g} m; "
            f"{'confirmed tracks only' if opts.confirmed_only else 'all tracks'}.</p>"
        )
    body = [
        f"<h1>{html.escape(title)}</h1>",
        f'<p class="note">Generated {dt.datetime.now(dt.UTC):%Y-%m-%d %H:%M UTC} by seatwin.</p>',
        conv,
        "<h2>Averaged Hellinger distances</h2>",
        _ahed_section(results),
        *(camera_section(res) for res in results if res.camera),
    ]
    for res in results:
        body.append(f"<h2>Scenario {html.escape(res.name)}</h2>")
        body.extend(f'<p class="note">{html.escape(n)}</p>' for n in res.notes)
        for comp in res.comparisons:
            for target in res.truth.names:
                body.append(_target_section(res, comp, target, mask))
        for cl in res.clouds:
            stamp = dt.datetime.fromtimestamp(cl.time, dt.UTC).strftime("%H:%M:%S")
            body.append(f"<h3>Point clouds at {stamp}</h3>")
            body.append(
                _img(
                    figures.clouds_figure(
                        cl.real, cl.synthetic, f"{res.name}: point clouds at {stamp} UTC", cl.ownship, cl.targets
                    ),
                    f"clouds {stamp}",
                )
            )
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>{html.escape(title)}</title><style>{_CSS}</style></head>\n<body>\n"
        + "\n".join(body)
        + _CHECK
        + "\n</body></html>\n"
    )


def write_report(
    out_dir: str | os.PathLike[str],
    results: list[ScenarioResult],
    title: str = "seatwin comparison report",
    mask: WaterMask | None = None,
) -> Path:
    """Write ``index.html`` (self-contained, works offline) into ``out_dir``; return its path.

    ``mask`` is a water mask (``is_water(north, east)``, e.g. :func:`seatwin.perception.map_mask.load_mask`)
    drawn as land under the track plots.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    page = out / "index.html"
    page.write_text(render_report(results, title, mask), encoding="utf-8")
    return page


def write_comparison_report(
    out_dir: str | os.PathLike[str],
    comparisons: list[Comparison],
    truth: TruthSet,
    title: str = "seatwin comparison report",
    scenario: str = "scenario",
    mask: WaterMask | None = None,
    clouds: list[Clouds] | None = None,
    notes: list[str] | None = None,
    camera: dict | None = None,
) -> Path:
    """The report of one scenario compared under one or more tunings; ``notes`` say what the datasets are;
    ``camera``: the camera block of ``seatwin compare`` (its own section)."""
    result = ScenarioResult(scenario, comparisons, truth, clouds or [], notes or [], camera)
    return write_report(out_dir, [result], title, mask)
