"""Table 4.1 of the thesis recomputed from its printed parameters, plus rows that follow
consistently from the equations, each with warnings for what does not add up.

Rows (``sensor``):

* ``rgb`` — the printed RGB camera row.
* ``lidar`` — the printed lidar row (VFOV_c 41.5°, HFOV_c 45°, N_c 8, N_c,h 3104); N_c,w is
  taken from 4.16 (4433), since the printed 32768 does not follow from any equation.
* ``lidar_eq417`` — everything from the equations for the VLP-16 (VFOV_s 30°) with N_c = 8:
  HFOV_c by 4.14, VFOV_c by 4.17, N_c,w by 4.16. This is the configuration the depth-buffer
  lidar model uses by default.
* ``lidar_nc4`` — the printed VFOV_c (41.5°) is what 4.17 gives for N_c = 4; this row is that
  configuration (HFOV_c 90°, N_c,w 8191 by 4.16).
* ``lidar_eq436`` — N_c,h from the printed memory ``B = 3.3·10^8`` through 4.36 with N_c = 8.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from seatwin.sensors.depthbuffer.errors import (
    grazing_term,
    height_from_memory,
    max_error,
    max_error_conditions,
    max_error_numeric,
    pixel_deviation_max,
    range_error_bound,
    storage_term,
    video_memory,
    video_memory_lidar,
)
from seatwin.sensors.depthbuffer.projection import (
    DEPTH_24BIT,
    DepthCamera,
    aspect_ratio,
    camera_hfov,
    camera_vfov,
    camera_width,
)

VLP16_VFOV_S = math.radians(30.0)
"""The VLP-16's vertical field of view VFOV_s (thesis 4.2.3)."""


@dataclass(frozen=True)
class PrintedRow:
    """A row as printed in Table 4.1 (degrees, metres, bytes)."""

    vfov_c_deg: float
    hfov_c_deg: float
    n_c: int
    n_ch: int
    n_cw: int
    n_cd: int
    near: float
    far: float
    eps_max: float
    bytes: float


PRINTED_RGB = PrintedRow(65.4, 75.0, 1, 512, 612, DEPTH_24BIT, 0.08, 1e4, 140.0, 9.4e4)
PRINTED_LIDAR = PrintedRow(41.5, 45.0, 8, 3104, 32768, DEPTH_24BIT, 0.05, 100.0, 0.04, 3.3e8)


@dataclass
class TableRow:
    """One recomputed row; ``to_json`` gives the ``seatwin errors --json`` form."""

    sensor: str
    vfov_c: float
    hfov_c: float
    n_c: int
    n_ch: int
    n_cw: int
    near: float
    far: float
    n_cd: int = DEPTH_24BIT
    warnings: list[str] = field(default_factory=list)

    @property
    def camera(self) -> DepthCamera:
        return DepthCamera(self.n_cw, self.n_ch, self.vfov_c, self.near, self.far, self.n_cd)

    @property
    def eps_max(self) -> float:
        """4.32 at the row's own HFOV_c and VFOV_c."""
        return max_error(self.camera, self.hfov_c)

    @property
    def bytes(self) -> float:
        """4.35 (general form)."""
        return video_memory(self.n_cw, self.n_ch, self.n_c, self.n_cd)

    def to_json(self) -> dict:
        return {
            "sensor": self.sensor,
            "vfov_c_deg": math.degrees(self.vfov_c),
            "hfov_c_deg": math.degrees(self.hfov_c),
            "n_c": self.n_c,
            "n_ch": self.n_ch,
            "n_cw": self.n_cw,
            "n_cd": self.n_cd,
            "near": self.near,
            "far": self.far,
            "eps_max": self.eps_max,
            "bytes": self.bytes,
            "warnings": list(self.warnings),
        }


def agrees_with_print(value: float, printed: float, digits: int = 2) -> bool:
    """True when ``value`` rounds to ``printed`` at the print's precision (``digits`` significant, 1 for 0.04)."""
    sig = len(f"{printed:.{digits}g}".split("e")[0].replace(".", "").lstrip("0").rstrip("0")) or 1
    return float(f"{value:.{sig}g}") == float(f"{printed:.{sig}g}")


