"""The structure-aware mutation families (``families.py``, issue #20) against the bag readers: a few
mutants per family and target here (``measure_escapes.py --families`` runs 300+ each, in a worker
under memory and time limits). Every mutant is read or refused with one InputError line."""

from __future__ import annotations

import sqlite3
import struct
from pathlib import Path

import pytest
from families import FAMILIES, family_mutant, without_crcs
from fuzz_helpers import escape, materialize

BAG_CASES = [(f, t) for f, fam in FAMILIES.items() if f != "yaml" for t in fam.targets]


@pytest.mark.parametrize(("family", "target"), BAG_CASES)
def test_bag_families_raise_only_input_error(family: str, target: str, seeds: dict[str, Path], tmp_path: Path) -> None:
    seed = seeds[target]
    data = seed.read_bytes()
    changed = 0
    for i in range(6):
        mutant = family_mutant(family, target, i, data)
        changed += mutant != data
        exc = escape(target, materialize(seed, mutant, tmp_path / "mutant"))
        assert exc is None, f"{family}/{target} mutant {i}: {type(exc).__name__}: {exc}"
    assert changed >= 4  # the family does mutate


def test_families_are_deterministic(seeds: dict[str, Path]) -> None:
    data = seeds["ros1"].read_bytes()
    assert family_mutant("length_forging", "ros1", 7, data) == family_mutant("length_forging", "ros1", 7, data)
    assert family_mutant("length_forging", "ros1", 7, data) != family_mutant("length_forging", "ros1", 8, data)


def test_sql_family_changes_types_or_rows(seeds: dict[str, Path], tmp_path: Path) -> None:
    data = seeds["sqlite3"].read_bytes()
    kinds = set()
    for i in range(30):
        db = tmp_path / f"{i}.db3"
        db.write_bytes(family_mutant("sql_types", "sqlite3", i, data))
        con = sqlite3.connect(db)
        types = {r for r in con.execute("SELECT typeof(timestamp), typeof(topic_id) FROM messages")}
        n = con.execute("SELECT count(*) FROM messages").fetchone()[0]
        con.close()
        kinds.add((frozenset(types), n))
    assert len(kinds) > 3


def test_mcap_seed_without_crcs(seeds: dict[str, Path]) -> None:
    data = seeds["mcap"].read_bytes()
    bare = without_crcs(data)
    assert len(bare) == len(data) and bare != data
    assert without_crcs(bare) == bare


def test_yaml_family_makes_aliases_depth_and_digits(seeds: dict[str, Path]) -> None:
    """The YAML family exists and makes each of its kinds (its escapes are measured, see docs/validation.md)."""
    text = [family_mutant("yaml", "campaign_yaml", i, seeds["campaign_yaml"].read_bytes()).decode() for i in range(60)]
    assert any("*l5" in t or "*l8" in t for t in text)  # an alias bomb
    assert any("[" * 100 in t for t in text) and any("{a: " * 100 in t for t in text)
    assert any("9" * 4300 in t for t in text)
    assert any("*nowhere" in t for t in text)


def test_bomb_family_forges_chunk_sizes(seeds: dict[str, Path]) -> None:
    data = seeds["mcap"].read_bytes()
    declared = set()
    for i in range(20):
        m = family_mutant("bomb", "mcap", i, data)
        pos = 8
        while pos + 9 <= len(m):
            op, length = struct.unpack_from("<BQ", m, pos)
            if op == 0x06:
                declared.add(struct.unpack_from("<Q", m, pos + 9 + 16)[0])
                break
            pos += 9 + length
    assert len(declared) > 3 and max(declared) >= 2**30
