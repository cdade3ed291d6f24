"""Run many independent jobs, cached and resumable, as Ray tasks or one by one in this process.

A :class:`Job` is a JSON-able mapping of parameters with a stable id (a hash of them,
:func:`job_id`) and the ids of the jobs whose results it needs. :func:`run_jobs` runs
``fn(params, inputs)`` for each — ``inputs`` maps every needed job's id to its result — and
keeps each outcome as ``out_dir/jobs/<id>.json``, written atomically by the driver as the job
finishes, so that:

* a re-run skips the jobs whose file says ``ok`` and was written by the code running now
  (:func:`seatwin.provenance.code_fingerprint`; a failed job, or one run by other code, is run again);
* a job that raises is recorded with its error message and never stops the others (a job that
  needs a failed one fails with the reason, without running);
* the driver does all the file I/O: tasks only compute and return, so a cluster needs no shared
  file system (only seatwin installed on every node; a result from a worker whose seatwin differs
  from the driver's is recorded as failed, with both fingerprints).

Engines: ``"ray"`` submits every job as a Ray task (dependencies passed as object references,
so a needed result travels between nodes once) on a local Ray instance of ``workers`` CPUs, or
on the cluster at ``address``; ``"sequential"`` runs them in this process in order — the
reference a Ray run must equal. Each job is a pure function of its parameters (every random
draw is keyed by a seed in them, :mod:`seatwin.rng`), so the results are bit-identical whatever
the engine, the number of workers or the order in which jobs finish.

A campaign (:mod:`seatwin.campaign.campaign`) is one user; a sweep (reference and degraded runs
per seed, the degraded ones needing their reference) or fidelity seeds map onto it the same way.
"""

from __future__ import annotations

import hashlib
import json
import os
import socket
import time
from collections import Counter
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Literal

from seatwin.errors import InputError, ParameterError
from seatwin.provenance import code_fingerprint

Engine = Literal["ray", "sequential"]
ENGINES: tuple[str, ...] = ("ray", "sequential")
JOBS_DIR = "jobs"
ID_LENGTH = 16
JobFn = Callable[[dict[str, Any], dict[str, Any]], Any]
"""``fn(params, inputs)`` → a JSON-able result; ``inputs`` maps each needed job's id to its result."""


def canonical_json(value: Any) -> str:
    """``value`` as JSON with sorted keys and no spaces: the same text for the same value, always."""
    try:
        return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise ParameterError("params", f"a job's parameters must be finite JSON values: {exc}") from None


def job_id(params: Mapping[str, Any]) -> str:
    """A stable id of a job's parameters: the first 16 hex digits of the SHA-256 of their canonical JSON."""
    return hashlib.sha256(canonical_json(params).encode()).hexdigest()[:ID_LENGTH]


@dataclass(frozen=True)
class Job:
    """One unit of work: its parameters, their id, and the ids of the jobs whose results it needs."""

    params: dict[str, Any]
    needs: tuple[str, ...] = ()
    id: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "params", json.loads(canonical_json(self.params)) if self.params else {})
        object.__setattr__(self, "needs", tuple(self.needs))
        if not self.id:
            object.__setattr__(self, "id", job_id(self.params))


@dataclass
class JobRecord:
    """A job's outcome, as ``jobs/<id>.json`` keeps it."""

    id: str
    params: dict[str, Any]
    ok: bool
    result: Any = None
    error: str | None = None
    elapsed_s: float = 0.0
    """Seconds the job's function ran (on the worker)."""
    cpu_s: float = 0.0
    """CPU seconds of the worker's process meanwhile (all its threads): the cost, whatever else shares the machine."""
    host: str = ""
    code: str = ""
    """The fingerprint of the seatwin code that ran it (:func:`seatwin.provenance.code_fingerprint`)."""
    cached: bool = False
    """True when this run found it finished and did not run it again (not stored)."""

    def to_json(self) -> dict[str, Any]:
        d = asdict(self)
        d.pop("cached")
        return {"status": "ok" if self.ok else "failed", **d}


