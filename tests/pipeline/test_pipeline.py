"""The pipeline layer: each use-case as one library call, the same results the CLI prints and writes."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.errors import InputError, ParameterError
from seatwin.evaluation import read_tracks
from seatwin.perception.measurements import MeasurementKind, Scan
from seatwin.pipeline import compare_runs, evaluate_run, simulate_run, track_recording, track_scans


@pytest.fixture(scope="module")
def recording(tmp_path_factory) -> Path:
    from seatwin.scenario.builtin import builtin_scenario

    out = tmp_path_factory.mktemp("pipe") / "run"
    sc = builtin_scenario("ferry_crossing")  # 35 s in: both targets within lidar range
    simulate_run(sc, out, start=sc.start + 35.0, duration=8.0, seed=2, progress=False, sensors=("lidar", "radar"))
    return out


def _scan(t: float, sensor: str, north: float, east: float) -> Scan:
    return Scan(t, sensor, MeasurementKind.CARTESIAN, [[north, east]])


def test_same_instant_scans_give_one_row_per_track_and_instant():
    """Two sensors at one instant: both are processed, the tracks are written once, after the last."""
    scans = []
    for k in range(8):
        t = float(k)
        scans += [_scan(t, "radar", 10.0 + k, 5.0), _scan(t, "radar", 10.2 + k, 5.1)]
    tracks = track_scans(scans, "joyride")
    assert tracks.confirmed.any()
    assert list(tracks.scan_times) == [float(k) for k in range(8)]
    for t in tracks.scan_times:
        ids = tracks.track_id[tracks.time == t]
        assert len(ids) == len(np.unique(ids))


def test_out_of_order_scans_are_refused():
    with pytest.raises(InputError, match="out of time order"):
        track_scans([_scan(2.0, "radar", 0, 0), _scan(1.0, "radar", 0, 0)], "joyride", source="x")


def test_track_recording_equals_the_cli_track_file(recording: Path, tmp_path: Path):
    res = track_recording(recording, tuning="synthetic")
    assert res.sensors == ("radar", "lidar") and res.n_scans > 10
    out = tmp_path / "t.csv"
    assert run(["track", str(recording), "--out", str(out), "--tuning", "synthetic", "--no-progress"]) == 0
    written = read_tracks(out)
    np.testing.assert_array_equal(written.time, res.tracks.time)
    np.testing.assert_array_equal(written.track_id, res.tracks.track_id)
    np.testing.assert_allclose(written.state, res.tracks.state, rtol=1e-12)


def test_track_recording_bad_input_names_the_parameter(tmp_path: Path, recording: Path):
    with pytest.raises(InputError, match="no such recording"):
        track_recording(tmp_path / "missing.mcap")
    with pytest.raises(ParameterError) as err:
        track_recording(recording, eps=-1.0)
    assert err.value.param == "eps"


def test_compare_runs_and_evaluate_run(recording: Path, tmp_path: Path):
    res = compare_runs([recording], [recording], recording, tunings=("synthetic",), keep_tracks=tmp_path / "tracks")
    assert [c.tuning for c in res.comparisons] == ["synthetic"]
    assert len(res.track_files) == 1 and res.track_files[0].exists()  # one recording, tracked once per tuning
    lines = res.table["targets"]
    common = [ln for ln in lines if ln["n_common"] > 0]
    assert common and all(ln["ahed"] == pytest.approx(0.0, abs=1e-9) for ln in common)  # a run against itself
    ev = evaluate_run(res.track_files[0], recording)
    assert {s.target for s in ev.summaries} == {"Havfruen", "Finn"}


def test_radar_frames_equal_recorded_or_not(recording: Path, tmp_path: Path):
    """One loop: the radar's plots are the same whether the loop records them or only exports them."""
    from seatwin.pipeline.radar import simulate_radar
    from seatwin.recording import open_bag

    plots = tmp_path / "plots.csv"
    simulate_radar("ferry_crossing", plots_csv=plots, seed=2, start_offset=35.0, duration=8.0)
    rows = list(csv.DictReader(plots.open()))
    with open_bag(recording) as rec:
        scans = list(rec.radar_scans())
    assert len(scans) == len({r["time"] for r in rows}) == 4
    assert sum(len(s.points) for s in scans) == len(rows)
    first = sorted(float(r["range_m"]) for r in rows if float(r["time"]) == float(rows[0]["time"]))
    np.testing.assert_allclose(sorted(scans[0].points["range"]), first, atol=1e-3)


def test_start_offset_is_the_start_relative_to_the_scenario(tmp_path: Path):
    from seatwin.recording import open_bag
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario("ferry_crossing")
    a = simulate_run(sc, tmp_path / "a", start_offset=30.0, duration=0.5, progress=False, sensors=("lidar",))
    b = simulate_run(sc, tmp_path / "b", start=sc.start + 30.0, duration=0.5, progress=False, sensors=("lidar",))
    assert a.frames == b.frames
    with open_bag(tmp_path / "a") as ra, open_bag(tmp_path / "b") as rb:
        assert [bytes(m[3]) for m in ra.raw_messages()] == [bytes(m[3]) for m in rb.raw_messages()]
    with pytest.raises(ParameterError) as err:
        simulate_run(sc, tmp_path / "c", start=sc.start, start_offset=1.0, progress=False)
    assert err.value.param == "start_offset"


def test_lidar_snapshot_speaks_the_shared_vocabulary(tmp_path: Path, capsys):
    """--offset/--out/--lidar-mode/--ray-drop as everywhere else; the old spellings still work."""
    new = ["--offset", "20", "--out", str(tmp_path / "a.png"), "--lidar-mode", "raycast", "--ray-drop", "0.5"]
    old = ["--time", "20", "--output", str(tmp_path / "b.png"), "--range-model", "raycast", "--drop", "0.5"]
    assert run(["lidar", "snapshot", "ferry_crossing", *new]) == 0
    assert run(["lidar", "snapshot", "ferry_crossing", *old]) == 0
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()
    assert run(["lidar", "snapshot", "ferry_crossing", "--out", str(tmp_path / "c.png"), "--ray-drop", "2"]) == 2
    assert "--ray-drop" in capsys.readouterr().err


def test_simulated_runs_name_their_harbour_and_false_tracks_are_counted(recording: Path):
    from seatwin.recording.manifest import read_manifest

    assert read_manifest(recording)["metadata"]["tracking"]["map"] == "harbour"
    res = compare_runs([recording], [recording], recording, tunings=("synthetic",))
    ft = res.table["false_tracks"][0]
    assert ft["real"] == ft["synthetic"] and ft["real"]["n_on_land"] is not None
    ev = evaluate_run(track_recording(recording, tuning="synthetic").tracks, recording, map_spec="none")
    assert ev.false_tracks is not None and ev.false_tracks.n_on_land == 0  # no mask: nothing is land
    ev_all = evaluate_run(track_recording(recording, tuning="synthetic", map_spec="none").tracks, recording)
    assert ev_all.false_tracks.n_tracks > 0 and ev_all.false_tracks.n_on_land is not None  # judged by the run's own mask
    # confirmed tracks stay consistent with the tuning's v_max (10 m/s): the speed gate deletes faster ones
    # (compare's false tracks may be none: tracks of the harbour's moored boats are don't-care there)
    speeds = [v for v in (ev_all.false_tracks.max_speed_mps, ft["real"]["max_speed_mps"]) if v is not None]
    assert speeds and max(speeds) <= 2 * 10.0
