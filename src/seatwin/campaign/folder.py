"""An experiment's output folder (a campaign, a sweep, a fidelity run: cached, resumable jobs plus result files)
remembers which experiment it holds (``<kind>-spec.json``: a fingerprint of its settings and input files), so the
results of two experiments never mix: the same settings resume, other ones are refused, or with ``overwrite``
start afresh (the earlier results and job files removed first; a user's other files stay)."""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from seatwin.campaign.engine import JOBS_DIR, canonical_json
from seatwin.campaign.results import CAMPAIGN_JSON, RESULTS_CSV
from seatwin.campaign.spec import CampaignSpec
from seatwin.errors import ParameterError
from seatwin.outputs import OutputExistsError, check_writable, refuse_inputs, remove_outputs, write_text_atomic

SPEC_FILE = "campaign-spec.json"
OUTPUTS = (RESULTS_CSV, CAMPAIGN_JSON, JOBS_DIR, SPEC_FILE)
"""What a campaign writes into its folder (nothing else there is touched)."""
HASHED_FILE_BYTES = 64 * 2**20
"""Input files up to this size are fingerprinted by content; larger ones by size and modification time."""


def fingerprint(settings: Mapping[str, Any], files: Iterable[str | os.PathLike[str] | None] = ()) -> str:
    """SHA-256 of ``settings``' canonical JSON and of each existing file in ``files`` (its content, or for a
    large one its size and modification time)."""
    h = hashlib.sha256(canonical_json(dict(settings)).encode())
    for f in files:
        if f is None or not os.path.isfile(f):
            continue
        st = os.stat(f)
        h.update(b"\0" + os.fsencode(f) + b"\0")
        h.update(Path(f).read_bytes() if st.st_size <= HASHED_FILE_BYTES else f"{st.st_size}:{st.st_mtime_ns}".encode())
    return h.hexdigest()


def spec_fingerprint(spec: CampaignSpec) -> str:
    """The fingerprint of a campaign: its spec and the scenario files it names."""
    return fingerprint(spec.model_dump(mode="json"), spec.scenarios)


def _recorded(path: Path) -> dict[str, Any] | None:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) and isinstance(data.get("fingerprint"), str) else None


def claim_experiment_folder(
    out: str | os.PathLike[str],
    param: str,
    *,
    kind: str,
    settings: Mapping[str, Any],
    files: Iterable[str | os.PathLike[str] | None],
    source: str | None,
    outputs: Iterable[str],
    overwrite: bool = False,
) -> None:
    """Make ``out`` the folder of this ``kind`` of experiment, before any job runs: refuse it if it is an input
    (``source``, ``files``) or lies in one, or holds another experiment's ``outputs`` (unless ``overwrite``:
    those are removed); record the fingerprint in ``out/<kind>-spec.json``."""
    out = Path(out)
    files = [f for f in files if f is not None]
    record_path = out / f"{kind}-spec.json"
    refuse_inputs(out, param, [source, *files])
    if os.path.lexists(out) and not os.path.isdir(out):
        raise ParameterError(param, f"{out} exists and is not a folder")
    mine = fingerprint(settings, files)
    recorded = _recorded(record_path)
    present = [out / n for n in (*outputs, record_path.name) if os.path.lexists(out / n)]
    if present and (recorded is None or recorded["fingerprint"] != mine):
        if not overwrite:
            if recorded is None:
                what = f"holds {kind} results with no record of their settings"
            elif recorded.get("source") and recorded["source"] != source:
                what = f"holds the results of another {kind} ({recorded['source']}, not {source or 'the one given'})"
            else:
                what = f"holds the results of another {kind} (other settings)"
            raise OutputExistsError(param, out, f"{what}; not mixed with them")
        remove_outputs(present)
    check_writable(record_path, param)
    record = {"fingerprint": mine, "source": source, "settings": dict(settings)}
    write_text_atomic(record_path, json.dumps(record, indent=1, default=str) + "\n")


def claim_folder(out: str | os.PathLike[str], spec: CampaignSpec, source: str | None, *, overwrite: bool = False) -> None:
    """:func:`claim_experiment_folder` for a campaign (its spec, the scenario files it names)."""
    claim_experiment_folder(
        out,
        "out",
        kind="campaign",
        settings=spec.model_dump(mode="json"),
        files=spec.scenarios,
        source=source,
        outputs=OUTPUTS,
        overwrite=overwrite,
    )
