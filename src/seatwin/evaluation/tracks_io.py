"""The track file (``TRACKS.csv``): a tracker's output, one row per (time, track).

Columns: ``time,track_id,existence,north,v_north,east,v_east``, the 16 covariance entries
``P00 … P33`` row-major in the state order ``[north, v_north, east, v_east]`` (thesis (5.32)),
then ``confirmed`` (0/1). Times are POSIX seconds, positions metres (local NED), velocities m/s.

A *scan marker* row — ``track_id`` −1 and every other field but ``time`` empty — records a
tracker instant at which no track existed. Evaluation needs these: an instant with no track is a
track loss (thesis 5.1.4), and a comparison can only count instants where both datasets had no
track (thesis scenario 7) if it knows the instants. :func:`write_tracks` writes them for every
scan time without a track row.
"""

from __future__ import annotations

import csv
import os
import warnings
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError, parse_csv, parse_finite, read_text

STATE_NAMES: tuple[str, ...] = ("north", "v_north", "east", "v_east")
"""State order of (5.32): the thesis's ``[Pos_x, Vel_x, Pos_y, Vel_y]`` with x north, y east."""
COV_COLUMNS: tuple[str, ...] = tuple(f"P{i}{j}" for i in range(4) for j in range(4))
COLUMNS: tuple[str, ...] = ("time", "track_id", "existence", *STATE_NAMES, *COV_COLUMNS, "confirmed")
NO_TRACK = -1
"""``track_id`` of a scan marker row."""
SYMMETRY_RTOL = 1e-6
PSD_RTOL = 1e-9
"""A covariance whose smallest eigenvalue is below −PSD_RTOL × its largest is rejected."""


@dataclass(frozen=True)
class PlotLog:
    """The positional measurements (plots, cluster centroids) the tracker was given: per scan, its time and
    (M, 2) north/east. Kept in memory beside the tracks for plot-level statistics (clutter); a track file
    does not store it."""

    times: NDArray[np.float64]
    positions: tuple[NDArray[np.float64], ...]
    shapes: tuple[NDArray[np.float64], ...] | None = None
    """Per scan, (M, 2) shape features of lidar clusters: log point count, log(thickness + 1 cm)
    (:func:`seatwin.perception.cluster.minor_spread`); None for sensors without cluster shapes."""
    sensor: NDArray[np.float64] | None = None
    """(n, 2) north/east of the sensor at each scan; None when not kept."""
    clusters: tuple[NDArray[np.float64] | None, ...] | None = None
    """Per scan, (M, 4) per lidar cluster: point count and horizontal covariance ``nn, ne, ee`` [m²]
    (:func:`seatwin.perception.lidar.cluster_moment_rows`), None for a scan that is no lidar sweep; None when
    not kept."""


@dataclass
class Tracks:
    """A tracker's output: ``n`` rows sorted by (time, track_id) and the tracker's scan times.

    ``state`` is (n, 4) in :data:`STATE_NAMES` order, ``covariance`` (n, 4, 4).
    ``scan_times`` holds every instant the tracker produced output, with or without tracks
    (sorted, unique); it always contains ``time``.
    """

    time: NDArray[np.float64]
    track_id: NDArray[np.int64]
    existence: NDArray[np.float64]
    state: NDArray[np.float64]
    covariance: NDArray[np.float64]
    confirmed: NDArray[np.bool_]
    scan_times: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    source: str = "<memory>"
    plots: PlotLog | None = None
    """The plots behind the tracks, when they were tracked in this process (never read from a track file)."""

    def __post_init__(self) -> None:
        self.time = np.asarray(self.time, dtype=float).reshape(-1)
        n = len(self.time)
        self.track_id = np.asarray(self.track_id, dtype=np.int64).reshape(n)
        self.existence = np.asarray(self.existence, dtype=float).reshape(n)
        self.state = np.asarray(self.state, dtype=float).reshape(n, 4)
        self.covariance = np.asarray(self.covariance, dtype=float).reshape(n, 4, 4)
        self.confirmed = np.asarray(self.confirmed, dtype=bool).reshape(n)
        _validate(self)
        order = np.lexsort((self.track_id, self.time))
        for name in ("time", "track_id", "existence", "state", "covariance", "confirmed"):
            setattr(self, name, getattr(self, name)[order])
        self.scan_times = np.unique(np.concatenate([np.asarray(self.scan_times, dtype=float).reshape(-1), self.time]))
        if not np.isfinite(self.scan_times).all():
            raise InputError(self.source, "scan times must be finite", where="time")

    def __len__(self) -> int:
        return len(self.time)

    def select(self, mask: ArrayLike) -> Tracks:
        """The rows where ``mask`` holds; the scan times are kept."""
        m = np.asarray(mask, dtype=bool)
        return Tracks(
            self.time[m],
            self.track_id[m],
            self.existence[m],
            self.state[m],
            self.covariance[m],
            self.confirmed[m],
            self.scan_times,
            self.source,
            self.plots,
        )

    def confirmed_only(self) -> Tracks:
        return self.select(self.confirmed)


