"""The README's command table runs as written, in order (outputs under a temporary ``runs/``)."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from seatwin.cli.main import run

ROOT = Path(__file__).resolve().parents[2]


def readme_commands() -> list[str]:
    """Every backticked ``seatwin …`` command in the README's "What you can do" table, in order."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    table = text[text.index("## What you can do") : text.index("## Use it as a library")]
    cmds = []
    for line in table.splitlines():
        if line.startswith("|"):
            last_cell = line.rstrip().rstrip("|").rsplit("|", 1)[-1]
            cmds += [c for c in re.findall(r"`([^`]+)`", last_cell) if c.startswith("seatwin ")]
    return cmds


# What the README says a command shows, checked on its output (stdout, stderr), by the command's first words.
SHOWS = {
    # unmatched seeds: the real-vs-synthetic example's runs share no random draws (issue 25, item 1)
    "seatwin compare": lambda out, err: "warning" not in err,
    # one seed: integers as integers, "floor" explained, the tie said in words (issue 25, item 2)
    "seatwin fidelity": lambda out, err: (
        re.search(r"common \d+\.0\b", out) is None and "floor: AHED between" in out and "ranking by fidelity score" in out
    ),
    "seatwin scenario info": lambda out, err: "{" not in out and "…" not in out,
    # the shipped GNSS examples import to a named scenario, every vessel on water (issue 25, item 5)
    "seatwin scenario info runs/gt/": lambda out, err: out.startswith("ravnkloa_example") and "on land" not in err,
    # results shown, not only written (issue 25, item 11)
    "seatwin track runs/ferry --sensors lidar --tuning": lambda out, err: (
        re.search(r"confirmed tracks \d+: false tracks \d+, on land \d+", out) is not None and "ferry_tracks.png" in out
    ),
    "seatwin simulate ferry_crossing": lambda out, err: "on water: Havfruen 100 %, Finn 100 %, milliAmpere 100 %" in out,
    "seatwin campaign": lambda out, err: "Summary" in out and "campaign.png" in out and "Token authentication" not in err,
}


def test_the_table_is_found():
    cmds = readme_commands()
    assert len(cmds) >= 20 and cmds[0].startswith("seatwin groundtruth")
    assert not [c for c in cmds if "…" in c or "[" in c], "README commands must be runnable as written"


@pytest.mark.slow
@pytest.mark.timeout(2400)  # every README command in turn: ~7 min alone, longer on a loaded machine
def test_readme_commands_run_as_written(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(ROOT)
    shared = (ROOT.parent / "shared" / "data").is_dir()
    skipped = []
    missing: set[str] = set()  # what skipped commands would have written (runs/…): later readers skip too
    for cmd in readme_commands():
        runs = {a for a in shlex.split(cmd) if a.startswith("runs/")}
        if not shared and ("../shared" in cmd or runs & missing):
            skipped.append(cmd)
            missing |= runs
            continue
        argv = [a.replace("runs/", f"{tmp_path}/runs/") for a in shlex.split(cmd)[1:]]
        code = run(argv)
        out, err = capsys.readouterr()
        assert code == 0, f"{cmd}\n{err}"
        for prefix, shows in SHOWS.items():
            if cmd.startswith(prefix):
                assert shows(out, err), f"{cmd}\n{out}\n{err}"
    if skipped and not shared:
        pytest.skip(f"{len(skipped)} README commands need ../shared/data (or what another writes from it), which is absent")
