"""A preview of a Foxglove layout filled with one instant of a run, as an HTML page (drawn by seatwin, not by
Foxglove): what ``docs/foxglove/seatwin-layout.json`` arranges, for the README when Foxglove itself cannot run.

The page follows the layout's split tree (``direction``, ``splitPercentage``). An ``Image!`` panel shows its
``imageTopic`` at the instant with its ``annotations`` topics drawn as Foxglove draws ImageAnnotations
(LINE_LOOP polygons and texts, in pixel coordinates). A ``3D!`` panel is drawn from above in ``map`` (ENU),
centred on its ``followTf`` frame: the point-cloud topics it lists (lidar coloured by height, radar red)
taken through the recording's tf tree, every vessel's box from ``/ground_truth/markers`` in its body frame,
and the tracks' entities of ``/tracks/scene`` (2σ ellipses, labels). Only what the layout names is drawn.
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from seatwin.errors import InputError


def layout_preview(run: str | Path, layout: str | Path, out_dir: str | Path, at_s: float = 0.0, size: int = 1200) -> Path:
    """Write ``preview.html`` (and a PNG per panel) into ``out_dir`` for ``run`` at ``at_s`` seconds after its
    start; return the page's path. ``size``: the page width in pixels."""
    from seatwin.recording import open_bag

    spec = json.loads(Path(layout).read_text(encoding="utf-8"))
    panels, tree = spec.get("configById"), spec.get("layout")
    if not isinstance(panels, dict) or tree is None:
        raise InputError(layout, "not a Foxglove layout: expected 'configById' and 'layout'")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    images: dict[str, str] = {}
    with open_bag(run) as rec:
        t_ns = rec.start_ns + int(at_s * 1e9)
        for pid, cfg in panels.items():
            name = pid.replace("!", "_") + ".png"
            if pid.startswith("Image!"):
                _image_panel(rec, cfg["imageMode"], t_ns, out / name)
            elif pid.startswith("3D!"):
                _scene_panel(rec, cfg, t_ns, out / name)
            else:
                continue
            images[pid] = name
    body = _split(tree, panels, images)
    page = out / "preview.html"
    page.write_text(
        "<!doctype html><html><head><meta charset='utf-8'><style>"
        "body{margin:0;background:#15151a;font:13px sans-serif;color:#ddd}"
        ".row,.column{display:flex;width:100%;height:100%}.column{flex-direction:column}"
        ".panel{display:flex;flex-direction:column;border:1px solid #333;box-sizing:border-box;min-width:0;min-height:0}"
        ".panel b{padding:3px 6px;background:#222}.panel img{flex:1;min-height:0;object-fit:contain;width:100%}"
        f"</style></head><body><div style='width:{size}px;height:{int(size * 0.75)}px'>{body}</div></body></html>",
        encoding="utf-8",
    )
    return page


def _split(node: Any, panels: dict[str, Any], images: dict[str, str]) -> str:
    if isinstance(node, str):
        cfg = panels.get(node, {})
        title = cfg.get("imageMode", {}).get("imageTopic") or node.split("!")[0] + " " + cfg.get("followTf", "")
        img = f"<img src='{html.escape(images[node])}'>" if node in images else ""
        return f"<div class='panel' style='flex:1'><b>{html.escape(title)}</b>{img}</div>"
    pct = float(node.get("splitPercentage", 50.0))
    kind = "row" if node.get("direction") == "row" else "column"
    first, second = _split(node["first"], panels, images), _split(node["second"], panels, images)
    return (
        f"<div class='{kind}'><div style='flex:{pct:.1f};display:flex;min-width:0;min-height:0'>{first}</div>"
        f"<div style='flex:{100 - pct:.1f};display:flex;min-width:0;min-height:0'>{second}</div></div>"
    )


def _nearest(rec: Any, topic: str, t_ns: int) -> Any:
    """The decoded message of ``topic`` logged nearest to ``t_ns`` (None if the topic is absent)."""
    if topic not in rec.topics:
        return None
    best = None
    for m in rec.messages(topic):
        if best is None or abs(m.log_time_ns - t_ns) < abs(best.log_time_ns - t_ns):
            best = m
        elif m.log_time_ns > t_ns:
            break
    return best


def _image_panel(rec: Any, mode: dict[str, Any], t_ns: int, path: Path) -> None:
    from PIL import Image, ImageDraw

    from seatwin.recording.images import image_to_array, to_rgb

    m = _nearest(rec, mode["imageTopic"], t_ns)
    if m is None:
        raise InputError(rec.path, f"the layout's image topic {mode['imageTopic']} is not in this recording")
    rgb = to_rgb(image_to_array(m.msg), str(m.msg.encoding))
    img = Image.fromarray(np.ascontiguousarray(rgb))
    draw = ImageDraw.Draw(img)
    for topic in mode.get("annotations", {}):
        a = _nearest(rec, topic, m.log_time_ns)
        if a is None:
            continue
        for p in a.msg.points:
            pts = [(q.x, q.y) for q in p.points]
            c = p.outline_color
            draw.line([*pts, pts[0]], fill=(int(255 * c.r), int(255 * c.g), int(255 * c.b)), width=max(1, round(p.thickness)))
        for tx in a.msg.texts:
            draw.text((tx.position.x, tx.position.y), tx.text, fill=(255, 255, 255))
    img.save(path)