def _validate(tracks: Tracks) -> None:
    src = tracks.source
    for name, values in (
        ("time", tracks.time),
        ("existence", tracks.existence),
        ("state", tracks.state),
        ("covariance", tracks.covariance),
    ):
        bad = ~np.isfinite(values).reshape(len(tracks.time), -1).all(axis=1) if len(tracks.time) else np.zeros(0, bool)
        if bad.any():
            raise InputError(src, f"{name} is not finite in row {int(np.flatnonzero(bad)[0])}", where=name)
    if len(tracks.time) == 0:
        return
    if (tracks.track_id < 0).any():
        raise InputError(src, f"track_id must be >= 0 in a track row, got {int(tracks.track_id.min())}", where="track_id")
    out = (tracks.existence < 0) | (tracks.existence > 1)
    if out.any():
        i = int(np.flatnonzero(out)[0])
        raise InputError(src, f"existence must lie in [0, 1], got {tracks.existence[i]!r} in row {i}", where="existence")
    p = tracks.covariance
    scale = np.maximum(np.abs(p).max(axis=(1, 2)), np.finfo(float).tiny)
    asym = np.abs(p - p.transpose(0, 2, 1)).max(axis=(1, 2)) > SYMMETRY_RTOL * scale
    if asym.any():
        raise InputError(src, f"covariance is not symmetric in row {int(np.flatnonzero(asym)[0])}", where="P")
    diag = np.einsum("nii->ni", p)
    if (diag <= 0).any():
        i = int(np.flatnonzero((diag <= 0).any(axis=1))[0])
        raise InputError(src, f"covariance diagonal must be positive, got {diag[i].tolist()} in row {i}", where="P")
    eig = np.linalg.eigvalsh(0.5 * (p + p.transpose(0, 2, 1)))
    neg = eig[:, 0] < -PSD_RTOL * eig[:, -1]
    if neg.any():
        i = int(np.flatnonzero(neg)[0])
        raise InputError(src, f"covariance is not positive semi-definite in row {i} (eigenvalues {eig[i].tolist()})", where="P")
    pairs = np.stack([tracks.time, tracks.track_id.astype(float)], axis=1)
    uniq = np.unique(pairs, axis=0)
    if len(uniq) != len(pairs):
        seen: set[tuple[float, int]] = set()
        for t, k in zip(tracks.time.tolist(), tracks.track_id.tolist()):
            if (t, k) in seen:
                raise InputError(src, f"track {k} appears twice at time {t!r}", where="track_id")
            seen.add((t, k))


def _fmt(x: float) -> str:
    return repr(float(x))


