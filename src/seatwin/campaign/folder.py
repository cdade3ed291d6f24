"""A campaign's output folder remembers which campaign it holds (``campaign-spec.json``: the spec's
fingerprint), so the results of two different campaigns never mix: the same spec resumes, another one
is refused, or with ``overwrite`` starts afresh (the earlier results and job files removed first)."""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any

from seatwin.campaign.engine import JOBS_DIR, canonical_json
from seatwin.campaign.results import CAMPAIGN_JSON, RESULTS_CSV
from seatwin.campaign.spec import CampaignSpec
from seatwin.outputs import OutputExistsError, check_writable, refuse_inputs, remove_outputs, write_text_atomic

SPEC_FILE = "campaign-spec.json"
OUTPUTS = (RESULTS_CSV, CAMPAIGN_JSON, JOBS_DIR, SPEC_FILE)
"""What a campaign writes into its folder (nothing else there is touched)."""


def spec_fingerprint(spec: CampaignSpec) -> str:
    """SHA-256 of the spec's canonical JSON and of the content of every scenario file it names."""
    h = hashlib.sha256(canonical_json(spec.model_dump(mode="json")).encode())
    for scenario in spec.scenarios:
        if os.path.isfile(scenario):
            h.update(b"\0" + scenario.encode() + b"\0" + Path(scenario).read_bytes())
    return h.hexdigest()


def _recorded(out: Path) -> dict[str, Any] | None:
    try:
        data = json.loads((out / SPEC_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) and isinstance(data.get("fingerprint"), str) else None


def claim_folder(out: str | os.PathLike[str], spec: CampaignSpec, source: str | None, *, overwrite: bool = False) -> None:
    """Make ``out`` the folder of this campaign, before any job runs: refuse it if it is an input or lies in
    one, or holds another campaign's results (unless ``overwrite``: those are removed); record the spec."""
    out = Path(out)
    label = source or "the campaign given"
    refuse_inputs(out, "out", [source, *spec.scenarios])
    if os.path.lexists(out) and not os.path.isdir(out):
        raise OutputExistsError("out", out, "exists and is not a folder")
    fingerprint = spec_fingerprint(spec)
    recorded = _recorded(out)
    present = [out / n for n in OUTPUTS if os.path.lexists(out / n)]
    if present and (recorded is None or recorded["fingerprint"] != fingerprint):
        if not overwrite:
            earlier = f"another campaign ({recorded.get('source') or 'a spec given in code'})" if recorded else "campaign results"
            raise OutputExistsError("out", out, f"holds the results of {earlier}, not of {label}; not mixed with them")
        remove_outputs(present)
    check_writable(out / SPEC_FILE, "out")
    record = {"fingerprint": fingerprint, "source": None if source is None else str(source), "spec": spec.model_dump(mode="json")}
    write_text_atomic(out / SPEC_FILE, json.dumps(record, indent=1) + "\n")