def _check(row: TableRow, printed: PrintedRow | None = None) -> TableRow:
    """Append warnings: failed 4.33 conditions, aspect (4.3) mismatch, differences to the print."""
    cam = row.camera
    for name, ok in max_error_conditions(cam).items():
        if not ok:
            num = max_error_numeric(cam, row.hfov_c)
            row.warnings.append(
                f"condition {name} fails, so 4.32 is not proven to be the maximum; a search over the "
                f"frustum finds max ε = {num:.4g} m (4.32: {row.eps_max:.4g} m)"
            )
    a_fov = aspect_ratio(row.hfov_c, row.vfov_c)
    if abs(a_fov - cam.aspect) > 1e-3 * a_fov:
        row.warnings.append(
            f"aspect ratio (4.3) broken: tan(HFOV_c/2)/tan(VFOV_c/2) = {a_fov:.4f} but N_cw/N_ch = "
            f"{cam.aspect:.4f}; HFOV_c and VFOV_c cannot both hold for one camera (N_cw = "
            f"{row.n_ch * a_fov:.0f} would fit)"
        )
    if printed is not None:
        if not agrees_with_print(row.eps_max, printed.eps_max):
            row.warnings.append(
                f"ε_max recomputed {row.eps_max:.4g} m, table prints {printed.eps_max:g} m "
                f"({100 * (row.eps_max / printed.eps_max - 1):+.0f} %)"
            )
        if not agrees_with_print(row.bytes, printed.bytes):
            row.warnings.append(
                f"B recomputed by 4.35 = {row.bytes:.4g} bytes, table prints {printed.bytes:.2g} "
                f"(factor {row.bytes / printed.bytes:.3g})"
            )
    return row


def rgb_row() -> TableRow:
    """The printed RGB row."""
    p = PRINTED_RGB
    row = TableRow("rgb", math.radians(p.vfov_c_deg), math.radians(p.hfov_c_deg), p.n_c, p.n_ch, p.n_cw, p.near, p.far, p.n_cd)
    return _check(row, p)


def lidar_row() -> TableRow:
    """The printed lidar row, with N_c,w from 4.16 instead of the printed 32768."""
    p = PRINTED_LIDAR
    hfov = math.radians(p.hfov_c_deg)
    n_cw = round(camera_width(p.n_ch, VLP16_VFOV_S, hfov))
    row = TableRow("lidar", math.radians(p.vfov_c_deg), hfov, p.n_c, p.n_ch, n_cw, p.near, p.far, p.n_cd)
    eq417 = math.degrees(camera_vfov(VLP16_VFOV_S, camera_hfov(p.n_c)))
    nc4 = math.degrees(camera_vfov(VLP16_VFOV_S, camera_hfov(4)))
    row.warnings.append(
        f"VFOV_c {p.vfov_c_deg}° does not follow from 4.17 with VFOV_s 30° and N_c = {p.n_c} "
        f"({eq417:.1f}°); it does with N_c = 4 (HFOV_s 90°: {nc4:.1f}°)"
    )
    big = DepthCamera(p.n_cw, p.n_ch, math.radians(p.vfov_c_deg), p.near, p.far, p.n_cd)
    failed = [k for k, ok in max_error_conditions(big).items() if not ok]
    row.warnings.append(
        f"printed N_cw = {p.n_cw} (2^15) does not follow from 4.16 ({camera_width(p.n_ch, VLP16_VFOV_S, hfov):.1f} "
        f"for N_c = 8; {camera_width(p.n_ch, VLP16_VFOV_S, camera_hfov(4)):.1f} ≈ 8192 for N_c = 4, and "
        f"4 × 8192 = 32768 is the stitched width of four cameras); with it B would be "
        f"{video_memory(p.n_cw, p.n_ch, p.n_c, p.n_cd):.3g} bytes, not the printed 3.3e8, and "
        f"{', '.join(failed) or 'no condition'} would fail"
    )
    consistent = lidar_equation_row("lidar_eq417", p.n_c, n_ch=p.n_ch)
    row.warnings.append(
        f"ε_max {row.eps_max:.4f} m matches the printed {p.eps_max} m only with the printed VFOV_c; with VFOV_c "
        f"from 4.17 for N_c = {p.n_c} it is {consistent.eps_max:.4f} m (row lidar_eq417)"
    )
    return _check(row, p)