def write_tracks(path: str | os.PathLike[str], tracks: Tracks) -> None:
    """Write ``tracks`` as a track file, with a scan marker row for every scan time without a track."""
    from seatwin.outputs import atomic_output

    path = Path(path)
    rows: list[tuple[float, int, list[str]]] = []
    for i in range(len(tracks)):
        cells = [_fmt(tracks.time[i]), str(int(tracks.track_id[i])), _fmt(tracks.existence[i])]
        cells += [_fmt(v) for v in tracks.state[i]] + [_fmt(v) for v in tracks.covariance[i].reshape(-1)]
        cells.append("1" if tracks.confirmed[i] else "0")
        rows.append((float(tracks.time[i]), int(tracks.track_id[i]), cells))
    with_rows = set(tracks.time.tolist())
    for t in tracks.scan_times.tolist():
        if t not in with_rows:
            rows.append((t, NO_TRACK, [_fmt(t), str(NO_TRACK)] + [""] * (len(COLUMNS) - 2)))
    rows.sort(key=lambda r: (r[0], r[1]))
    with atomic_output(path) as tmp, tmp.open("w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(COLUMNS)
        writer.writerows(r[2] for r in rows)


def read_tracks(path: str | os.PathLike[str]) -> Tracks:
    """Read a track file; an :class:`InputError` names the file, line and column of any bad value."""
    path = Path(path)
    text = read_text(path, "a track file", encoding="utf-8-sig")
    return parse_csv(path, text, lambda reader: _read_rows(path, reader))


def _read_rows(path: Path, reader: Iterator[list[str]]) -> Tracks:
    numeric: list[list[float]] = []
    lines: list[int] = []
    ids: list[int] = []
    confirmed: list[bool] = []
    scans: list[float] = []
    header = next(reader, None)
    if header is None:
        raise InputError(path, f"empty file, expected the header {','.join(COLUMNS)}")
    header = [h.strip() for h in header]
    missing = [c for c in COLUMNS if c not in header]
    if missing:
        raise InputError(path, f"missing column(s) {missing}; expected {','.join(COLUMNS)}", where="line 1")
    col = {c: header.index(c) for c in COLUMNS}
    value_cols = ["existence", *STATE_NAMES, *COV_COLUMNS]
    for line, row in enumerate(reader, start=2):
        if not row or all(not c.strip() for c in row):
            continue
        if len(row) < len(header):
            raise InputError(path, f"expected {len(header)} fields, got {len(row)}", where=f"line {line}")

        def number(name: str, row: list[str] = row, line: int = line) -> float:
            return parse_finite(row[col[name]].strip(), path, name, line)

        t = number("time")
        tid_text = row[col["track_id"]].strip()
        try:
            tid = int(tid_text)
        except ValueError:
            raise InputError(path, f"expected an integer track_id, got {tid_text!r}", where=f"line {line}") from None
        if tid == NO_TRACK:
            filled = [c for c in value_cols + ["confirmed"] if row[col[c]].strip()]
            if filled:
                raise InputError(
                    path, f"a scan marker row (track_id {NO_TRACK}) must leave {filled[0]} empty", where=f"line {line}"
                )
            scans.append(t)
            continue
        if tid < 0:
            raise InputError(path, f"track_id must be >= 0 (or {NO_TRACK} for a scan marker), got {tid}", where=f"line {line}")
        values = [t] + [number(c) for c in value_cols]
        flag = row[col["confirmed"]].strip()
        if flag not in ("0", "1"):
            raise InputError(path, f"confirmed must be 0 or 1, got {flag!r}", where=f"line {line}")
        numeric.append(values)
        lines.append(line)
        ids.append(tid)
        confirmed.append(flag == "1")
    arr = np.asarray(numeric, dtype=float).reshape(-1, 2 + 4 + 16)
    back = np.flatnonzero(np.diff(arr[:, 0]) < 0)
    if back.size:  # kept, sorted by (time, track_id); a repeated (time, track_id) stays an error
        warnings.warn(
            f"{path}: track rows are not in time order (time {arr[back[0] + 1, 0]!r} after {arr[back[0], 0]!r}, "
            f"line {lines[back[0] + 1]}); they are sorted by time",
            stacklevel=3,
        )
    return Tracks(
        time=arr[:, 0],
        track_id=np.asarray(ids, dtype=np.int64),
        existence=arr[:, 1],
        state=arr[:, 2:6],
        covariance=arr[:, 6:22].reshape(-1, 4, 4),
        confirmed=np.asarray(confirmed, dtype=bool),
        scan_times=np.asarray(scans, dtype=float),
        source=str(path),
    )
