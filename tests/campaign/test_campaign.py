"""Campaigns end to end: rows per job and target, resume, a failing job, and Ray's rows equal to the sequential run's."""

from __future__ import annotations

import csv
import json

import pytest

from seatwin.campaign import load_campaign, run_campaign
from seatwin.campaign.results import TARGET_COLUMNS
from seatwin.cli.main import run
from seatwin.outputs import OutputExistsError

TINY = """\
scenarios: [ferry_crossing]
seeds: [1, 2]
duration: 2.5
synthetic: {lidar_mode: [depthbuffer, raycast]}
reference: {lidar_mode: raycast}
tunings: [synthetic]
"""


def _spec(tmp_path, text=TINY):
    path = tmp_path / "campaign.yaml"
    path.write_text(text)
    return path


def _stored(out, job_id):
    return json.loads((out / "jobs" / f"{job_id}.json").read_text())["result"]


def _rows(out):
    return list(csv.DictReader((out / "results.csv").open()))


@pytest.fixture
def count_simulations(monkeypatch):
    import seatwin.sim

    calls = []
    real = seatwin.sim.simulate_scenario

    def counted(scenario, run_dir, settings=None, **kw):
        calls.append((kw["seed"], kw.get("lidar_mode")))
        return real(scenario, run_dir, settings, **kw)

    monkeypatch.setattr(seatwin.sim, "simulate_scenario", counted)
    return calls


@pytest.mark.slow
def test_rows_and_resume(tmp_path, count_simulations):
    spec = _spec(tmp_path, TINY.replace("[1, 2]", "[1]"))
    out = tmp_path / "out"
    first = run_campaign(spec, out, engine="sequential")
    # one reference (seed 1 + 1000) shared by both synthetic jobs, simulated once
    assert sorted(count_simulations) == [(1, "depthbuffer"), (1, "raycast"), (1001, "raycast")]
    rows = _rows(out)
    assert [(r["lidar_mode"], r["target"]) for r in rows] == [
        ("depthbuffer", "Havfruen"),
        ("depthbuffer", "Finn"),
        ("raycast", "Havfruen"),
        ("raycast", "Finn"),
    ]
    assert list(rows[0]) == ["job_id", "scenario", "seed", "reference_seed", "lidar_mode", *TARGET_COLUMNS, "error"]
    for r in rows:
        assert r["scenario"] == "ferry_crossing" and r["seed"] == "1" and r["reference_seed"] == "1001"
        assert r["tuning"] == "synthetic" and r["error"] == ""
        assert 0 < int(r["n_common"]) <= int(r["n_instants"]) == 25
        assert 0.0 <= float(r["ahed"]) < 1.0
        # the lidar's sensor-level part (S7) beside S5, inside it (S5 = 1 − Π(1 − part))
        assert float(r["score_sensor_ci_low"]) <= float(r["score_sensor"]) <= float(r["score_overall"])
    table = json.loads((out / "campaign.json").read_text())
    assert table["engine"] == "sequential" and table["failed"] == 0 and table["rows"] == 4
    assert table["grid"]["varied"] == ["lidar_mode"] and table["grid"]["jobs"] == 2 and table["grid"]["reference_jobs"] == 1
    assert table["timings"]["synthetic"]["n"] == 2 and table["timings"]["synthetic"]["mean_s"] > 0
    syn = [j for j in table["jobs"] if j["kind"] == "synthetic"]
    assert all(set(j["timings"]) == {"simulate_s", "track_s", "compare_s"} for j in syn) and len(syn) == 2
    assert all(j["elapsed_s"] > 0 and j["cpu_s"] > 0 for j in table["jobs"])
    before = (out / "results.csv").read_text()

    # a re-run simulates nothing and writes the same rows
    count_simulations.clear()
    again = run_campaign(spec, out, engine="sequential")
    assert count_simulations == [] and again.report.n_cached == 3
    assert (out / "results.csv").read_text() == before
    assert json.loads((out / "campaign.json").read_text())["run"]["cached"] == 3

    # an interrupted campaign resumes: a missing job runs again, its reference comes from its file
    (out / "jobs" / f"{first.grid.synthetic_jobs[1].id}.json").unlink()
    count_simulations.clear()
    run_campaign(spec, out, engine="sequential")
    assert count_simulations == [(1, "raycast")]
    assert (out / "results.csv").read_text() == before

    # another campaign (here: one more seed) in the same folder is refused, the results untouched ...
    count_simulations.clear()
    grown = _spec(tmp_path, TINY)
    with pytest.raises(OutputExistsError, match="holds the results of another campaign"):
        run_campaign(grown, out, engine="sequential")
    assert count_simulations == [] and (out / "results.csv").read_text() == before
    # ... or with overwrite starts afresh: every job runs again, none of the first campaign's files is reused
    run_campaign(grown, out, engine="sequential", overwrite=True)
    assert len(count_simulations) == 6 and len(_rows(out)) == 8
    assert _rows(out)[:2] == rows[:2]  # same code, same seeds: the same rows


