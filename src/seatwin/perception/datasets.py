"""Real radar datasets: readers, and importers that write them as seatwin recordings.

* joyride (``joyride.mat``, CC0): VIMMJIPDA radar experiments near Trondheim — per scan the
  radar plots ``[north, east]`` (rows with inf invalid), ground truth of the target boat and
  of the ownship Telemetron ``[north, v_north, east, v_east]``, POSIX times.
* Ravnkloa shore radar 2023 (CSV, CC0): ``scan_time_s,north_m,east_m``; radar at north −8 m,
  east 0 m of the Fosenkaia NED frame; no target ground truth.

Importers go through :class:`seatwin.recording.RecordingWriter`: radar plots as world-frame
radar clouds, ground truth as the recording's pose/odometry topics; the manifest's
``metadata.tracking`` suggests the tuning, map and plot merging to ``seatwin track``.
"""

from __future__ import annotations

import datetime as dt
import math
import os
import struct
import zlib
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, parse_csv, read_text

Array = NDArray[np.float64]

RAVNKLOA_RADAR_POSITION = (-8.0, 0.0)
"""North, east [m] of the Ravnkloa shore radar in the Fosenkaia NED frame (data README)."""


@dataclass(frozen=True)
class RadarDataset:
    """Radar plots per scan with optional ground truth (states ``[north, v_north, east, v_east]``)."""

    time: Array
    """(K,) POSIX seconds of each scan."""
    plots: list[Array]
    """K arrays (m_k, 2) of world north/east."""
    sensor: Array
    """(K, 4) the radar platform's state (velocity 0 for a shore radar)."""
    targets: dict[str, Array]
    """Ground truth per target: (K, 4)."""
    source: str = ""


JOYRIDE_VARIABLES = ("time", "measurements", "target", "telemetron")
MAT_MAX_VARIABLE_BYTES = 256 * 2**20
"""Largest decompressed variable :func:`check_mat5` accepts (joyride's largest is 7 kB)."""
_MI_SIZES = {1: 1, 2: 1, 3: 2, 4: 2, 5: 4, 6: 4, 7: 4, 9: 8, 12: 8, 13: 8, 16: 1, 17: 2, 18: 4}
"""MAT v5 data types (miINT8 … miUTF32) → item size [B]."""
_NUMERIC_CLASSES = {4, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}
"""mxCHAR and the numeric array classes; 1 is mxCELL."""
_MI_MATRIX, _MI_COMPRESSED = 14, 15


def _mat_elements(buf: bytes, order: str, where: str, p: Path) -> Iterator[tuple[int, bytes]]:
    """(data type, data) of the tagged elements filling ``buf``; every size is checked against ``buf``."""
    i = 0
    while i < len(buf):
        if i + 8 > len(buf):
            raise InputError(p, f"truncated element tag at byte {i}", where=where)
        (tag,) = struct.unpack_from(order + "I", buf, i)
        if tag >> 16:  # small data element: the size in the upper half, the data in the next 4 bytes
            kind, n = tag & 0xFFFF, tag >> 16
            if n > 4:
                raise InputError(p, f"small data element of {n} bytes (at most 4)", where=where)
            yield kind, buf[i + 4 : i + 4 + n]
            i += 8
            continue
        kind, n = struct.unpack_from(order + "II", buf, i)
        if n > len(buf) - i - 8:
            raise InputError(p, f"element of {n} bytes at byte {i} exceeds its {len(buf) - i - 8} remaining bytes", where=where)
        yield kind, buf[i + 8 : i + 8 + n]
        i += 8 + n + (0 if kind == _MI_COMPRESSED else -n % 8)


