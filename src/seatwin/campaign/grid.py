"""A campaign's grid as jobs: one reference job per (scenario, reference seed), one job per (scenario, setting, seed).

Jobs come in a deterministic order — scenarios, then settings combinations (``synthetic``'s fields
in the file's order, the last varying fastest), then seeds, as the file lists them — each
reference just before the first job that needs it. A job's id is the hash of its parameters
(:func:`seatwin.campaign.engine.job_id`), so it names the same work in every run of the file.
"""

from __future__ import annotations

import itertools
import os
from dataclasses import dataclass, field
from typing import Any

from pydantic import TypeAdapter

from seatwin.campaign.engine import Job
from seatwin.campaign.spec import CampaignSpec
from seatwin.errors import InputError, ParameterError
from seatwin.evaluation.compare import CompareOptions

REFERENCE = "reference"
SYNTHETIC = "synthetic"


def window_offset(span: float, duration: float, offset: float | None, scenario: str) -> float:
    """The window's start [s after the scenario's start]: ``offset``, or the window centred in ``span`` s (checked)."""
    start = offset if offset is not None else max(0.0, (span - duration) / 2)
    if start + duration > span + 1e-9:
        raise ParameterError(
            "duration" if offset is None else "offset",
            f"scenario {scenario}: the window [{start:g}, {start + duration:g}] s is not inside its {span:g} s",
        )
    return float(start)


@dataclass
class CampaignGrid:
    """Every job of a campaign, in run order, and the parts of the grid results.csv needs."""

    spec: CampaignSpec
    jobs: list[Job] = field(default_factory=list)
    """References and synthetic jobs, each reference before the jobs that need it."""

    @property
    def synthetic_jobs(self) -> list[Job]:
        return [j for j in self.jobs if j.params["kind"] == SYNTHETIC]

    @property
    def reference_jobs(self) -> list[Job]:
        return [j for j in self.jobs if j.params["kind"] == REFERENCE]

    def describe(self) -> dict[str, Any]:
        """The grid as campaign.json records it."""
        return {
            "spec": self.spec.describe(),
            "varied": list(self.spec.varied),
            "points": self.spec.n_points(),
            "jobs": len(self.synthetic_jobs),
            "reference_jobs": len(self.reference_jobs),
            "reference_seeds": "seed + reference_seed_offset (a different seed than the synthetic run's)",
        }


def reference_job(window: dict[str, Any], seed: int, settings: dict[str, Any]) -> Job:
    """The job simulating and tracking a reference run: ``window`` (scenario, start_offset, duration, tunings, and
    optionally map_spec: the water mask for tracking, default the recording's own)."""
    return Job({"kind": REFERENCE, **window, "seed": seed, "settings": dict(settings)})


def synthetic_job(reference: Job, seed: int, settings: dict[str, Any], comparison: dict[str, Any]) -> Job:
    """The job simulating ``settings`` with ``seed`` in ``reference``'s window, compared with it (its ``needs``).

    Any experiment made of "this setting against that reference" (a campaign, a sweep's degraded
    copies) builds its jobs with these two and runs them with :func:`seatwin.campaign.job.campaign_job`."""
    window = {k: v for k, v in reference.params.items() if k not in ("kind", "seed", "settings")}
    params = {
        "kind": SYNTHETIC,
        **window,
        "seed": seed,
        "settings": dict(settings),
        "reference": reference.id,
        "reference_seed": reference.params["seed"],
        "comparison": comparison,
    }
    return Job(params, needs=(reference.id,))


def _spans(spec: CampaignSpec, source: str | os.PathLike[str] | None) -> dict[str, float]:
    """Each scenario's span [s]; a scenario that cannot be loaded is an error naming it."""
    from seatwin.scenario.load import load_scenario

    spans = {}
    for name in spec.scenarios:
        try:
            sc = load_scenario(name)
        except InputError as exc:
            if source is None:
                raise ParameterError("scenarios", str(exc)) from None
            raise InputError(source, str(exc), where="scenarios") from None
        spans[name] = float(sc.end - sc.start)
    return spans


def expand_grid(spec: CampaignSpec, source: str | os.PathLike[str] | None = None) -> CampaignGrid:
    """Every job of ``spec`` (errors name ``source``, the campaign file, when given)."""
    spans = _spans(spec, source)
    comparison = TypeAdapter(CompareOptions).dump_python(spec.comparison, mode="json")
    tunings = list(spec.tunings)
    grid = CampaignGrid(spec)
    references: dict[tuple[str, int], Job] = {}
    names = spec.varied
    for scenario in spec.scenarios:
        try:
            start = window_offset(spans[scenario], spec.duration, spec.offset, scenario)
        except ParameterError as exc:
            if source is None:
                raise
            raise InputError(source, exc.detail, where=exc.param) from None
        window = {"scenario": scenario, "start_offset": start, "duration": spec.duration, "tunings": tunings}
        for values in itertools.product(*(spec.synthetic[n] for n in names)):
            for seed in spec.seeds:
                ref_seed = seed + spec.reference_seed_offset
                ref = references.get((scenario, ref_seed))
                if ref is None:
                    ref = references[(scenario, ref_seed)] = reference_job(window, ref_seed, spec.reference)
                    grid.jobs.append(ref)
                grid.jobs.append(synthetic_job(ref, seed, dict(zip(names, values)), comparison))
    return grid
