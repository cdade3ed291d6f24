"""Fixtures of the recording tests; puts ``recording_helpers`` (shared test data) on ``sys.path``
(the suite runs with ``--import-mode=importlib``, which does not add test folders itself)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

if str(Path(__file__).parent) not in sys.path:
    sys.path.insert(0, str(Path(__file__).parent))


@pytest.fixture(params=["mcap", "sqlite3", "ros1"])
def fmt(request: pytest.FixtureRequest) -> str:
    return request.param