def _check_matrix(body: bytes, order: str, where: str, p: Path, full: bool, depth: int = 0) -> str:
    """Check one miMATRIX element (its name returned); ``full``: its data as well, not only its header."""
    if depth > 8:
        raise InputError(p, "cell arrays nested deeper than 8", where=where)
    parts = _mat_elements(body, order, where, p)
    head = [next(parts, None) for _ in range(3)]
    if None in head or [h[0] for h in head] != [6, 5, 1] or len(head[0][1]) != 8:  # type: ignore[index]
        raise InputError(p, "array without array flags, dimensions and name", where=where)
    flags = struct.unpack_from(order + "I", head[0][1])[0]  # type: ignore[index]
    dims_raw = head[1][1]  # type: ignore[index]
    if len(dims_raw) % 4 or len(dims_raw) < 8:
        raise InputError(p, f"dimensions of {len(dims_raw)} bytes", where=where)
    dims = struct.unpack(order + f"{len(dims_raw) // 4}i", dims_raw)
    if min(dims) < 0 or math.prod(dims) > MAT_MAX_VARIABLE_BYTES:
        raise InputError(p, f"impossible dimensions {dims}", where=where)
    name = head[2][1].decode("ascii", errors="replace")  # type: ignore[index]
    if not full:
        return name
    cls, count = flags & 0xFF, math.prod(dims)
    rest = list(parts)
    if cls == 1:  # cell: one array per element
        if len(rest) != count or any(k != _MI_MATRIX for k, _ in rest):
            raise InputError(p, f"cell array {dims} does not hold {count} arrays", where=where)
        for j, (_, sub) in enumerate(rest):
            _check_matrix(sub, order, f"{where}{{{j + 1}}}", p, True, depth + 1)
    elif cls in _NUMERIC_CLASSES:
        want = 2 if flags & 0x800 else 1
        if len(rest) != want:
            raise InputError(p, f"numeric array with {len(rest)} data parts, expected {want}", where=where)
        for kind, data in rest:
            size = _MI_SIZES.get(kind)
            if size is None or len(data) != count * size:
                raise InputError(p, f"array {dims} with {len(data)} bytes of data type {kind}", where=where)
    else:
        raise InputError(p, f"unsupported MATLAB array class {cls} (expected numeric or cell arrays)", where=where)
    return name


def check_mat5(p: Path, needed: tuple[str, ...]) -> None:
    """Validate the structure of a MATLAB v5 file before scipy reads it: every element size fits its
    parent, compressed variables inflate to at most :data:`MAT_MAX_VARIABLE_BYTES`, and the ``needed``
    variables are numeric or cell arrays whose data match their dimensions. (scipy's reader trusts the
    file's sizes and types; some corrupt files crash the interpreter.)"""
    data = p.read_bytes()
    if len(data) < 128 or data[126:128] not in (b"IM", b"MI"):
        raise InputError(p, "not a MATLAB v5 .mat file (no v5 header)")
    order = "<" if data[126:128] == b"IM" else ">"
    body = data[128:]
    for index, (kind, elem) in enumerate(_mat_elements(body, order, "header", p)):
        where = f"variable {index + 1}"
        if kind == _MI_COMPRESSED:
            inflate = zlib.decompressobj()
            try:
                raw = inflate.decompress(elem, MAT_MAX_VARIABLE_BYTES + 1)
            except zlib.error as exc:
                raise InputError(p, f"corrupt compressed variable: {exc}", where=where) from None
            if len(raw) > MAT_MAX_VARIABLE_BYTES or inflate.unconsumed_tail:
                raise InputError(p, f"compressed variable inflates beyond {MAT_MAX_VARIABLE_BYTES} bytes", where=where)
            inner = list(_mat_elements(raw, order, where, p))
            if len(inner) != 1:
                raise InputError(p, "compressed element does not hold one variable", where=where)
            kind, elem = inner[0]
        if kind != _MI_MATRIX:
            raise InputError(p, f"top-level element of data type {kind}, expected an array", where=where)
        name = _check_matrix(elem, order, where, p, full=False)
        if name in needed:
            _check_matrix(elem, order, f"variable {name!r}", p, full=True)


