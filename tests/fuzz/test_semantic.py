"""Semantic checks of the readers: timestamps, teleports, track covariances, PointCloud2 sizes.

Errors: unsorted or duplicated times in scenario CSVs, GNSS logs, radar datasets; a repeated
(time, track) in a track file; a teleport; non-finite or non-PSD covariances; a PointCloud2 whose
sizes exceed its data. Sorted with a warning: track-file rows out of time order (nothing dropped).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from types import SimpleNamespace as F

import numpy as np
import pytest
from fuzz_helpers import check_shared_joyride

from seatwin.errors import InputError, ParameterError
from seatwin.evaluation.tracks_io import read_tracks
from seatwin.recording import unpack
from seatwin.scenario.gemini_csv import read_gemini_csv
from seatwin.scenario.load import load_scenario

HEADER = "TimeInSecondsPosix,V1x,V1y,V1Heading,V2x,V2y,V2Heading\n"


def _csv(tmp_path: Path, rows: list[str]) -> Path:
    p = tmp_path / "sc.csv"
    p.write_text(HEADER + "".join(r + "\n" for r in rows))
    return p


def test_teleport_is_an_error_naming_line_and_vessel(tmp_path: Path) -> None:
    p = _csv(tmp_path, ["100.0,0,0,0,0,0,0", "101.0,2,0,0,1,0,0", "102.0,4,0,0,60,0,0", "103.0,6,0,0,61,0,0"])
    with pytest.raises(InputError, match=r"line 4, columns V2x, V2y: vessel 2 moves 59 m in 1 s \(59 m/s\)"):
        load_scenario(p)
    assert read_gemini_csv(p, max_speed=60.0)[2].north[2] == 60.0
    assert len(load_scenario(p, max_speed=math.inf).vessels) == 2
    for bad in (0.0, -1.0, math.nan):
        with pytest.raises(ParameterError, match="max_speed"):
            load_scenario(p, max_speed=bad)


def test_scenario_times_duplicated_or_unsorted_are_errors(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="line 3: duplicated time"):
        load_scenario(_csv(tmp_path, ["100.0,0,0,0,0,0,0", "100.0,0,0,0,0,0,0"]))
    with pytest.raises(InputError, match="line 3: decreasing time"):
        load_scenario(_csv(tmp_path, ["100.0,0,0,0,0,0,0", "99.0,0,0,0,0,0,0"]))


def test_gnss_times_duplicated_or_unsorted_are_errors(tmp_path: Path) -> None:
    from seatwin.groundtruth.read_csv import read_csv_log

    p = tmp_path / "g.csv"
    p.write_text("time,lat,lon\n1.0,63.4,10.4\n2.0,63.4,10.4\n2.0,63.4,10.4\n")
    with pytest.raises(InputError, match="line 4: duplicated time"):
        read_csv_log(p)
    p.write_text("time,lat,lon\n1.0,63.4,10.4\n3.0,63.4,10.4\n2.0,63.4,10.4\n")
    with pytest.raises(InputError, match="line 4: decreasing"):
        read_csv_log(p)


def _tracks(tmp_path: Path, rows: list[tuple[float, int, np.ndarray]]) -> Path:
    from seatwin.evaluation.tracks_io import COLUMNS

    p = tmp_path / "TRACKS.csv"
    lines = [",".join(COLUMNS)]
    for t, k, cov in rows:
        lines.append(",".join([repr(t), str(k), "0.9", "1", "0", "2", "0", *(repr(float(v)) for v in cov.reshape(-1)), "1"]))
    p.write_text("\n".join(lines) + "\n")
    return p


def test_track_covariances_must_be_finite_and_psd(tmp_path: Path) -> None:
    good = np.eye(4)
    with pytest.raises(InputError, match="expected a finite number for P11"):
        read_tracks(_tracks(tmp_path, [(1.0, 0, np.diag([1.0, math.inf, 1.0, 1.0]))]))
    not_psd = np.eye(4)
    not_psd[0, 1] = not_psd[1, 0] = 3.0
    with pytest.raises(InputError, match="not positive semi-definite"):
        read_tracks(_tracks(tmp_path, [(1.0, 0, not_psd)]))
    asym = np.eye(4)
    asym[0, 1] = 0.5
    with pytest.raises(InputError, match="not symmetric"):
        read_tracks(_tracks(tmp_path, [(1.0, 0, asym)]))
    with pytest.raises(InputError, match="track 0 appears twice"):
        read_tracks(_tracks(tmp_path, [(1.0, 0, good), (1.0, 0, good)]))


def test_track_rows_out_of_order_are_sorted_with_a_warning(tmp_path: Path) -> None:
    p = _tracks(tmp_path, [(2.0, 0, np.eye(4)), (1.0, 0, np.eye(4)), (1.0, 1, np.eye(4))])
    with pytest.warns(UserWarning, match="line 3\\); they are sorted"):
        tr = read_tracks(p)
    assert tr.time.tolist() == [1.0, 1.0, 2.0] and len(tr) == 3
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_tracks(_tracks(tmp_path, [(1.0, 0, np.eye(4)), (2.0, 0, np.eye(4))]))


def test_pointcloud_sizes_must_fit_the_data() -> None:
    x = [F(name="x", offset=0, datatype=7, count=1)]
    assert unpack(np.zeros(12, np.uint8), x, 4, 3).size == 3
    with pytest.raises(InputError, match=r"data has 8 bytes, expected 12 .*exceeds the data"):
        unpack(np.zeros(8, np.uint8), x, 4, 3)
    with pytest.raises(InputError, match="exceeds the data"):
        unpack(np.zeros(24, np.uint8), x, 4, 3, height=2, row_step=16)
    with pytest.raises(InputError, match="row_step 8 is smaller"):
        unpack(np.zeros(64, np.uint8), x, 4, 3, height=2, row_step=8)
    with pytest.raises(InputError, match="point_step is 0"):
        unpack(np.zeros(64, np.uint8), [], 0, 2**31)
    with pytest.raises(InputError, match="exceeds the data"):
        unpack(np.zeros(64, np.uint8), x, 4, 2**32 - 1, height=2**32 - 1)


def test_real_joyride_passes_the_structure_check(shared_data: Path) -> None:
    check_shared_joyride(shared_data / "joyride" / "joyride.mat")
