"""Ground truth of a recording: its own topics, else the scenario file beside the bag."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.evaluation.truth import recording_truth, truth_from_scenario_file
from seatwin.recording import open_bag
from seatwin.recording.messages import typestore
from seatwin.scenario import Trajectory
from seatwin.scenario.gemini_csv import write_gemini_csv

T0 = 1_600_000_000.25


def _foreign_bag(path: Path) -> None:
    from rosbags.rosbag2 import StoragePlugin, Writer

    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        w.add_connection("/x", "std_msgs/msg/String", typestore=typestore("mcap"))


def test_truth_from_scenario_beside_bag(tmp_path: Path) -> None:
    """A foreign bag without truth topics: truth comes from the Gemini CSV beside it (last vessel = ownship)."""
    _foreign_bag(tmp_path / "real")
    t = T0 + np.arange(5) * 0.1
    write_gemini_csv(
        tmp_path / "scenario.csv",
        [Trajectory(t, t - T0, 2 * (t - T0), np.full(5, 0.3)), Trajectory(t, -(t - T0), np.zeros(5), np.zeros(5))],
    )
    with open_bag(tmp_path / "real") as rec:
        truth = recording_truth(rec)
    assert set(truth) == {"V1", "V2"} and truth["V2"].ownship and not truth["V1"].ownship
    np.testing.assert_allclose(truth["V1"].v_east, 2.0, atol=1e-5)
    again = truth_from_scenario_file(tmp_path / "scenario.csv")
    np.testing.assert_array_equal(again["V1"].north, truth["V1"].north)


def test_no_truth_at_all(tmp_path: Path) -> None:
    _foreign_bag(tmp_path / "real")
    with open_bag(tmp_path / "real") as rec, pytest.raises(InputError, match="no ground truth"):
        recording_truth(rec)
    with pytest.raises(InputError, match="scenario file not found"):
        truth_from_scenario_file(tmp_path / "missing.csv")
