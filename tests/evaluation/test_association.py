"""Track-to-truth association (thesis 5.1.4): closest within 10 m, the closest subscriber, switches, losses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.evaluation.association import NO_TRACK, associate, track_losses, track_switches
from seatwin.evaluation.evaluate import evaluate
from seatwin.evaluation.truth import TruthSet, TruthTrack


def test_closest_subscribed_track_is_the_target(truth, tracks_factory) -> None:
    # At t=2 A is at (2, 0), B at (0, 100).
    tr = tracks_factory([(2.0, 1, 2.0, 3.0), (2.0, 2, 2.0, 1.0), (2.0, 7, 4.0, 100.0), (2.0, 9, 50.0, 50.0)])
    a = associate(tr, truth)
    assert a.targets == ["A", "B"]
    assert a.track_id[:, 0].tolist() == [2, 7]
    assert a.distance[:, 0] == pytest.approx([1.0, 4.0])


def test_track_subscribes_to_its_closest_truth_only(tracks_factory) -> None:
    t = np.arange(3.0)
    truth = TruthSet({"A": TruthTrack("A", t, 0 * t, 0 * t), "C": TruthTrack("C", t, 0 * t, 0 * t + 8.0)})
    a = associate(tracks_factory([(1.0, 4, 0.0, 5.0)]), truth)  # 5 m from A, 3 m from C
    assert a.track_id[:, 0].tolist() == [NO_TRACK, 4]  # A has a track loss although a track is within 10 m


@pytest.mark.parametrize(("offset", "associated"), [(9.99, True), (10.0, True), (10.01, False)])
def test_gate_is_10_m(truth, tracks_factory, offset: float, associated: bool) -> None:
    a = associate(tracks_factory([(0.0, 1, 0.0, -offset)]), truth)
    assert bool(a.track_id[0, 0] == 1) is associated


def test_switches_losses_and_coverage(truth, tracks_factory) -> None:
    rows = [(t, 1 if t < 5 else 2, t + 0.5, 0.0) for t in range(11) if t != 3]
    tr = tracks_factory(rows, scan_times=list(range(11)))
    ev = evaluate(tr, truth)
    s = ev.summaries[0]
    assert s.target == "A"
    assert (s.n_instants, s.n_valid) == (11, 10)
    assert s.coverage == pytest.approx(10 / 11)
    assert s.track_switches == 1 and s.track_losses == 1 and s.track_ids == [1, 2]
    assert (s.first_time, s.last_time) == (0.0, 10.0)
    b = ev.summaries[1]
    assert b.n_valid == 0 and b.coverage == 0.0 and b.anees is None and b.anees_verdict == "undefined"
    assert track_switches(np.array([1, -1, 1, 2, -1, 2, 3])) == 2
    assert track_losses(np.array([-1, 1, -1, -1, 1, -1]), np.array([True] * 5 + [False])) == 1


def test_metrics_at_valid_instants(truth, tracks_factory) -> None:
    # Track 1 m ahead of A with zero velocity (truth v_north = 1): error [1, −1, 0, 0], P = I.
    tr = tracks_factory([(t, 1, t + 1.0, 0.0) for t in range(11)])
    ev = evaluate(tr, truth)
    series = ev.series["A"]
    assert np.allclose(series.nees, 2.0) and np.allclose(series.rmse, math.sqrt(2.0))
    assert np.allclose(series.rmse_position, 1.0)
    s = ev.summaries[0]
    assert s.anees == pytest.approx(2.0) and s.rmse == pytest.approx(math.sqrt(2.0))
    assert s.rmse_position == pytest.approx(1.0) and s.rmse_velocity == pytest.approx(1.0)
    assert s.anees_verdict == "underconfident"
    assert s.anees_upper == pytest.approx(ev.summaries[0].anees_upper)


def test_unconfirmed_tracks_are_ignored_by_default(truth, tracks_factory) -> None:
    tr = tracks_factory([(1.0, 1, 1.0, 0.0)], confirmed=False)
    assert evaluate(tr, truth).summaries[0].n_valid == 0
    assert evaluate(tr, truth, confirmed_only=False).summaries[0].n_valid == 1


def test_instants_outside_truth_span_are_not_losses(truth, tracks_factory) -> None:
    tr = tracks_factory([(5.0, 1, 5.0, 0.0)], scan_times=[-3.0, 5.0, 20.0])
    s = evaluate(tr, truth).summaries[0]
    assert s.n_instants == 1 and s.coverage == 1.0
