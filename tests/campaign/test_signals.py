"""``seatwin campaign`` and ``seatwin sweep`` stopped by SIGTERM as by Ctrl-C: one line, status 130, only finished jobs kept."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

TINY = """\
scenarios: [ferry_crossing]
seeds: [1, 2]
duration: 2.5
synthetic: {lidar_mode: [depthbuffer, raycast]}
reference: {lidar_mode: raycast}
tunings: [synthetic]
"""


def _sigterm_after_first_job(args: list[str], jobs: Path, timeout_s: float = 300.0) -> subprocess.CompletedProcess:
    proc = subprocess.Popen(
        [sys.executable, "-c", "from seatwin.cli.main import main; main()", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        for _ in range(int(timeout_s / 0.1)):  # bounded: until the first job's record is written
            if proc.poll() is not None or (jobs.is_dir() and any(jobs.glob("*.json"))):
                break
            time.sleep(0.1)
    finally:
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=120)
    return subprocess.CompletedProcess(proc.args, proc.returncode, out, err)


def _finished_records(jobs: Path) -> list[dict]:
    records = [json.loads(p.read_text()) for p in sorted(jobs.glob("*.json"))]
    assert records and all(r["ok"] for r in records), records
    return records


@pytest.mark.slow
# in this process; on a local Ray (whose ray.init replaces the SIGTERM handler), in the xdist group of the Ray tests
@pytest.mark.parametrize("workers", ["0", pytest.param("1", marks=pytest.mark.xdist_group("ray"))])
def test_campaign_stops_on_sigterm_as_on_ctrl_c(tmp_path: Path, workers: str) -> None:
    spec = tmp_path / "campaign.yaml"
    spec.write_text(TINY)
    out = tmp_path / "out"
    done = _sigterm_after_first_job(
        ["campaign", str(spec), "--out", str(out), "--workers", workers, "--no-progress"], out / "jobs"
    )
    assert done.returncode == 130, done.stderr
    assert done.stderr.strip().splitlines()[-1] == "seatwin: interrupted (SIGTERM)" and "Traceback" not in done.stderr
    n = len(_finished_records(out / "jobs"))
    assert n < 6 and not (out / "results.csv").exists()


@pytest.mark.slow
def test_sweep_stops_on_sigterm_as_on_ctrl_c(tmp_path: Path) -> None:
    out = tmp_path / "sweep"
    args = ["sweep", "--out", str(out), "--duration", "2", "--seeds", "1", "--kinds", "noise", "--workers", "0", "--no-progress"]
    done = _sigterm_after_first_job(args, out / "jobs")
    assert done.returncode == 130, done.stderr
    assert done.stderr.strip().splitlines()[-1] == "seatwin: interrupted (SIGTERM)" and "Traceback" not in done.stderr
    _finished_records(out / "jobs")
