"""Fixtures of the reader fuzz tests: valid seed files of every format, made once per session;
puts ``fuzz_helpers`` on ``sys.path`` (the suite runs with ``--import-mode=importlib``)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent
for extra in (HERE, HERE.parent / "groundtruth"):
    if str(extra) not in sys.path:
        sys.path.insert(0, str(extra))

from fuzz_helpers import make_seeds  # noqa: E402


@pytest.fixture(scope="session")
def seeds(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Reader name → a valid file it reads (see :func:`fuzz_helpers.make_seeds`)."""
    return make_seeds(tmp_path_factory.mktemp("fuzz-seeds"))
