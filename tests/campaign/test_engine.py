"""The job engine in this process: records per job, resume, failures recorded without stopping the others."""

from __future__ import annotations

import json

import pytest

from seatwin.campaign import Job, run_jobs
from seatwin.campaign.engine import check_jobs, error_message
from seatwin.errors import InputError, ParameterError

CALLS: list[int] = []


def square_or_fail(params, inputs):
    CALLS.append(params["x"])
    if params["x"] == 3:
        raise RuntimeError("three is\nunlucky")
    return {"y": params["x"] ** 2 + sum(r["y"] for r in inputs.values()), "half": params["x"] / 2}


@pytest.fixture(autouse=True)
def _clear():
    CALLS.clear()


def _jobs():
    a, b, c = Job({"x": 1}), Job({"x": 2}), Job({"x": 3})
    return [a, b, c, Job({"x": 4}, needs=(a.id, b.id)), Job({"x": 5}, needs=(c.id,))]


def test_records_failures_and_dependents(tmp_path):
    jobs = _jobs()
    seen = []
    report = run_jobs(jobs, square_or_fail, tmp_path, engine="sequential", progress=lambda d, t: seen.append((d, t)))
    assert CALLS == [1, 2, 3, 4]  # 5 needs the failed 3: not run
    recs = [report.records[j.id] for j in jobs]
    assert [r.ok for r in recs] == [True, True, False, True, False]
    assert recs[3].result == {"y": 16 + 1 + 4, "half": 2.0}
    assert recs[2].error == "RuntimeError: three is unlucky"  # one line, no traceback
    assert recs[4].error == f"needs job {jobs[2].id}, which failed: RuntimeError: three is unlucky"
    assert seen[0] == (0, 5) and seen[-1] == (5, 5)
    assert (report.n_run, report.n_cached, report.n_failed) == (5, 0, 2)
    stored = json.loads((tmp_path / "jobs" / f"{jobs[3].id}.json").read_text())
    assert stored["status"] == "ok" and stored["params"] == {"x": 4} and stored["result"]["y"] == 21
    failed = json.loads((tmp_path / "jobs" / f"{jobs[2].id}.json").read_text())
    assert failed["status"] == "failed" and failed["error"] == "RuntimeError: three is unlucky"
    assert not list((tmp_path / "jobs").glob(".*"))  # no temporary files left behind


def test_rerun_skips_finished_jobs_and_retries_failed_ones(tmp_path):
    jobs = _jobs()
    first = run_jobs(jobs, square_or_fail, tmp_path, engine="sequential")
    CALLS.clear()
    again = run_jobs(jobs, square_or_fail, tmp_path, workers=0)  # workers=0: in this process
    assert again.engine == "sequential"
    assert CALLS == [3]  # only the failed one runs again (and fails again; its dependent is not run)
    assert (again.n_cached, again.n_run, again.n_failed) == (3, 2, 2)
    for j in jobs:
        assert again.records[j.id].result == first.records[j.id].result
    # a removed record is run again, and a job needing a finished job gets its stored result
    (tmp_path / "jobs" / f"{jobs[3].id}.json").unlink()
    CALLS.clear()
    third = run_jobs(jobs[:2] + [jobs[3]], square_or_fail, tmp_path, engine="sequential")
    assert CALLS == [4] and third.records[jobs[3].id].result == first.records[jobs[3].id].result
    # a record whose parameters differ from the job's (a corrupt or foreign file) is not trusted
    path = tmp_path / "jobs" / f"{jobs[0].id}.json"
    path.write_text(path.read_text().replace('"x": 1', '"x": 7'))
    CALLS.clear()
    run_jobs(jobs[:1], square_or_fail, tmp_path, engine="sequential")
    assert CALLS == [1]