@dataclass
class RunReport:
    """What :func:`run_jobs` did: every job's record in the order given, and how it ran."""

    records: dict[str, JobRecord]
    engine: str
    workers: int | None
    address: str | None
    wall_s: float
    ray_version: str | None = None
    cluster_cpus: float | None = None
    n_run: int = 0
    n_cached: int = 0
    n_failed: int = 0
    n_stale: int = 0
    """Finished jobs run again because other code had run them."""
    extra: dict[str, Any] = field(default_factory=dict)

    def describe(self) -> dict[str, Any]:
        """The engine's part of a results JSON: engine, workers, counts and timings."""
        ran = [r for r in self.records.values() if not r.cached]
        return {
            "engine": self.engine,
            "address": self.address,
            "workers": self.workers,
            "cluster_cpus": self.cluster_cpus,
            "ray_version": self.ray_version,
            "jobs": len(self.records),
            "run": self.n_run,
            "cached": self.n_cached,
            "failed": self.n_failed,
            "rerun_for_other_code": self.n_stale,
            "code": code_fingerprint(),
            "wall_s": self.wall_s,
            "job_s_this_run": float(sum(r.elapsed_s for r in ran)),
            "job_cpu_s_this_run": float(sum(r.cpu_s for r in ran)),
            "job_s_all": float(sum(r.elapsed_s for r in self.records.values())),
            "job_cpu_s_all": float(sum(r.cpu_s for r in self.records.values())),
        }


def error_message(exc: BaseException) -> str:
    """One line for a failed job: an input error's own message, else the exception's type and message."""
    if isinstance(exc, InputError):
        return str(exc)
    text = " ".join(str(exc).split())
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def execute(fn: JobFn, job: Job, *needed: JobRecord) -> JobRecord:
    """Run one job (in a Ray worker or in this process): its record, never an exception."""
    host, code = socket.gethostname(), code_fingerprint()
    failed = [f"needs job {r.id}, which failed: {r.error}" for r in needed if not r.ok]
    other = [
        f"needs job {r.id}, which ran with seatwin code {r.code}, not this worker's {code}" for r in needed if r.code != code
    ]
    if failed or other:
        return JobRecord(job.id, job.params, False, error=(failed + other)[0], host=host, code=code)
    start, cpu = time.perf_counter(), time.process_time()
    try:
        # through JSON, so that a fresh result is exactly what a later run reads back from the job's file
        result = json.loads(json.dumps(fn(dict(job.params), {r.id: r.result for r in needed})))
        ok, error = True, None
    except Exception as exc:  # noqa: BLE001 - a job's failure is recorded, never stops the others
        result, ok, error = None, False, error_message(exc)
    elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu
    return JobRecord(job.id, job.params, ok, result, error, elapsed, cpu, host=host, code=code)


