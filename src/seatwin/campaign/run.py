"""Run a campaign: its grid as jobs on the engine (Ray by default), then results.csv, campaign.json, the summary
per setting and campaign.png."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from seatwin.campaign.engine import Engine, run_jobs
from seatwin.campaign.folder import claim_folder
from seatwin.campaign.grid import SYNTHETIC, expand_grid
from seatwin.campaign.job import campaign_job
from seatwin.campaign.results import CampaignResult, write_results
from seatwin.campaign.spec import CampaignSpec, load_campaign
from seatwin.campaign.summary import CAMPAIGN_PNG, plot_campaign, summarise_campaign


def run_campaign(
    spec: CampaignSpec | str | os.PathLike[str],
    out: str | Path,
    *,
    address: str | None = None,
    workers: int | None = None,
    engine: Engine = "ray",
    progress: Callable[[int, int], None] | None = None,
    overwrite: bool = False,
) -> CampaignResult:
    """Run the campaign ``spec`` (or its YAML file) into ``out``; jobs finished there by an earlier run are not run again.

    ``engine="ray"``: a local Ray instance of ``workers`` CPUs (default: all), or the Ray cluster at
    ``address`` (``workers`` then caps the jobs in flight); ``workers=0`` or ``engine="sequential"``
    runs the jobs in this process, one by one. A failed job is recorded with its error (in
    results.csv and campaign.json) and the others go on. ``progress(done, total)`` counts jobs.
    ``out`` remembers the spec (:mod:`seatwin.campaign.folder`): another campaign's results there are refused,
    or with ``overwrite`` removed before this one starts.
    """
    source = None
    if not isinstance(spec, CampaignSpec):
        source = spec
        spec = load_campaign(spec)
    grid = expand_grid(spec, source)
    claim_folder(out, spec, None if source is None else str(source), overwrite=overwrite)
    report = run_jobs(
        grid.jobs,
        campaign_job,
        out,
        engine=engine,
        address=address,
        workers=workers,
        progress=progress,
        keep=lambda job: job.params["kind"] == SYNTHETIC,  # the rows; a reference's tracks stay in its file
    )
    result = write_results(out, grid, report)
    result.summary = summarise_campaign(result.rows, spec.varied)
    if any(s.score is not None for s in result.summary):
        result.png_path = plot_campaign(result.summary, Path(out) / CAMPAIGN_PNG, title=f"Fidelity campaign: {Path(out).name}")
    return result