@pytest.mark.slow
def test_a_failing_job_is_recorded_and_the_others_finish(tmp_path, capsys):
    spec = _spec(
        tmp_path, TINY.replace("[1, 2]", "[1]").replace("lidar_mode: [depthbuffer, raycast]", "harbour: [/no/land.bin, default]")
    )
    out = tmp_path / "out"
    assert run(["campaign", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 1
    captured = capsys.readouterr()
    assert "1 failed" in captured.out and "map raster file not found" in captured.err
    rows = _rows(out)
    assert [r["harbour"] for r in rows] == ["/no/land.bin", "default", "default"]
    assert rows[0]["error"].startswith("harbour: /no/land.yaml: map raster file not found") and rows[0]["target"] == ""
    assert all(r["error"] == "" and r["ahed"] != "" for r in rows[1:])
    table = json.loads((out / "campaign.json").read_text())
    failed = [j for j in table["jobs"] if j["status"] == "failed"]
    assert len(failed) == 1 and "Traceback" not in failed[0]["error"] and table["failed"] == 1


@pytest.fixture(scope="module")
def local_ray():
    """One local Ray instance of 2 CPUs for the module (run_jobs uses it, capping jobs in flight at ``workers``)."""
    ray = pytest.importorskip("ray")
    import logging

    ray.init(num_cpus=2, include_dashboard=False, logging_level=logging.WARNING, log_to_driver=False)
    yield ray
    ray.shutdown()


# The tests that start Ray share one xdist group (``make test`` runs --dist loadgroup): one worker runs them, so
# they share this module's Ray instance and two Ray instances never start side by side on the test machine.
@pytest.mark.slow
@pytest.mark.xdist_group("ray")
def test_ray_rows_equal_the_sequential_runs(tmp_path, local_ray):
    spec = load_campaign(_spec(tmp_path))
    seq = run_campaign(spec, tmp_path / "seq", engine="sequential")
    assert seq.report.engine == "sequential" and len(seq.rows) == 8
    expected = (tmp_path / "seq" / "results.csv").read_bytes()
    for workers in (1, 2):
        out = tmp_path / f"ray{workers}"
        result = run_campaign(spec, out, workers=workers)
        assert result.report.engine == "ray" and result.report.n_run == 6 and result.n_failed == 0
        assert (out / "results.csv").read_bytes() == expected, workers  # bit-identical, whatever the workers
        table = json.loads((out / "campaign.json").read_text())
        assert table["engine"] == "ray" and table["run"]["workers"] == workers and table["versions"]["ray"]
        for job in result.grid.jobs:  # every job's stored result too (the reference's tracks included)
            key = "rows" if job.needs else "tracks"
            assert _stored(out, job.id)[key] == _stored(tmp_path / "seq", job.id)[key]
            # the driver keeps the rows, and lets a reference's tracks go once its jobs are done
            assert (result.report.records[job.id].result is None) == (not job.needs)


@pytest.mark.slow
@pytest.mark.xdist_group("ray")
def test_cli_on_ray_with_a_failing_job(tmp_path, local_ray, capsys):
    text = TINY.replace("[1, 2]", "[3]").replace("lidar_mode: [depthbuffer, raycast]", "harbour: [default, /no/land.bin]")
    out = tmp_path / "out"
    assert run(["campaign", str(_spec(tmp_path, text)), "--out", str(out), "--workers", "2", "--no-progress"]) == 1
    captured = capsys.readouterr()
    assert "3 jobs on local Ray: 3 run, 0 already done, 1 failed" in captured.out
    rows = _rows(out)
    assert rows[-1]["harbour"] == "/no/land.bin" and "map raster file not found" in rows[-1]["error"]
    assert all(r["ahed"] != "" for r in rows[:-1])
    assert json.loads((out / "campaign.json").read_text())["engine"] == "ray"