def test_results_of_other_code_are_run_again_and_a_worker_with_other_code_fails(tmp_path, monkeypatch):
    from seatwin.campaign import engine
    from seatwin.provenance import code_fingerprint

    jobs = _jobs()[:2]
    first = run_jobs(jobs, square_or_fail, tmp_path, engine="sequential")
    assert {r.code for r in first.records.values()} == {code_fingerprint()}
    assert json.loads((tmp_path / "jobs" / f"{jobs[0].id}.json").read_text())["code"] == code_fingerprint()
    path = tmp_path / "jobs" / f"{jobs[0].id}.json"
    path.write_text(path.read_text().replace(code_fingerprint(), "0123456789abcdef"))  # made by other code
    CALLS.clear()
    again = run_jobs(jobs, square_or_fail, tmp_path, engine="sequential")
    assert CALLS == [1] and (again.n_cached, again.n_stale) == (1, 1)
    assert again.describe()["rerun_for_other_code"] == 1 and again.describe()["code"] == code_fingerprint()

    # a worker whose seatwin differs from the driver's (a cluster node not updated): its result is not kept,
    # and a job needing it does not run on it either
    real_execute = engine.execute

    def on_other_node(fn, job, *needed):
        record = real_execute(fn, job, *needed)
        record.code, record.host = "fedcba9876543210", "node7"
        return record

    monkeypatch.setattr(engine, "execute", on_other_node)
    a = Job({"x": 10})
    report = run_jobs([a, Job({"x": 11}, needs=(a.id,))], square_or_fail, tmp_path / "other", engine="sequential")
    rec_a, rec_b = report.records.values()
    assert not rec_a.ok and rec_a.result is None
    assert rec_a.error == (
        f"ran on node7 with seatwin code fedcba9876543210, but this driver runs code {code_fingerprint()}: "
        "install the same seatwin on every node"
    )
    assert not rec_b.ok and rec_b.error.startswith(f"needs job {a.id}, which failed: ran on node7")
    # on Ray a dependent task gets the needed result as the worker returned it: it checks the code itself
    monkeypatch.setattr(engine, "execute", real_execute)
    stale_input = engine.JobRecord(a.id, a.params, True, {"y": 100}, code="fedcba9876543210")
    rec = engine.execute(square_or_fail, Job({"x": 11}, needs=(a.id,)), stale_input)
    assert not rec.ok
    assert rec.error == f"needs job {a.id}, which ran with seatwin code fedcba9876543210, not this worker's {code_fingerprint()}"


def test_bad_job_lists_and_options(tmp_path):
    a = Job({"x": 1})
    with pytest.raises(ParameterError, match="listed twice"):
        check_jobs([a, Job({"x": 1})])
    with pytest.raises(ParameterError, match="not listed before it"):
        check_jobs([Job({"x": 2}, needs=(a.id,)), a])
    with pytest.raises(ParameterError) as err:
        run_jobs([a], square_or_fail, tmp_path, engine="spark")
    assert err.value.param == "engine"
    with pytest.raises(ParameterError) as err:
        run_jobs([a], square_or_fail, tmp_path, workers=0, address="ray://x:1")
    assert err.value.param == "workers"
    (tmp_path / "file").write_text("")
    with pytest.raises(ParameterError) as err:
        run_jobs([a], square_or_fail, tmp_path / "file", engine="sequential")
    assert err.value.param == "out_dir"


def test_error_message():
    assert error_message(InputError("f.yaml", "bad", where="x")) == "f.yaml: x: bad"
    assert error_message(KeyError("k")) == "KeyError: 'k'"
    assert error_message(ZeroDivisionError()) == "ZeroDivisionError"


def test_results_not_kept_are_let_go_but_reach_the_jobs_that_need_them(tmp_path):
    jobs = _jobs()
    a, b, d = jobs[0], jobs[1], jobs[3]

    def keep(job):
        return job.params["x"] >= 4

    report = run_jobs(jobs, square_or_fail, tmp_path, engine="sequential", keep=keep)
    assert report.records[a.id].result is None and report.records[b.id].result is None
    assert report.records[d.id].result == {"y": 21, "half": 2.0}
    # d again: a's and b's results come back from their files for it, and are let go again
    (tmp_path / "jobs" / f"{d.id}.json").unlink()
    CALLS.clear()
    again = run_jobs(jobs, square_or_fail, tmp_path, engine="sequential", keep=keep)
    assert CALLS == [3, 4] and again.records[d.id].result == {"y": 21, "half": 2.0}
    assert again.records[a.id].result is None and again.records[a.id].cached


def test_an_unreachable_ray_address_is_refused_at_once(tmp_path):
    import socket

    from seatwin.campaign.engine import check_address

    with socket.socket() as s:  # a port nothing listens at: bound, never listening
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
        for address in (f"127.0.0.1:{port}", f"ray://127.0.0.1:{port}"):
            with pytest.raises(ParameterError, match="cannot reach a Ray cluster") as err:
                check_address(address)
            assert err.value.param == "address"
        with pytest.raises(ParameterError, match="cannot reach"):
            run_jobs([Job({"x": 1})], square_or_fail, tmp_path, address=f"127.0.0.1:{port}")
    check_address("auto")  # left to Ray
