"""Replay the regression corpus: every mutated file that once let a non-InputError escape (or
crashed the interpreter), kept gzip-compressed under ``corpus/`` as ``<target>__<what>.gz``."""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_helpers import CORPUS, TARGETS, corpus_bytes, corpus_cases, escape, materialize

CASES = corpus_cases()


def test_corpus_is_small_and_named_by_target() -> None:
    assert CASES, "the corpus is empty"
    assert sum(c.stat().st_size for c in CASES) < 200_000
    assert {corpus_bytes(c)[0] for c in CASES} <= set(TARGETS)
    assert not [p for p in CORPUS.iterdir() if p.suffix != ".gz"]


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_corpus_case_raises_only_input_error(case: Path, seeds: dict[str, Path], tmp_path: Path) -> None:
    target, data = corpus_bytes(case)
    path = materialize(seeds[target], data, tmp_path / "case")
    exc = escape(target, path)
    assert exc is None, f"{case.name}: {type(exc).__name__}: {exc}"