def read_joyride(path: str | os.PathLike[str]) -> RadarDataset:
    """Read ``joyride.mat`` (see the module docstring); inf rows of a scan are dropped."""
    from scipy.io import loadmat

    p = Path(path)
    if not p.is_file():
        raise InputError(p, "no such file")
    check_mat5(p, JOYRIDE_VARIABLES)
    try:
        d = loadmat(p, variable_names=list(JOYRIDE_VARIABLES))
    except Exception as exc:  # noqa: BLE001 - any parser failure becomes one line
        text = " ".join(str(exc).split())[:300]
        raise InputError(p, f"not a MATLAB v5 file scipy can read: {type(exc).__name__}: {text}") from None
    for key in ("time", "measurements", "target", "telemetron"):
        if key not in d:
            raise InputError(p, f"missing variable {key!r}; expected time, measurements, target, telemetron")
    time = np.asarray(d["time"], float).reshape(-1)
    k = time.size
    meas = np.asarray(d["measurements"], dtype=object).reshape(-1)
    target = np.asarray(d["target"], float)
    tel = np.asarray(d["telemetron"], float)
    if meas.size != k or target.shape != (k, 4) or tel.shape != (k, 4):
        raise InputError(
            p,
            f"expected {k} scans: measurements {k}×1, target and telemetron {k}×4; got {meas.shape}, {target.shape}, {tel.shape}",
        )
    if not np.all(np.diff(time) > 0):
        raise InputError(p, "scan times must increase", where="time")
    plots = []
    for i, m in enumerate(meas):
        a = np.asarray(m, float)
        if a.size == 0:
            plots.append(np.zeros((0, 2)))
            continue
        if a.ndim != 2 or a.shape[1] != 2:
            raise InputError(p, f"expected an m×2 array [north, east], got shape {a.shape}", where=f"measurements[{i}]")
        plots.append(a[np.isfinite(a).all(axis=1)])
    return RadarDataset(time, plots, tel, {"target": target}, str(p))


def read_ravnkloa_radar(path: str | os.PathLike[str]) -> RadarDataset:
    """Read one Ravnkloa radar-2023 CSV; times = file-name date-time (read as UTC) + ``scan_time_s``."""
    p = Path(path)
    if not p.is_file():
        raise InputError(p, "no such file")
    try:
        start = dt.datetime.strptime(p.stem, "%Y-%m-%d-%H-%M-%S").replace(tzinfo=dt.UTC).timestamp()
    except ValueError:
        raise InputError(p, "expected a file name YYYY-MM-DD-HH-MM-SS.csv (the recording start)") from None
    text = read_text(p, "a radar CSV", encoding="utf-8-sig")
    rows = parse_csv(p, text, lambda reader: _radar_rows(p, reader))
    if not rows:
        raise InputError(p, "no radar detections in the file")
    a = np.array(rows)
    if np.any(np.diff(a[:, 0]) < 0):
        raise InputError(p, "scan_time_s must not decrease", where="scan_time_s")
    times, idx = np.unique(a[:, 0], return_index=True)
    plots = np.split(a[:, 1:], idx[1:])
    k = times.size
    sensor = np.tile([RAVNKLOA_RADAR_POSITION[0], 0.0, RAVNKLOA_RADAR_POSITION[1], 0.0], (k, 1))
    return RadarDataset(start + times, plots, sensor, {}, str(p))


def _radar_rows(p: Path, reader: Iterator[list[str]]) -> list[tuple[float, float, float]]:
    rows: list[tuple[float, float, float]] = []
    header = next(reader, None)
    if header is None or [h.strip() for h in header[:3]] != ["scan_time_s", "north_m", "east_m"]:
        raise InputError(p, f"expected the header scan_time_s,north_m,east_m, got {header}", where="line 1")
    for line_no, row in enumerate(reader, start=2):
        if not row:
            continue
        try:
            t, n, e = (float(v) for v in row[:3])
        except ValueError:
            raise InputError(p, f"expected three numbers, got {row}", where=f"line {line_no}") from None
        if not all(math.isfinite(v) for v in (t, n, e)):
            raise InputError(p, f"non-finite value in {row}", where=f"line {line_no}")
        rows.append((t, n, e))
    return rows


