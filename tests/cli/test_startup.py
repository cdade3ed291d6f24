"""The command line starts fast: a verb that fails on its input does so before any heavy import."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

HEAVY = ("matplotlib", "scipy.stats", "rosbags.typesys", "embreex", "trimesh")

CHILD = """
import json, sys
from seatwin.cli.main import run
code = run(sys.argv[1:])
sys.stdout.write(json.dumps({"code": code, "modules": sorted(sys.modules)}))
"""


def test_track_on_a_missing_file_answers_before_heavy_imports(tmp_path: Path) -> None:
    missing = tmp_path / "missing.mcap"
    out = tmp_path / "x.csv"
    proc = subprocess.run(
        [sys.executable, "-c", CHILD, "track", str(missing), "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path,
    )
    assert proc.returncode == 0, proc.stderr  # the child reports run()'s status on stdout
    result = json.loads(proc.stdout)
    assert result["code"] == 2
    lines = proc.stderr.strip("\n").split("\n")
    assert len(lines) == 1 and lines[0].startswith("seatwin: error: ") and str(missing) in lines[0], proc.stderr
    loaded = set(result["modules"])
    heavy = [m for m in HEAVY if m in loaded]
    assert not heavy, f"imported by a failing 'seatwin track': {heavy}"
    assert not out.exists()


def test_track_into_a_directory_fails_before_reading_the_recording(tmp_path: Path) -> None:
    """``--out DIR`` is refused before the recording is opened or anything is tracked (issue: after 30 s of work)."""
    from seatwin.cli.main import run

    rec = tmp_path / "rec"
    assert run(["simulate", "ferry_crossing", "--out", str(rec), "--duration", "0.5", "--quiet"]) == 0
    out = tmp_path / "tracks"
    out.mkdir()
    proc = subprocess.run(
        [sys.executable, "-c", CHILD, "track", str(rec), "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    result = json.loads(proc.stdout)
    assert result["code"] == 2
    lines = proc.stderr.strip("\n").split("\n")
    assert len(lines) == 1 and lines[0].startswith("seatwin: error: ") and str(out) in lines[0], proc.stderr
    loaded = set(result["modules"])
    heavy = [m for m in (*HEAVY, "seatwin.tracking.tracker") if m in loaded]
    assert not heavy, f"imported by 'seatwin track' before refusing its --out: {heavy}"
    assert not any(out.iterdir())
