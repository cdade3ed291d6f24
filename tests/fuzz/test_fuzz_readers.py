"""Property-based fuzzing of every reader: a mutated valid file is either read or rejected with
:class:`InputError` (one line); nothing else escapes. Budgets are bounded (``max_examples``,
derandomised so the suite is deterministic); the bag readers' larger budgets are marked slow.
``measure_escapes.py`` runs the same mutations at scale."""

from __future__ import annotations

import traceback
from pathlib import Path

import pytest
from fuzz_helpers import BINARY_KINDS, FAMILY_KINDS, TARGETS, TEXT_KINDS, apply, escape, materialize
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

# campaign_yaml is fuzzed by the yaml family only (families.py); its byte-level escapes belong to issue #20's YAML part
TEXT_TARGETS = [n for n, t in TARGETS.items() if t.text and n not in ("rosbag2_yaml", "campaign_yaml")]
BAG_TARGETS = ["ros1", "mcap", "sqlite3"]
_SETTINGS = dict(deadline=None, derandomize=True, database=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


def mutations(text: bool, kinds: tuple[str, ...] | None = None) -> st.SearchStrategy:
    kinds = kinds or BINARY_KINDS + (TEXT_KINDS if text else ())
    one = st.tuples(st.sampled_from(kinds), st.integers(0, 2**30), st.integers(0, 2**16))
    return st.lists(one, min_size=1, max_size=3)


def _check(target: str, seeds: dict[str, Path], work: Path, muts: list) -> None:
    seed = seeds[target]
    path = materialize(seed, apply(seed.read_bytes(), muts), work / "mutant")
    exc = escape(target, path)
    if exc is not None:
        tb = "".join(traceback.format_exception(exc))
        pytest.fail(f"{target}: mutations {muts} let {type(exc).__name__} escape:\n{tb}")


@pytest.mark.parametrize("target", TEXT_TARGETS + ["joyride"])
@settings(max_examples=50, **_SETTINGS)
@given(data=st.data())
def test_text_and_mat_readers_raise_only_input_error(target: str, seeds: dict[str, Path], tmp_path: Path, data) -> None:
    _check(target, seeds, tmp_path, data.draw(mutations(TARGETS[target].text)))


@pytest.mark.parametrize("target", ["scenario_yaml", "campaign_yaml", "scenario_csv", "gpx", "nmea", "rtklib", "gnss_csv"])
@settings(max_examples=40, **_SETTINGS)
@given(data=st.data())
def test_alias_depth_huge_and_non_finite_numbers_raise_only_input_error(
    target: str, seeds: dict[str, Path], tmp_path: Path, data
) -> None:
    """YAML alias bombs, deep nesting and huge integers; nan/inf, a no-break space or a non-ASCII digit in a number."""
    _check(target, seeds, tmp_path, data.draw(mutations(True, FAMILY_KINDS)))


@pytest.mark.parametrize("target", BAG_TARGETS)
@settings(max_examples=12, **_SETTINGS)
@given(data=st.data())
def test_bag_readers_raise_only_input_error(target: str, seeds: dict[str, Path], tmp_path: Path, data) -> None:
    _check(target, seeds, tmp_path, data.draw(mutations(False)))


@pytest.mark.slow
@pytest.mark.parametrize("target", [*BAG_TARGETS, "rosbag2_yaml"])
@settings(max_examples=60, **_SETTINGS)  # the families in measure_escapes.py do the long runs
@given(data=st.data())
def test_bag_readers_raise_only_input_error_long(target: str, seeds: dict[str, Path], tmp_path: Path, data) -> None:
    _check(target, seeds, tmp_path, data.draw(mutations(TARGETS[target].text)))


@pytest.mark.parametrize("target", list(TARGETS))
def test_seeds_are_valid(target: str, seeds: dict[str, Path]) -> None:
    """The unmutated seed reads without error (else the fuzzing would only test rejections)."""
    TARGETS[target].read(seeds[target])