def _scene_panel(rec: Any, cfg: dict[str, Any], t_ns: int, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Ellipse, Polygon

    from seatwin.recording.tf_tree import TfTree

    def tree_at(log_ns: int) -> TfTree:
        tree = TfTree(rec.static_transforms())
        tf = _nearest(rec, rec.topic_config.tf, log_ns)
        for tr in tf.msg.transforms if tf is not None else ():
            tt, q = tr.transform.translation, tr.transform.rotation
            tree.add(tr.header.frame_id, tr.child_frame_id, (tt.x, tt.y, tt.z), (q.x, q.y, q.z, q.w))
        return tree

    tree = tree_at(t_ns)
    follow = cfg.get("followTf")
    centre = tree.lookup("map", follow).translation if follow else np.zeros(3)
    half = float(cfg.get("cameraState", {}).get("distance", 120.0))
    fig, ax = plt.subplots(figsize=(8, 5), dpi=110, facecolor="#15151a")
    ax.set_facecolor("#15151a")
    for topic, style in cfg.get("topics", {}).items():
        if not style.get("visible", True) or topic not in rec.topics:
            continue
        msgtype = rec.topics[topic].msgtype
        if msgtype.endswith("PointCloud2"):
            cloud = None  # the latest sweep or scan at the instant (the first, if none is before it)
            for c in rec.point_clouds(topic):
                if cloud is not None and c.log_time_ns > t_ns:
                    break
                cloud = c
            if cloud is None:
                continue
            xyz = tree_at(cloud.log_time_ns).lookup("map", cloud.frame_id).apply(cloud.xyz().astype(float))
            if style.get("colorMode") == "flat":
                ax.scatter(xyz[:, 0], xyz[:, 1], s=14, c=style.get("flatColor", "#ff3b30"), label=topic, zorder=4)
            else:
                ax.scatter(xyz[:, 0], xyz[:, 1], s=1.5, c=xyz[:, 2], cmap="turbo", label=topic, zorder=3)
        elif msgtype.endswith("MarkerArray"):
            m = _nearest(rec, topic, t_ns)
            for mk in m.msg.markers if m is not None else ():
                if mk.type != 1:  # the vessels' boxes
                    continue
                lx, ly = mk.scale.x / 2, mk.scale.y / 2
                corners = np.array([[lx, ly, 0], [lx, -ly, 0], [-lx, -ly, 0], [-lx, ly, 0]]) + [
                    mk.pose.position.x,
                    mk.pose.position.y,
                    0,
                ]
                xy = tree.lookup("map", mk.header.frame_id).apply(corners)[:, :2]
                c = mk.color
                ax.add_patch(Polygon(xy, closed=True, fc=(c.r, c.g, c.b, 0.5), ec=(c.r, c.g, c.b), zorder=2))
        elif msgtype.endswith("SceneUpdate"):
            m = _nearest(rec, topic, t_ns)
            for ent in m.msg.entities if m is not None else ():
                to_map = tree.lookup("map", ent.frame_id)
                for cyl in ent.cylinders:
                    p = to_map.apply([cyl.pose.position.x, cyl.pose.position.y, 0.0])
                    q = cyl.pose.orientation
                    axis = to_map.rotation @ [1 - 2 * q.z * q.z, 2 * q.z * q.w, 0.0]  # the ellipse's major axis
                    angle = math.degrees(math.atan2(axis[1], axis[0]))
                    color = (cyl.color.r, cyl.color.g, cyl.color.b)
                    ax.add_patch(
                        Ellipse(
                            p[:2], max(cyl.size.x, 1.0), max(cyl.size.y, 1.0), angle=angle, fc="none", ec=color, lw=2, zorder=5
                        )
                    )  # noqa: E501
                    label = ent.texts[0].text if ent.texts else ent.id
                    ax.annotate(label, p[:2], xytext=(6, 6), textcoords="offset points", color=color, zorder=6)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half * 0.6, centre[1] + half * 0.6)
    ax.set_aspect("equal")
    ax.grid(color="#333", lw=0.5)
    ax.tick_params(colors="#aaa")
    ax.set_xlabel("east [m] (map)", color="#aaa")
    ax.set_ylabel("north [m] (map)", color="#aaa")
    ax.legend(loc="upper right", fontsize=7, facecolor="#222", labelcolor="#ddd", markerscale=4)
    fig.tight_layout()
    fig.savefig(path, facecolor=fig.get_facecolor())
    plt.close(fig)