def lidar_equation_row(sensor: str, n_c: int, n_ch: int | None = None, b_s: float | None = None) -> TableRow:
    """A VLP-16 row where every dependent parameter follows from 4.14, 4.16, 4.17 (and 4.36 with ``b_s``)."""
    p = PRINTED_LIDAR
    hfov = camera_hfov(n_c)
    if n_ch is None:
        if b_s is None:
            raise ValueError("give n_ch or b_s")
        n_ch = round(height_from_memory(b_s, n_c, p.n_cd, VLP16_VFOV_S))
    n_cw = round(camera_width(n_ch, VLP16_VFOV_S, hfov))
    row = TableRow(sensor, camera_vfov(VLP16_VFOV_S, hfov), hfov, n_c, n_ch, n_cw, p.near, p.far, p.n_cd)
    return _check(row)


def table_rows() -> list[TableRow]:
    """All rows of the recomputed Table 4.1."""
    eq436 = lidar_equation_row("lidar_eq436", 8, b_s=PRINTED_LIDAR.bytes)
    eq436.warnings.append(
        f"4.36 with B_s = 3.3e8 and N_c = 8 gives N_ch = "
        f"{height_from_memory(PRINTED_LIDAR.bytes, 8, DEPTH_24BIT, VLP16_VFOV_S):.1f} (the printed 3104 "
        f"gives B_s = {video_memory_lidar(3104, 8, DEPTH_24BIT, VLP16_VFOV_S):.4g} ≈ 3.3e8): the thesis sized "
        "N_ch for N_c = 8"
    )
    return [
        rgb_row(),
        lidar_row(),
        lidar_equation_row("lidar_eq417", 8, n_ch=PRINTED_LIDAR.n_ch),
        lidar_equation_row("lidar_nc4", 4, n_ch=PRINTED_LIDAR.n_ch),
        eq436,
    ]


BOUND_RANGES_M = (10.0, 25.0, 50.0, 100.0)
BOUND_INCIDENCES_DEG = (0.0, 45.0, 60.0, 75.0, 85.0)


def range_bound(row: TableRow | None = None) -> dict:
    """The complete range-error bound next to Table 4.1, for the depth-buffer lidar's row (``lidar_eq417``).

    Per range and incidence (from the normal): the storage term (one level of 4.21, the thesis's
    truncated ``z^d``), the grazing term at the largest pixel deviation ``δ_max``, their sum (the
    thesis's filter) and the bound of ``depthbuffer-plane`` on a planar surface with the 24-bit
    buffer (:func:`~seatwin.sensors.depthbuffer.errors.range_error_bound`).
    """
    row = row if row is not None else lidar_equation_row("lidar_eq417", 8, n_ch=PRINTED_LIDAR.n_ch)
    cam = row.camera
    dev = pixel_deviation_max(cam)
    rows = []
    for r in BOUND_RANGES_M:
        for i_deg in BOUND_INCIDENCES_DEG:
            i = math.radians(i_deg)
            rows.append(
                {
                    "range_m": r,
                    "incidence_deg": i_deg,
                    "storage_m": float(storage_term(r, cam)),
                    "grazing_m": float(grazing_term(r, dev, i)),
                    "filter_m": float(range_error_bound(r, i, cam)),
                    "plane_m": float(range_error_bound(r, i, cam, plane=True)),
                }
            )
    return {"sensor": row.sensor, "pixel_deviation_max_deg": math.degrees(dev), "rows": rows}


def table_json() -> dict:
    """``{"rows": [...], "range_bound": {...}}`` as printed by ``seatwin errors --json``."""
    rows = table_rows()
    return {"rows": [r.to_json() for r in rows], "range_bound": range_bound(rows[2])}
