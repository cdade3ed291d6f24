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

import csv
import datetime as dt
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError

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


def read_joyride(path: str | os.PathLike[str]) -> RadarDataset:
    """Read ``joyride.mat`` (see the module docstring); inf rows of a scan are dropped."""
    from scipy.io import loadmat

    p = Path(path)
    if not p.is_file():
        raise InputError(p, "no such file")
    try:
        d = loadmat(p)
    except Exception as exc:  # noqa: BLE001 - any parser failure becomes one line
        raise InputError(p, f"not a MATLAB v5 file scipy can read: {type(exc).__name__}: {exc}") from None
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
    rows: list[tuple[float, float, float]] = []
    with p.open(newline="") as fh:
        reader = csv.reader(fh)
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


def import_joyride(mat: str | os.PathLike[str], out: str | os.PathLike[str], fmt: str = "mcap") -> str:
    """Write the joyride dataset as a recording in ``out``; returns a one-line summary."""
    ds = read_joyride(mat)
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
) -> str:
    """Write one Ravnkloa shore-radar CSV as a recording in ``out``; returns a one-line summary."""
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
    return _write(ds, out, fmt, platform="ravnkloa_radar", metadata=meta)