def _write(ds: RadarDataset, out: str | os.PathLike[str], fmt: str, *, platform: str, metadata: dict) -> str:
    from seatwin.recording import VesselPose, open_recording

    with open_recording(out, fmt, metadata=metadata, sensors={"radar": {"kind": "radar plots", "frame": "world"}}) as w:
        topic = w.topics.topic("radar", sensor="radar")
        frame = w.topics.world_frame
        n_plots = 0
        for k, t in enumerate(ds.time.tolist()):
            s = ds.sensor[k]
            vessels = [VesselPose(platform, s[0], s[2], _course(s), v_north=s[1], v_east=s[3], ownship=True)]
            for name, x in ds.targets.items():
                vessels.append(VesselPose(name, x[k, 0], x[k, 2], _course(x[k]), v_north=x[k, 1], v_east=x[k, 3]))
            w.write_ground_truth(t, vessels)
            pl = ds.plots[k]
            w.write_radar(topic, frame, t, pl[:, 0], pl[:, 1], origin=(float(s[0]), float(s[2])))
            n_plots += pl.shape[0]
    return f"{ds.time.size} radar scans, {n_plots} plots, {len(ds.targets)} target(s) with ground truth"


def _course(x: Array) -> float:
    """Heading taken as the course over ground (the datasets give no heading); 0 when at rest."""
    return float(math.atan2(x[3], x[1])) if math.hypot(x[1], x[3]) > 0.1 else 0.0


def import_joyride(
    mat: str | os.PathLike[str], out: str | os.PathLike[str], fmt: str = "mcap", *, overwrite: bool = False
) -> str:
    """Write the joyride dataset as a recording in ``out`` (new or empty; ``overwrite`` replaces an earlier run
    there, :func:`~seatwin.recording.manifest.check_new_run`); returns a one-line summary."""
    from seatwin.outputs import remove_outputs
    from seatwin.recording.manifest import check_new_run

    stale = check_new_run(out, "out", inputs=[mat], overwrite=overwrite)
    ds = read_joyride(mat)
    remove_outputs(stale)
    meta = {
        "dataset": "joyride",
        "source": str(mat),
        "licence": "CC0",
        "note": "radar plots in the world NED frame of the dataset; headings are courses over ground",
        "tracking": {"tuning": "joyride", "map": "none", "radar_merge": 0.0},
    }
    return _write(ds, out, fmt, platform="telemetron", metadata=meta)


def import_ravnkloa_radar(
    csv_path: str | os.PathLike[str],
    out: str | os.PathLike[str],
    fmt: str = "mcap",
    map_path: str | os.PathLike[str] | None = None,
    *,
    overwrite: bool = False,
) -> str:
    """Write one Ravnkloa shore-radar CSV as a recording in ``out`` (new or empty; ``overwrite`` replaces an
    earlier run there); returns a one-line summary."""
    from seatwin.outputs import remove_outputs
    from seatwin.recording.manifest import check_new_run

    stale = check_new_run(out, "out", inputs=[csv_path, map_path], overwrite=overwrite)
    ds = read_ravnkloa_radar(csv_path)
    hints: dict = {"tuning": "ravnkloa", "radar_merge": 3.0}
    if map_path is not None:
        mp = Path(map_path)
        if not mp.with_suffix(".yaml").is_file():
            raise InputError(mp, "map raster not found (expected NAME.yaml beside NAME.bin)")
        hints["map"] = str(mp.resolve())
    meta = {
        "dataset": "ravnkloa-radar-2023",
        "source": str(csv_path),
        "licence": "CC0",
        "note": "shore radar recorded as a stationary ownship; times = file name (UTC) + scan_time_s",
        "tracking": hints,
    }
    remove_outputs(stale)
    return _write(ds, out, fmt, platform="ravnkloa_radar", metadata=meta)
