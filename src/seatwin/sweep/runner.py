"""Run a fidelity sweep: reference runs per seed, the reference model and degraded copies per (kind, strength, seed).

Every copy is compared with a reference run of a *different* seed (``seed + reference_seed_offset``):
a real and a synthetic dataset never share random draws, and a fidelity measure must work
without that crutch. The reference model itself at the copy's seed is one more point on every
kind's curve (strength = the kind's reference): its distance from the reference run is what
independent draws alone produce (the floor). ``reference_seed_offset = 0`` gives the old
seed-matched method (a copy then shares every draw with its reference but the degraded one).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from seatwin.settings import validated
from seatwin.sweep.degradations import reference_model
from seatwin.sweep.results import REFERENCE_KIND, SweepResult, SweepRow
from seatwin.sweep.settings import SweepSettings

SWEEP_OUTPUTS = ("sweep.csv", "sweep.json", "sweep.png")
"""The result files of a sweep (beside its jobs/ folder)."""


def _row(kind: str, strength: float, seed: int, ref_seed: int, rows: list[dict[str, Any]]) -> SweepRow:
    """The overall fidelity score (S5), its sensor-level part and AHED (mean over targets) of one comparison's
    per-target ``rows``."""
    ahed = [r["ahed"] for r in rows if r["ahed"] is not None]
    frac = [r["fraction_only_one"] for r in rows if r["fraction_only_one"] is not None]
    first = rows[0] if rows else {}
    return SweepRow(
        kind,
        float(strength),
        int(seed),
        int(ref_seed),
        first.get("score_overall"),
        first.get("score_overall_ci_low"),
        first.get("score_overall_ci_high"),
        float(np.mean(ahed)) if ahed else None,
        int(sum(r["n_common"] for r in rows)),
        float(np.mean(frac)) if frac else None,
        len(ahed),
        first.get("score_sensor"),
        first.get("score_sensor_ci_low"),
        first.get("score_sensor_ci_high"),
    )


def run_sweep(
    out_dir: str | Path,
    settings: SweepSettings | None = None,
    *,
    workers: int = 0,
    address: str | None = None,
    progress: Callable[[int, int], None] | None = None,
    overwrite: bool = False,
    **changes: Any,
) -> SweepResult:
    """Run the sweep of ``settings`` (default :class:`SweepSettings`, with field ``changes``) into ``out_dir``.

    Every run is a job of the campaign engine (:func:`seatwin.campaign.engine.run_jobs` with
    :func:`seatwin.campaign.job.campaign_job`): in this process (``workers=0``), on a local Ray
    instance of ``workers`` CPUs, or on the Ray cluster at ``address``; results identical either way.
    Each job's outcome is kept under ``out_dir/jobs``, so an interrupted sweep resumes where it
    stopped. ``progress(done, total)`` is called as jobs finish. A failed job is an :class:`InputError`.
    ``out_dir`` remembers the settings (:func:`seatwin.campaign.folder.claim_experiment_folder`): another sweep's
    results there are refused, or with ``overwrite`` removed first.
    """
    from pydantic import TypeAdapter

    from seatwin.campaign.engine import JOBS_DIR, run_jobs
    from seatwin.campaign.folder import claim_experiment_folder
    from seatwin.campaign.grid import reference_job, synthetic_job
    from seatwin.campaign.job import campaign_job
    from seatwin.errors import InputError
    from seatwin.evaluation.compare import CompareOptions
    from seatwin.scenario.load import load_scenario

    settings = validated(SweepSettings, {**(settings or SweepSettings()).model_dump(), **changes})
    scenario = load_scenario(settings.scenario)
    settings = settings.with_(offset=settings.window_offset(scenario.end - scenario.start))
    # No land mask, as in the published sweep figures (docs/validation.md).
    window = {
        "scenario": settings.scenario,
        "start_offset": settings.offset,
        "duration": settings.duration,
        "tunings": [settings.tuning],
        "map_spec": "none",
    }
    comparison = TypeAdapter(CompareOptions).dump_python(settings.comparison, mode="json")
    off, base = settings.reference_seed_offset, reference_model()
    refs = {s: reference_job(window, s + off, base) for s in settings.seeds}
    points = [(REFERENCE_KIND, 0.0, s, synthetic_job(refs[s], s, base, comparison)) for s in settings.seeds]
    for d in settings.degradations:
        for strength in settings.strengths_of(d):
            points += [(d.kind, strength, s, synthetic_job(refs[s], s, d.settings(strength), comparison)) for s in settings.seeds]
    jobs = list(refs.values()) + [job for *_, job in points]
    claim_experiment_folder(
        out_dir,
        "out_dir",
        kind="sweep",
        settings=settings.model_dump(mode="json"),
        files=[settings.scenario, settings.tuning],
        source=None,
        outputs=(*SWEEP_OUTPUTS, JOBS_DIR),
        overwrite=overwrite,
    )
    in_process = workers == 0 and address is None
    report = run_jobs(
        jobs,
        campaign_job,
        out_dir,
        engine="sequential" if in_process else "ray",
        workers=0 if in_process else (workers or None),
        address=address,
        progress=progress,
        keep=lambda job: job.params["kind"] != "reference",
    )
    failed = [r for r in report.records.values() if not r.ok]
    if failed:
        raise InputError(Path(out_dir) / "jobs", f"{len(failed)} of {len(jobs)} runs failed; the first: {failed[0].error}")
    result = SweepResult(settings)
    for kind, strength, seed, job in points:
        result.rows.append(_row(kind, strength, seed, seed + off, report.records[job.id].result["rows"]))
    return result
