"""The CLI path for a few corpus cases: exit status 2 and one line on stderr, no traceback."""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_helpers import CORPUS, corpus_bytes, materialize

from seatwin.cli.main import run

CASES = {
    "ros1__typesyserror-msg-00152.gz": ["bag", "info", "{path}"],
    "sqlite3__corrupterror-cursor-00120.gz": ["bag", "info", "{path}"],
    "scenario_csv__unicodedecodeerror-frozen-codecs-00118.gz": ["scenario", "info", "{path}"],
    "scenario_csv__error-gemini-csv-00069.gz": ["scenario", "info", "{path}"],
    "joyride__segfault-in-scipy-loadmat-00092.gz": ["import", "joyride", "{path}", "--out", "{out}"],
    "radar_csv__unicodedecodeerror-frozen-codecs-00042.gz": ["import", "ravnkloa-radar", "{path}", "--out", "{out}"],
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_cli_rejects_corrupt_file_in_one_line(
    name: str, seeds: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target, data = corpus_bytes(CORPUS / name)
    path = materialize(seeds[target], data, tmp_path / "case")
    argv = [a.format(path=path, out=tmp_path / "out") for a in CASES[name]]
    rc = run(argv)
    err = capsys.readouterr().err
    assert rc == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("seatwin: error: "), err
    assert str(path.name) in lines[0]
