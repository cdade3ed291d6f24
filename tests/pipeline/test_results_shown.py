"""``simulate`` and ``track`` show what they did, not only write it (issue 25, item 11): a console summary and,
on request, a figure; the numbers are the library's (:func:`tracking_summary`, :func:`vessels_on_water`)."""

from __future__ import annotations

import contextlib
import dataclasses
import io
import re
from pathlib import Path

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.pipeline import evaluate_run, simulated_scenario, track_recording, tracking_summary, vessels_on_water

pytestmark = pytest.mark.xdist_group("results_shown")  # one worker: the module's run is simulated once

PNG = b"\x89PNG\r\n\x1a\n"


@dataclasses.dataclass(frozen=True)
class Simulated:
    folder: Path
    run: Path
    figure: Path
    printed: str


@pytest.fixture(scope="module")
def ferry(tmp_path_factory) -> Simulated:
    """``seatwin simulate`` of 8 s of ferry_crossing's lidar (from 25 s in, both targets 25–70 m away) with a figure,
    once for the module (its printout kept): the simulate test checks it, the track tests track that run, whichever
    worker and order they run in."""
    d = tmp_path_factory.mktemp("shown")
    out, fig = d / "run", d / "run.png"
    argv = ["simulate", "ferry_crossing", "--out", str(out), "--offset", "25", "--duration", "8", "--sensors", "lidar"]
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert run([*argv, "--no-progress", "--figure", str(fig)]) == 0
    return Simulated(d, out, fig, printed.getvalue())


def test_simulate_prints_water_and_draws_the_window(ferry):
    out, fig, text = ferry.run, ferry.figure, ferry.printed
    assert "frames: ground truth 80, lidar 80" in text
    assert "on water: Havfruen 100 %, Finn 100 %, milliAmpere 100 %" in text
    assert f"wrote {fig}" in text and fig.read_bytes().startswith(PNG)
    sc = simulated_scenario(out)  # the recorded window, not the whole scenario
    assert all(v.trajectory.time[-1] - v.trajectory.time[0] == pytest.approx(8.0, abs=0.11) for v in sc.vessels)
    assert vessels_on_water(sc) == {"Havfruen": 1.0, "Finn": 1.0, "milliAmpere": 1.0}


def test_simulate_refuses_a_figure_it_could_not_write_before_any_work(tmp_path, capsys):
    out = tmp_path / "run"
    argv = ["simulate", "ferry_crossing", "--out", str(out), "--duration", "1", "--sensors", "lidar", "--no-progress"]
    assert run([*argv, "--figure", str(out / "inside.png")]) == 2
    assert "--figure" in capsys.readouterr().err and not out.exists()
    (tmp_path / "taken.png").write_bytes(b"mine")
    assert run([*argv, "--figure", str(tmp_path / "taken.png")]) == 2
    assert "--overwrite" in capsys.readouterr().err and not out.exists()
    assert (tmp_path / "taken.png").read_bytes() == b"mine"


def test_track_prints_coverage_false_tracks_on_land_and_draws(ferry, capsys):
    run_dir = ferry.run
    tracks, fig = ferry.folder / "tracks.csv", ferry.folder / "tracks.png"
    argv = ["track", str(run_dir), "--sensors", "lidar", "--tuning", "synthetic", "--out", str(tracks), "--no-progress"]
    assert run([*argv, "--figure", str(fig)]) == 0
    text = capsys.readouterr().out
    m = re.search(r"confirmed tracks (\d+): false tracks (\d+), on land (\d+)", text)
    assert m, text
    assert re.search(r"targets \(share of their time with a confirmed track\): Finn (\d+ %|never tracked), Havfruen", text)
    assert fig.read_bytes().startswith(PNG)
    # The same numbers as the library and as `seatwin evaluate` (false tracks: confirmed, never a target's nor on one
    # of the harbour's moored boats, which are don't-care).
    result = track_recording(run_dir, sensors=("lidar",), tuning="synthetic")
    s = tracking_summary(result, recording=run_dir)
    assert (s.n_confirmed, s.false_tracks, s.on_land) == tuple(int(x) for x in m.groups())
    ev = evaluate_run(result.tracks, run_dir)
    assert s.false_tracks == ev.false_tracks.n_tracks
    assert s.coverage == {t.target: t.coverage for t in ev.summaries}


def test_summary_without_truth_or_mask_says_so_and_counts_tracks_on_land(ferry):
    from seatwin.cli.track import summary_lines

    run_dir = ferry.run
    result = track_recording(run_dir, sensors=("lidar",), tuning="synthetic")
    bare = tracking_summary(dataclasses.replace(result, truth=None, water=None))
    assert (bare.false_tracks, bare.on_land, bare.coverage) == (None, None, {})
    assert summary_lines(bare)[-1].endswith("false tracks — (no ground truth in the recording), on land — (no water mask)")

    class AllLand:
        def is_water(self, north, east):  # noqa: ANN001, ANN201
            return np.zeros(np.shape(north), dtype=bool)

    land = tracking_summary(dataclasses.replace(result, water=AllLand()))
    assert land.on_land == land.n_confirmed == result.n_confirmed > 0
