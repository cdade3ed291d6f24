"""Fidelity campaigns: scenarios × seeds × synthetic sensor settings × tunings against a reference, as cached jobs on Ray.

``engine`` runs any list of jobs (Ray tasks or in-process, cached and resumable under an output
folder); a campaign is one user of it: ``spec`` (the YAML), ``grid`` (the jobs), ``job`` (simulate,
track, compare), ``results`` (results.csv, campaign.json), ``run`` (:func:`run_campaign`).
"""

from seatwin.campaign.engine import Job, JobRecord, RunReport, job_id, run_jobs
from seatwin.campaign.grid import CampaignGrid, expand_grid
from seatwin.campaign.results import CampaignResult, target_row
from seatwin.campaign.run import run_campaign
from seatwin.campaign.spec import CampaignSpec, load_campaign

__all__ = [
    "CampaignGrid",
    "CampaignResult",
    "CampaignSpec",
    "Job",
    "JobRecord",
    "RunReport",
    "expand_grid",
    "job_id",
    "load_campaign",
    "run_campaign",
    "run_jobs",
    "target_row",
]
