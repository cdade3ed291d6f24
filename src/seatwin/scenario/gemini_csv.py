"""The Gemini scenario CSV: ``TimeInSecondsPosix`` (or ``TimeOfDay`` + a date), then
``V{n}x`` (north, m), ``V{n}y`` (east, m), ``V{n}Heading`` (degrees clockwise from north) for
vessels n = 1, 2, … (see ``shared/data/README.md``).
"""

from __future__ import annotations

import csv
import datetime as dt
import os
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError, parse_csv, parse_finite, read_text
from seatwin.geo import deg_to_rad_heading, rad_to_deg_heading
from seatwin.scenario.model import Trajectory
from seatwin.scenario.plausibility import MAX_SPEED, MAX_TURN_RATE, first_heading_spike, first_teleport

TIME_POSIX = "TimeInSecondsPosix"
TIME_OF_DAY = "TimeOfDay"
_VESSEL_COLUMN = re.compile(r"^V([0-9]+)(x|y|Heading)$")


def _parse_time_of_day(text: str, date: dt.date, path: Path, line: int) -> float:
    try:
        t = dt.time.fromisoformat(text.strip(" \t"))
    except ValueError:
        raise InputError(path, f"expected HH:MM:SS[.fff] in {TIME_OF_DAY}, got {text!r}", where=f"line {line}") from None
    return dt.datetime.combine(date, t, tzinfo=dt.UTC).timestamp()


def read_gemini_csv(
    path: str | os.PathLike[str], date: dt.date | None = None, max_speed: float = MAX_SPEED, max_turn_rate: float = MAX_TURN_RATE
) -> dict[int, Trajectory]:
    """Read a Gemini scenario CSV into one trajectory per vessel number.

    ``date`` (UTC) is required when the file has ``TimeOfDay`` instead of POSIX seconds.
    Raises :class:`InputError` naming the file, line and column for any malformed value (numbers
    in ASCII only: :func:`~seatwin.errors.parse_finite`), for times that do not strictly increase
    (duplicates and unsorted rows are errors: a scenario is written by a program, and a repeated or
    misplaced row means a broken export), for a vessel that moves faster than ``max_speed`` [m/s]
    between two rows (a teleport) and for a one-row heading spike turning faster than
    ``max_turn_rate`` [°/s] (:mod:`seatwin.scenario.plausibility`; ``inf`` turns either check off).
    """
    check_max_speed(max_speed)
    check_max_turn_rate(max_turn_rate)
    path = Path(path)
    text = read_text(path, "a Gemini CSV", encoding="utf-8-sig")
    return parse_csv(path, text, lambda reader: _read_rows(path, reader, date, max_speed, max_turn_rate))


def check_max_speed(max_speed: float) -> None:
    """A :class:`ParameterError` unless ``max_speed`` is a positive number (``inf`` turns the check off)."""
    if not isinstance(max_speed, int | float) or not max_speed > 0:
        raise ParameterError("max_speed", f"expected a speed > 0 m/s (inf: no check), got {max_speed!r}")


def check_max_turn_rate(max_turn_rate: float) -> None:
    """A :class:`ParameterError` unless ``max_turn_rate`` is a positive number of °/s (``inf`` turns the check off)."""
    if not isinstance(max_turn_rate, int | float) or not max_turn_rate > 0:
        raise ParameterError("max_turn_rate", f"expected a turn rate > 0 °/s (inf: no check), got {max_turn_rate!r}")


def _check_motion(
    path: Path,
    time: NDArray[np.float64],
    data: NDArray[np.float64],
    columns: dict[int, dict[str, int]],
    lines: list[int],
    max_speed: float,
    max_turn_rate: float,
) -> None:
    for n, cols in sorted(columns.items()):
        jump = first_teleport(time, data[:, cols["x"]], data[:, cols["y"]], max_speed)
        if jump is not None:
            k = jump.index
            raise InputError(
                path,
                f"vessel {n} moves {jump.step:.4g} m in {jump.dt:.4g} s ({jump.speed:.4g} m/s) after line {lines[k]}, faster "
                f"than max_speed {max_speed:g} m/s: a teleport (a corrupt or mis-scaled row?)",
                where=f"line {lines[k + 1]}, columns V{n}x, V{n}y",
            )
        spike = first_heading_spike(time, data[:, cols["Heading"]], max_turn_rate)
        if spike is not None:
            k = spike.index
            raise InputError(
                path,
                f"vessel {n} heading jumps {spike.jump:.1f}° and back (from {spike.before:g}° after line {lines[k - 1]} to "
                f"{spike.at:g}° to {spike.after:g}° within {spike.span:.3g} s), faster than max_turn_rate "
                f"{max_turn_rate:g} °/s: a heading spike (a corrupt row?)",
                where=f"line {lines[k]}, column V{n}Heading",
            )


