"""The README's command table runs as written (outputs under a temporary ``runs/``): one test per command.

A command that reads what an earlier one writes (a ``runs/…`` path both name) needs that command first: the
commands linked that way form a chain, whose tests share one pytest-xdist group (``make test`` runs
``--dist loadgroup``), so one worker runs the chain in README order, each command once. A test run alone (``-k``)
runs the commands it needs first, with the same checks. Each chain writes into its own folder, so a command
that needed another chain's output without naming it would fail, never pass by the luck of scheduling.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path, PurePosixPath

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


def _runs_paths(cmd: str) -> set[PurePosixPath]:
    return {PurePosixPath(a) for a in shlex.split(cmd) if a.startswith("runs/")}


def _related(a: PurePosixPath, b: PurePosixPath) -> bool:
    """The same path, or one inside the other (a folder and a file in it)."""
    return a == b or a in b.parents or b in a.parents


def prerequisites(cmds: list[str]) -> list[list[int]]:
    """For each command, the earlier commands it needs, in order: for each of its ``runs/…`` paths, the first
    command that names it (or a folder or file inside it) — the command that writes it — and, in turn, what
    that command needs."""
    paths = [_runs_paths(c) for c in cmds]
    needs: list[list[int]] = []
    for i, mine in enumerate(paths):
        direct = set()
        for p in mine:
            writer = next(j for j in range(i + 1) if any(_related(p, q) for q in paths[j]))
            if writer != i:
                direct.add(writer)
        needs.append(sorted(direct.union(*(needs[j] for j in direct))))
    return needs


def chains(cmds: list[str]) -> list[int]:
    """For each command, its chain: the first command of the commands linked to it by what they need."""
    root = list(range(len(cmds)))

    def find(i: int) -> int:
        while root[i] != i:
            i = root[i]
        return i

    for i, needed in enumerate(prerequisites(cmds)):
        for j in needed:
            a, b = sorted((find(i), find(j)))
            root[b] = a
    return [find(i) for i in range(len(cmds))]


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

COMMANDS = readme_commands()
NEEDS = prerequisites(COMMANDS)
CHAIN = chains(COMMANDS)
SHARED = (ROOT.parent / "shared" / "data").is_dir()


def _needs_shared(i: int) -> bool:
    return any("../shared" in COMMANDS[j] for j in [*NEEDS[i], i])


def _param(i: int) -> pytest.param:
    words = [w for w in shlex.split(COMMANDS[i])[1:4] if not w.startswith("-")]
    marks = [pytest.mark.slow]
    if any(CHAIN[j] == CHAIN[i] for j in range(len(COMMANDS)) if j != i):  # a chain of several: one worker
        marks.append(pytest.mark.xdist_group(f"readme-chain-{CHAIN[i]:02d}"))
    elif COMMANDS[i].startswith("seatwin campaign"):  # it starts a local Ray: in the Ray tests' group
        marks.append(pytest.mark.xdist_group("ray"))
    return pytest.param(i, marks=marks, id=f"{i:02d}-" + "-".join(words))


class _Walk:
    """One worker's README walk: each command run at most once, in its chain's folder, with its outcome kept."""

    def __init__(self, base: Path) -> None:
        self.base = base
        self.outcome: dict[int, str | None] = {}  # command → None (ran as the README says) or what went wrong

    def run(self, i: int, capsys: pytest.CaptureFixture) -> str | None:
        if i not in self.outcome:
            runs = f"{self.base / f'chain-{CHAIN[i]:02d}'}/runs/"
            argv = [a.replace("runs/", runs) for a in shlex.split(COMMANDS[i])[1:]]
            capsys.readouterr()
            code = run(argv)
            out, err = capsys.readouterr()
            problem = None if code == 0 else f"exit status {code}\n{err}"
            for prefix, shows in SHOWS.items():
                if problem is None and COMMANDS[i].startswith(prefix) and not shows(out, err):
                    problem = f"it does not show what the README says\n{out}\n{err}"
            self.outcome[i] = problem
        return self.outcome[i]


@pytest.fixture(scope="session")
def readme_walk(tmp_path_factory: pytest.TempPathFactory) -> _Walk:
    return _Walk(tmp_path_factory.mktemp("readme"))


def test_the_table_is_found():
    assert len(COMMANDS) >= 20 and COMMANDS[0].startswith("seatwin groundtruth")
    assert not [c for c in COMMANDS if "…" in c or "[" in c], "README commands must be runnable as written"


def test_the_commands_that_read_runs_outputs_need_their_writers():
    """Chains as the README's data flow has them: ``runs/gt/…`` (groundtruth, then scenario info on its output),
    a reader needs its writer and what that needs, and commands that share no ``runs/`` path are independent."""
    gt_info = next(i for i, c in enumerate(COMMANDS) if c.startswith("seatwin scenario info runs/gt/"))
    assert NEEDS[gt_info] == [0] and CHAIN[gt_info] == 0
    for i, needed in enumerate(NEEDS):
        assert all(j < i and CHAIN[j] == CHAIN[i] for j in needed)
        assert all(set(NEEDS[j]) <= set(needed) for j in needed)  # transitive
        for j in range(i):
            if any(_related(p, q) for p in _runs_paths(COMMANDS[i]) for q in _runs_paths(COMMANDS[j])):
                assert CHAIN[i] == CHAIN[j], (COMMANDS[i], COMMANDS[j])
    assert len(set(CHAIN)) >= 10  # most commands stand alone: they run in parallel under xdist


@pytest.mark.timeout(2400)  # a command and, run alone, the commands it needs; on a loaded machine
@pytest.mark.parametrize("i", [_param(i) for i in range(len(COMMANDS))])
def test_readme_command_runs_as_written(i, readme_walk, monkeypatch, capsys):
    if not SHARED and _needs_shared(i):
        pytest.skip("this README command needs ../shared/data (or what another writes from it), which is absent")
    monkeypatch.chdir(ROOT)
    for j in NEEDS[i]:
        problem = readme_walk.run(j, capsys)
        assert problem is None, f"needs `{COMMANDS[j]}`, which failed: {problem}"
    problem = readme_walk.run(i, capsys)
    assert problem is None, f"{COMMANDS[i]}\n{problem}"