def execute_in_task(fn: JobFn, job: Job, *needed: JobRecord) -> JobRecord:
    """:func:`execute` in a Ray task of one CPU: seatwin's own thread pools (Embree casts) use one thread too,
    unless ``SEATWIN_THREADS`` says otherwise (threads never change results, only contention)."""
    os.environ.setdefault("SEATWIN_THREADS", "1")
    return execute(fn, job, *needed)


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file beside it, so a reader never sees half a file."""
    from seatwin.outputs import write_text_atomic

    write_text_atomic(path, text)


def record_path(out_dir: Path, job_id_: str) -> Path:
    return out_dir / JOBS_DIR / f"{job_id_}.json"


def _finished(out_dir: Path, job: Job) -> dict[str, Any] | None:
    """The file of ``job`` under ``out_dir`` if it holds a finished (``ok``) run of these params, by any code."""
    try:
        data = json.loads(record_path(out_dir, job.id).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("status") != "ok" or data.get("params") != job.params:
        return None
    return data


def read_record(out_dir: Path, job: Job) -> JobRecord | None:
    """A finished (``ok``) record of ``job`` under ``out_dir`` written by the code running now, else None
    (missing, failed, unreadable, other params, other code)."""
    return _current_record(job, _finished(out_dir, job))


def _current_record(job: Job, data: dict[str, Any] | None) -> JobRecord | None:
    """The record in ``data`` (a :func:`_finished` file) if the code running now wrote it, else None."""
    if data is None or data.get("code") != code_fingerprint():
        return None
    return JobRecord(
        job.id,
        job.params,
        True,
        data.get("result"),
        None,
        float(data.get("elapsed_s", 0.0)),
        float(data.get("cpu_s", 0.0)),
        str(data.get("host", "")),
        str(data.get("code", "")),
        True,
    )


def write_record(out_dir: Path, record: JobRecord) -> None:
    write_atomic(record_path(out_dir, record.id), json.dumps(record.to_json()))


def check_jobs(jobs: Sequence[Job]) -> None:
    """Ids unique, and every needed job listed before the jobs that need it."""
    seen: set[str] = set()
    for job in jobs:
        if job.id in seen:
            raise ParameterError("jobs", f"job {job.id} is listed twice")
        missing = [n for n in job.needs if n not in seen]
        if missing:
            raise ParameterError("jobs", f"job {job.id} needs {missing[0]}, which is not listed before it")
        seen.add(job.id)


def _sequential(fn: JobFn, todo: list[Job], records: dict[str, JobRecord], done: Callable[[JobRecord], None]) -> None:
    for job in todo:
        done(execute(fn, job, *(records[n] for n in job.needs)))


def check_address(address: str, timeout_s: float = 5.0) -> None:
    """Refuse at once a Ray address (``host:port`` or ``ray://host:port``) nothing listens at (Ray itself would retry
    for minutes); ``auto``, ``local`` and other forms are left to Ray."""
    hostport = address.removeprefix("ray://")
    host, sep, port = hostport.rpartition(":")
    if not sep or not host or not port.isdigit():
        return
    try:
        socket.create_connection((host.strip("[]"), int(port)), timeout=timeout_s).close()
    except OSError as exc:
        raise ParameterError("address", f"cannot reach a Ray cluster at {address}: {exc.strerror or exc}") from None


class _DropMessage:
    """A logging filter dropping the records whose message starts with ``prefix``."""

    def __init__(self, prefix: str) -> None:
        self.prefix = prefix

    def filter(self, record: Any) -> bool:
        return not str(record.getMessage()).startswith(self.prefix)


def _ray_init(address: str | None, workers: int | None) -> tuple[Any, bool]:
    """The ``ray`` module, initialised (a local instance of ``workers`` CPUs, or the cluster at ``address``), and
    whether this call started it (a Ray already initialised in this process is used as it is)."""
    import logging

    try:
        import ray
    except ImportError:
        raise ParameterError("engine", "the Ray engine needs the 'ray' package (pip install ray)") from None
    if ray.is_initialized():
        return ray, False
    if address:
        check_address(address)
    from seatwin.interrupts import sigterm_kept

    try:
        with sigterm_kept():  # SIGTERM stays a Ctrl-C (ray.init installs an exit without finishing)
            if address:
                ray.init(address=address, logging_level=logging.WARNING, log_to_driver=False)
            else:  # a local instance: Ray's note that token auth is on (its secure default) says nothing to act on
                auth_log = logging.getLogger("ray._private.authentication.authentication_token_setup")
                note = _DropMessage("Token authentication is enabled")
                auth_log.addFilter(note)
                try:
                    ray.init(num_cpus=workers, include_dashboard=False, logging_level=logging.WARNING, log_to_driver=False)
                finally:
                    auth_log.removeFilter(note)
    except (ConnectionError, RuntimeError, ValueError) as exc:
        raise ParameterError("address" if address else "workers", f"cannot start Ray: {error_message(exc)}") from None
    return ray, True


def _ray(
    fn: JobFn,
    todo: list[Job],
    records: dict[str, JobRecord],
    done: Callable[[JobRecord], None],
    ray: Any,
    limit: int | None,
) -> None:
    """Submit ``todo`` in order — with a ``limit`` on the jobs in flight, only jobs whose inputs are ready — and hand
    each record to ``done`` as it finishes."""
    task = ray.remote(num_cpus=1)(execute_in_task)
    fn_ref = ray.put(fn)
    refs: dict[str, Any] = {}
    unsubmitted = Counter(n for job in todo for n in job.needs)
    job_of: dict[Any, Job] = {}
    queue = list(todo)
    pending: list[Any] = []

    def submit(job: Job) -> None:
        for n in job.needs:
            if n not in refs:  # a finished (cached) job: its record goes to the object store once
                refs[n] = ray.put(records[n])
        ref = task.remote(fn_ref, job, *(refs[n] for n in job.needs))
        for n in job.needs:
            unsubmitted[n] -= 1
            if not unsubmitted[n]:  # its last user is submitted: the tasks hold the object from here on
                del refs[n]
        if unsubmitted[job.id]:
            refs[job.id] = ref
        job_of[ref] = job
        pending.append(ref)

    def next_runnable() -> int | None:
        """Without a cap, the next job; with one, the first whose needed jobs have finished (a task waiting for its
        inputs would hold a slot of the cap without running)."""
        if limit is None:
            return 0
        return next((i for i, job in enumerate(queue) if all(n in records for n in job.needs)), None)

    while queue or pending:
        while queue and (limit is None or len(pending) < limit):
            i = next_runnable()
            if i is None:
                break
            submit(queue.pop(i))
        ready, pending[:] = ray.wait(pending, num_returns=1)
        for ref in ready:
            job = job_of.pop(ref)
            try:
                record = ray.get(ref)
            except Exception as exc:  # noqa: BLE001 - a lost worker or node fails this job, not the run
                record = JobRecord(job.id, job.params, False, error=error_message(exc))
            done(record)


def run_jobs(
    jobs: Iterable[Job],
    fn: JobFn,
    out_dir: str | Path,
    *,
    engine: Engine = "ray",
    address: str | None = None,
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    keep: Callable[[Job], bool] | None = None,
) -> RunReport:
    """Run ``fn`` for every job not yet finished under ``out_dir``; every job's record, in the order of ``jobs``.

    ``engine``: ``"ray"`` (a local Ray instance of ``workers`` CPUs — default all — or the cluster at
    ``address``, where ``workers`` caps the jobs in flight; a Ray instance already started in this
    process is used as it is) or ``"sequential"`` (in this process, one by one; ``workers=0`` means
    the same). ``fn`` must be picklable (a module-level function) for Ray. ``progress(done, total)``
    is called as jobs finish (cached ones count as done from the start). ``keep(job)``: whether the
    returned record of ``job`` holds its result (default: all); the others' results are let go as
    soon as no job still to run needs them (their files keep them), so that large intermediate
    results (a campaign's reference tracks) do not pile up in the driver's memory.
    """
    jobs = list(jobs)
    check_jobs(jobs)
    if engine not in ENGINES:
        raise ParameterError("engine", f"expected one of {', '.join(ENGINES)}, got {engine!r}")
    if workers is not None and workers < 0:
        raise ParameterError("workers", f"expected 0 (run in this process) or more, got {workers}")
    if workers == 0:
        if address:
            raise ParameterError("workers", "0 workers runs the jobs in this process; it cannot go with a Ray address")
        engine = "sequential"
    out_dir = Path(out_dir)
    try:
        (out_dir / JOBS_DIR).mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ParameterError("out_dir", f"cannot create {out_dir / JOBS_DIR}: {exc.strerror or exc}") from None
    start = time.perf_counter()
    keep = keep or (lambda _job: True)
    records: dict[str, JobRecord] = {}
    todo: list[Job] = []
    n_stale = 0
    for job in jobs:
        data = _finished(out_dir, job)
        cached = _current_record(job, data)
        if cached is None:
            n_stale += data is not None
            todo.append(job)
            continue
        if not keep(job):
            cached.result = None  # read again below if a job still to run needs it
        records[job.id] = cached
    by_id = {job.id: job for job in jobs}
    users = Counter(n for job in todo for n in job.needs)
    for n in users:
        if n in records and not keep(by_id[n]):
            records[n] = read_record(out_dir, by_id[n]) or records[n]
    n_done = len(records)
    if progress is not None:
        progress(n_done, len(jobs))

    def release(job_id_: str) -> None:
        """Forget a result nobody keeps once no job still to run needs it (its file keeps it)."""
        if not users[job_id_] and not keep(by_id[job_id_]):
            records[job_id_].result = None

    def done(record: JobRecord) -> None:
        nonlocal n_done
        if record.ok and record.code != code_fingerprint():
            record.ok, record.result = False, None
            record.error = (
                f"ran on {record.host} with seatwin code {record.code}, but this driver runs code {code_fingerprint()}: "
                "install the same seatwin on every node"
            )
        records[record.id] = record
        write_record(out_dir, record)
        release(record.id)
        for n in by_id[record.id].needs:
            users[n] -= 1
            release(n)
        n_done += 1
        if progress is not None:
            progress(n_done, len(jobs))

    report = RunReport({}, engine, workers, address if engine == "ray" else None, 0.0)
    if engine == "sequential":
        _sequential(fn, todo, records, done)
    elif todo:
        ray, started = _ray_init(address, workers)
        try:
            report.ray_version = ray.__version__
            report.cluster_cpus = float(ray.cluster_resources().get("CPU", 0.0))
            limit = workers if (address or not started) else None
            _ray(fn, todo, records, done, ray, limit)
        finally:
            if started:
                ray.shutdown()
    report.records = {job.id: records[job.id] for job in jobs}
    report.wall_s = time.perf_counter() - start
    report.n_cached = sum(r.cached for r in report.records.values())
    report.n_run = len(jobs) - report.n_cached
    report.n_failed = sum(not r.ok for r in report.records.values())
    report.n_stale = n_stale
    return report