def _read_rows(
    path: Path, reader: Iterator[list[str]], date: dt.date | None, max_speed: float, max_turn_rate: float
) -> dict[int, Trajectory]:
    header = next(reader, None)
    if header is None:
        raise InputError(path, "empty file, expected a header line")
    header = [h.strip() for h in header]
    if TIME_POSIX in header:
        time_col, posix = header.index(TIME_POSIX), True
    elif TIME_OF_DAY in header:
        time_col, posix = header.index(TIME_OF_DAY), False
        if date is None:
            raise InputError(path, f"the file has {TIME_OF_DAY}; give the recording date (UTC) to place it in time")
    else:
        raise InputError(path, f"expected a {TIME_POSIX} or {TIME_OF_DAY} column", where="line 1")
    columns: dict[int, dict[str, int]] = {}
    for i, name in enumerate(header):
        m = _VESSEL_COLUMN.match(name)
        if m:
            if len(m.group(1)) > 6:
                raise InputError(path, f"vessel number of {len(m.group(1))} digits in column {name[:20]!r}…", where="line 1")
            columns.setdefault(int(m.group(1)), {})[m.group(2)] = i
    if not columns:
        raise InputError(path, "no vessel columns V{n}x, V{n}y, V{n}Heading", where="line 1")
    for n, cols in sorted(columns.items()):
        missing = [f"V{n}{k}" for k in ("x", "y", "Heading") if k not in cols]
        if missing:
            raise InputError(path, f"missing column(s) {', '.join(missing)}", where="line 1")
    rows: list[list[float]] = []
    row_lines: list[int] = []
    time_text: list[str] = []
    for line_no, row in enumerate(reader, start=2):
        if not row or all(not c.strip() for c in row):
            continue
        if len(row) != len(header):
            raise InputError(path, f"expected {len(header)} fields, got {len(row)}", where=f"line {line_no}")
        values = []
        for i, cell in enumerate(row):
            if i == time_col and not posix:
                values.append(_parse_time_of_day(cell, date, path, line_no))  # type: ignore[arg-type]
                continue
            values.append(parse_finite(cell, path, header[i], line_no))
        rows.append(values)
        row_lines.append(line_no)
        time_text.append(row[time_col].strip())
    if len(rows) < 2:
        raise InputError(path, f"expected at least 2 data lines, got {len(rows)}")
    data = np.asarray(rows, dtype=float)
    time = data[:, time_col]
    steps = np.diff(time)
    if (steps <= 0).any():
        k = int(np.flatnonzero(steps <= 0)[0]) + 1
        kind = "duplicated" if steps[k - 1] == 0 else "decreasing"
        raise InputError(
            path,
            f"{kind} time {time_text[k]} after {time_text[k - 1]} (line {row_lines[k - 1]}); times must increase",
            where=f"line {row_lines[k]}",
        )
    _check_motion(path, time, data, columns, row_lines, max_speed, max_turn_rate)
    return {
        n: Trajectory(
            time=time,
            north=data[:, cols["x"]],
            east=data[:, cols["y"]],
            heading=deg_to_rad_heading(data[:, cols["Heading"]]),
            source=f"{path} (vessel {n})",
        )
        for n, cols in sorted(columns.items())
    }


def _times_of_day(time: NDArray[np.float64], path: Path) -> tuple[list[str], dt.date]:
    """POSIX seconds → ``HH:MM:SS.fff`` (µs when needed) and their UTC date; one day only."""
    stamps = [dt.datetime.fromtimestamp(float(t), tz=dt.UTC) for t in time]
    if stamps[0].date() != stamps[-1].date():
        raise InputError(path, f"{TIME_OF_DAY} cannot span midnight UTC ({stamps[0]} to {stamps[-1]}); write {TIME_POSIX}")
    spec = "milliseconds" if all(s.microsecond % 1000 == 0 for s in stamps) else "microseconds"
    return [s.time().isoformat(timespec=spec) for s in stamps], stamps[0].date()


def write_gemini_csv(
    path: str | os.PathLike[str],
    trajectories: list[Trajectory],
    time: NDArray[np.float64] | None = None,
    time_format: Literal["posix", "time_of_day"] = "posix",
) -> dt.date | None:
    """Write trajectories as a Gemini CSV, vessels numbered 1, 2, … in the order given.

    All trajectories are sampled at ``time`` (default: the first trajectory's samples; every
    trajectory must cover it). ``time_format="time_of_day"`` writes ``TimeOfDay`` and returns
    the UTC date a reader needs (``None`` for POSIX). Written to a temporary file and renamed,
    so a failure leaves no half-written output.
    """
    path = Path(path)
    if not trajectories:
        raise InputError(path, "nothing to write: no trajectories")
    if time_format not in ("posix", "time_of_day"):
        raise InputError(path, f"time_format must be 'posix' or 'time_of_day', got {time_format!r}")
    t = trajectories[0].time if time is None else np.asarray(time, float)
    date = None
    if time_format == "posix":
        time_cells = [repr(float(v)) for v in t]
        header = [TIME_POSIX]
    else:
        time_cells, date = _times_of_day(t, path)
        header = [TIME_OF_DAY]
    columns = []
    for n, traj in enumerate(trajectories, start=1):
        s = traj.state_at(t)
        columns += [s.north, s.east, np.asarray(rad_to_deg_heading(s.heading))]
        header += [f"V{n}x", f"V{n}y", f"V{n}Heading"]
    tmp = path.with_name(path.name + ".part")
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        with tmp.open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            for cell, row in zip(time_cells, zip(*columns)):
                w.writerow([cell] + [repr(float(v)) for v in row])
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return date
