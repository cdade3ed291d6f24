"""Figures of thesis 4.1–4.2 recomputed: 4.6 (filter mask), 4.8 (camera-count gain),
4.12 / 4.13 (error against distance for the RGB camera and the lidar), and the part-5
verification figure (depth-buffer vs exact points, with and without the filter)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from seatwin.sensors.depthbuffer.errors import camera_count_gain, error, error_components
from seatwin.sensors.depthbuffer.filter import grid_columns, grid_directions, spherical_filter
from seatwin.sensors.depthbuffer.projection import DepthCamera, camera_hfov, camera_vfov, camera_width
from seatwin.sensors.depthbuffer.table import TableRow, lidar_equation_row, lidar_row, rgb_row


def _plt():  # noqa: ANN202
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def filter_mask(n_sw: int = 256, n_sh: int = 16, n_c: int = 4, n_ch: int = 64, vfov_s: float = math.radians(30.0)) -> np.ndarray:
    """The mask ``M`` of Fig. 4.6 (one camera): the thesis's beam grid (4.12) through 4.18."""
    hfov = camera_hfov(n_c)
    cam = DepthCamera(round(camera_width(n_ch, vfov_s, hfov)), n_ch, camera_vfov(vfov_s, hfov), 0.05, 100.0)
    return spherical_filter(grid_directions(n_sw, n_sh, n_c, vfov_s), cam, n_c, grid_columns(n_sw, n_sh, n_c)).mask(0)


def fig_filter_mask(path: Path, n_sw: int = 256, n_sh: int = 16, n_c: int = 4, n_ch: int = 64) -> Path:
    """Fig. 4.6: the spherical projection filter as an image mask."""
    plt = _plt()
    m = filter_mask(n_sw, n_sh, n_c, n_ch)
    fig, ax = plt.subplots(figsize=(8, 3.6))
    ax.imshow(m, origin="lower", cmap="gray", interpolation="nearest")
    size = f"{m.shape[1]}×{m.shape[0]} px"
    ax.set_title(rf"Spherical projection filter (Fig. 4.6): $N_{{s,w}}$={n_sw}, $N_{{s,h}}$={n_sh}, $N_c$={n_c}, {size}")
    ax.set_xlabel(r"$x^d$ [pixel]")
    ax.set_ylabel(r"$y^d$ [pixel]")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def fig_camera_gain(path: Path, n_max: int = 16) -> Path:
    """Fig. 4.8: ``1/cos(π/N_c)``, the diminishing return of more cameras."""
    plt = _plt()
    n = np.arange(3, n_max + 1)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(n, camera_count_gain(n), "o-")
    ax.set_xlabel(r"number of cameras $N_c$")
    ax.set_ylabel(r"$1\,/\cos(\pi / N_c)$")
    ax.set_title(r"Fig. 4.8: factor of $C_2$ (4.34)")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def error_curves(row: TableRow, samples: int = 200) -> dict[str, np.ndarray]:
    """Total and component errors (4.21–4.22) along the frustum's negative corner ray, against distance."""
    d = np.geomspace(row.near, row.far, samples)
    q = -d[:, None] * np.array([math.tan(row.hfov_c / 2), math.tan(row.vfov_c / 2), 1.0])
    comp = np.abs(error_components(q, row.camera))
    return {"distance": d, "total": error(q, row.camera), "x": comp[:, 0], "y": comp[:, 1], "z": comp[:, 2]}


def fig_error_vs_distance(path: Path, row: TableRow, title: str, extra: TableRow | None = None) -> Path:
    """Fig. 4.12 / 4.13: total, component-wise and maximum error against distance (log axes)."""
    plt = _plt()
    c = error_curves(row)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.loglog(c["distance"], c["total"], "k-", lw=2, label=r"$\varepsilon^v$ (4.22)")
    ax.loglog(c["distance"], c["x"], label=r"$|x^v_\varepsilon|$")
    ax.loglog(c["distance"], c["y"], label=r"$|y^v_\varepsilon|$")
    ax.loglog(c["distance"], c["z"], label=r"$|z^v_\varepsilon|$")
    ax.axhline(row.eps_max, color="r", ls="--", label=rf"$\varepsilon_{{max}}$ = {row.eps_max:.3g} m (4.32)")
    if extra is not None:
        e = error_curves(extra)
        eps_max = rf"$\varepsilon_{{max}}$ {extra.eps_max:.3g} m"
        ax.loglog(e["distance"], e["total"], "k:", label=rf"$\varepsilon^v$, {extra.sensor} ({eps_max})")
    ax.set_xlabel(r"distance $|z^v|$ along the frustum corner [m]")
    ax.set_ylabel("error [m]")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


ERROR_PLOTS = ["fig4_6_filter_mask.png", "fig4_8_camera_gain.png", "fig4_12_rgb_error.png", "fig4_13_lidar_error.png"]
"""The files :func:`write_error_plots` writes."""


def write_error_plots(out: Path) -> list[Path]:
    """Write Fig. 4.6, 4.8, 4.12 and 4.13 into ``out`` (:data:`ERROR_PLOTS`)."""
    out.mkdir(parents=True, exist_ok=True)
    return [
        fig_filter_mask(out / ERROR_PLOTS[0]),
        fig_camera_gain(out / ERROR_PLOTS[1]),
        fig_error_vs_distance(out / ERROR_PLOTS[2], rgb_row(), "Fig. 4.12: RGB camera (Table 4.1)"),
        fig_error_vs_distance(
            out / ERROR_PLOTS[3],
            lidar_row(),
            "Fig. 4.13: lidar (Table 4.1 as printed)",
            extra=lidar_equation_row("lidar_eq417", 8, n_ch=3104),
        ),
    ]


def fig_verification(path: Path, results: dict, rings: dict | None = None) -> Path:
    """Part-5 figure: error against range for both modes on the harbour scene (+ rings on a plane)."""
    plt = _plt()
    ncols = 2 if rings else 1
    fig, axes = plt.subplots(1, ncols, figsize=(6.5 * ncols, 4.8))
    axes = np.atleast_1d(axes)
    ax = axes[0]
    colors = {"filter": "tab:blue", "legacy": "tab:orange"}
    for name, res in results.items():
        ax.semilogy(
            res.range,
            np.maximum(res.distance, 1e-5),
            ".",
            ms=2.5,
            alpha=0.5,
            color=colors.get(name),
            label=f"{name} (p99 {np.percentile(res.distance, 99):.3g} m)",
        )
    any_res = next(iter(results.values()))
    ax.axhline(any_res.eps_max, color="r", ls="--", label=rf"$\varepsilon_{{max}}$ = {any_res.eps_max:.3g} m")
    ax.set_xlabel("range of the exact point [m]")
    ax.set_ylabel("|depth-buffer point − exact point| [m]")
    ax.set_title(r"Default harbour, VLP-16, $N_c$ = 8 (edges excluded)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, markerscale=4)
    if rings:
        ax = axes[1]
        for name, pts in rings.items():
            ax.plot(pts[:, 0], pts[:, 1], ".", ms=1.0, color=colors.get(name), label=name)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title(r"Rings on a flat ground plane, $N_c$ = 4 (cf. Fig. 4.7)")
        ax.legend(markerscale=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path
