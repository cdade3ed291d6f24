"""The track file: round trip, scan markers, and clear errors for bad input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.evaluation.tracks_io import COLUMNS, read_tracks, write_tracks


def test_round_trip_with_scan_markers(tmp_path: Path, tracks_factory) -> None:
    tr = tracks_factory([(1.0, 3, 1.5, 2.5), (1.0, 1, 0.1, 0.2), (2.0, 1, 0.3, 0.4)], scan_times=[0.0, 1.0, 2.0, 3.0])
    tr.covariance[0, 0, 1] = tr.covariance[0, 1, 0] = 0.1234567890123
    path = tmp_path / "tracks.csv"
    write_tracks(path, tr)
    lines = path.read_text().splitlines()
    assert lines[0] == ",".join(COLUMNS)
    assert lines[1].startswith("0.0,-1,,")  # scan marker
    back = read_tracks(path)
    assert np.array_equal(back.scan_times, [0.0, 1.0, 2.0, 3.0])
    assert back.track_id.tolist() == [1, 3, 1]  # sorted by (time, id)
    assert np.array_equal(back.state, tr.state) and np.array_equal(back.covariance, tr.covariance)  # exact (repr)
    assert back.confirmed.all()


def _write(tmp_path: Path, body: str) -> Path:
    path = tmp_path / "bad.csv"
    path.write_text(",".join(COLUMNS) + "\n" + body + "\n")
    return path


def _row(**over: str) -> str:
    vals = {c: "0" for c in COLUMNS}
    vals.update(
        {"time": "1.0", "track_id": "1", "existence": "0.9", "P00": "1", "P11": "1", "P22": "1", "P33": "1", "confirmed": "1"}
    )
    vals.update(over)
    return ",".join(vals[c] for c in COLUMNS)


@pytest.mark.parametrize(
    ("row", "needle"),
    [
        (_row(north="abc"), "expected a number for north"),
        (_row(P01="0.5"), "not symmetric"),
        (_row(P22="0"), "diagonal must be positive"),
        (_row(P01="2", P10="2"), "not positive semi-definite"),
        (_row(confirmed="2"), "confirmed must be 0 or 1"),
        (_row(existence="1.5"), "existence must lie in [0, 1]"),
        (_row(time="nan"), "expected a finite number for time"),
        (_row(track_id="x"), "integer track_id"),
        (_row(track_id="-5"), "track_id must be >= 0"),
        ("1.0,-1,0.5" + "," * (len(COLUMNS) - 3), "must leave existence empty"),
        (_row() + "\n" + _row(), "appears twice"),
    ],
)
def test_bad_rows_name_file_line_and_field(tmp_path: Path, row: str, needle: str) -> None:
    path = _write(tmp_path, row)
    with pytest.raises(InputError) as err:
        read_tracks(path)
    assert needle in str(err.value) and "bad.csv" in str(err.value)


def test_missing_column_and_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "t.csv"
    path.write_text("time,track_id\n1,1\n")
    with pytest.raises(InputError, match="missing column"):
        read_tracks(path)
    with pytest.raises(InputError, match="cannot open"):
        read_tracks(tmp_path / "absent.csv")
    (tmp_path / "empty.csv").write_text("")
    with pytest.raises(InputError, match="empty file"):
        read_tracks(tmp_path / "empty.csv")


def test_short_row_names_line(tmp_path: Path) -> None:
    path = _write(tmp_path, _row() + "\n1.0,2,0.5")
    with pytest.raises(InputError, match="line 3"):
        read_tracks(path)
