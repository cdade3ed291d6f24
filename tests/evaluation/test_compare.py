"""Real-versus-synthetic comparison: time matching, HED per instant, AHED (5.34) and its conventions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.evaluation.compare import CompareOptions, compare, comparison_table, match_times

H_STD = math.sqrt(1 - math.exp(-1 / 8))  # NEES(μ₁, μ₂, P̄) = 1 with P₁ = P₂ = I, |μ₁ − μ₂| = 1
H_PRINTED = math.sqrt(1 - math.exp(-1 / 16))


def test_match_times_mutual_nearest_within_tolerance() -> None:
    ia, ib = match_times(np.array([0.0, 1.0, 2.0]), np.array([0.01, 1.5, 2.02, 3.0]), 0.05)
    assert ia.tolist() == [0, 1, -1, 2, -1]
    assert ib.tolist() == [0, -1, 1, 2, 3]
    ia, ib = match_times(np.array([0.0, 1.0]), np.array([]), 0.05)
    assert ia.tolist() == [0, 1] and ib.tolist() == [-1, -1]


def _runs(tracks_factory, shift: float = 0.0):
    scans = list(range(11))
    real = tracks_factory([(t, 1, t + 0.5, 0.0) for t in range(0, 10)], scan_times=scans)
    synt = tracks_factory([(t + shift, 5, t - 0.5, 0.0) for t in range(2, 10)], scan_times=[s + shift for s in scans])
    return real, synt


def test_ahed_over_common_instants_and_one_sided_counts(truth, tracks_factory) -> None:
    real, synt = _runs(tracks_factory)
    c = compare(real, synt, truth, tuning="real")
    a, b = c.targets
    assert (a.target, a.tuning) == ("A", "real")
    assert (a.n_instants, a.n_common, a.n_only_real, a.n_only_synthetic, a.n_both_missing) == (11, 8, 2, 0, 1)
    assert a.ahed == pytest.approx(H_STD) and a.ahed_standard == pytest.approx(H_STD)
    assert a.ahed_printed == pytest.approx(H_PRINTED)
    assert a.fraction_only_one == pytest.approx(2 / 10)
    assert a.mean_covdiff == pytest.approx(0.0, abs=1e-7)
    assert a.anees_real == pytest.approx(0.25 + 1) and a.anees_synthetic == pytest.approx(0.25 + 1)
    assert a.nees_difference_rms == pytest.approx(0.0) and a.rmse_difference_rms == pytest.approx(0.0)
    # B: neither dataset ever had a track → AHED undefined by default (never "perfect agreement") …
    assert b.ahed is None and b.n_common == 0 and b.n_both_missing == 11 and b.fraction_only_one is None
    # … and 0 ("full agreement") only under the thesis's scenario-7 convention.
    never = compare(real, synt, truth, options=CompareOptions(both_missing="never"))
    assert never.targets[1].ahed == 0.0
    assert comparison_table([c])["ahed_mean"] == pytest.approx(H_STD)  # B left out of the mean, not averaged as 0
    series = c.series["A"]
    assert np.isnan(series.hed[:2]).all() and np.allclose(series.hed[2:10], H_STD) and np.isnan(series.hed[10])


def test_both_missing_conventions(truth, tracks_factory) -> None:
    real, synt = _runs(tracks_factory)
    zero = compare(real, synt, truth, options=CompareOptions(both_missing="zero"))
    assert zero.targets[0].ahed == pytest.approx(8 * H_STD / 9)
    assert zero.targets[1].ahed == 0.0
    skip = compare(real, synt, truth, options=CompareOptions(both_missing="skip"))
    assert skip.targets[0].ahed == pytest.approx(H_STD)
    assert skip.targets[1].ahed is None


def test_only_one_dataset_tracks_gives_undefined_ahed(truth, tracks_factory) -> None:
    real, _ = _runs(tracks_factory)
    empty = tracks_factory([], scan_times=list(range(11)))
    a = compare(real, empty, truth).targets[0]
    assert a.ahed is None and a.n_only_real == 10 and a.fraction_only_one == 1.0


def test_printed_form_option(truth, tracks_factory) -> None:
    real, synt = _runs(tracks_factory)
    a = compare(real, synt, truth, options=CompareOptions(form="printed")).targets[0]
    assert a.hellinger_form == "printed" and a.ahed == pytest.approx(H_PRINTED)
    assert a.ahed_standard == pytest.approx(H_STD)


def test_time_tolerance(truth, tracks_factory) -> None:
    real, synt = _runs(tracks_factory, shift=0.02)
    assert compare(real, synt, truth).targets[0].n_common == 8
    a = compare(real, synt, truth, options=CompareOptions(time_tolerance=0.01)).targets[0]
    assert a.n_common == 0 and a.n_only_real == 10 and a.n_only_synthetic == 8 and a.ahed is None


def test_table_shape(truth, tracks_factory) -> None:
    real, synt = _runs(tracks_factory)
    table = comparison_table([compare(real, synt, truth, "synthetic"), compare(real, real, truth, "real")])
    assert [(t["target"], t["tuning"]) for t in table["targets"]] == [
        ("A", "synthetic"),
        ("B", "synthetic"),
        ("A", "real"),
        ("B", "real"),
    ]
    assert table["ahed_mean_by_tuning"]["real"] == pytest.approx(0.0, abs=1e-7)
    assert table["ahed_mean"] == pytest.approx(H_STD / 2)  # A in both tunings; B (never tracked) undefined
    for key in ("ahed", "n_common", "n_only_real", "n_only_synthetic", "mean_covdiff"):
        assert key in table["targets"][0]
    assert table["conventions"]["both_missing"] == "skip"
    assert table["ahed_n"] == 2 and table["ahed_n_by_tuning"] == {"synthetic": 1, "real": 1}


def test_bad_options() -> None:
    with pytest.raises(ValueError):
        CompareOptions(form="other")  # type: ignore[arg-type]
    with pytest.raises(ValueError):
        CompareOptions(both_missing="maybe")  # type: ignore[arg-type]


def test_target_outside_every_instant_is_undefined(tracks_factory) -> None:
    from seatwin.evaluation.truth import TruthSet, TruthTrack

    truth = TruthSet({"late": TruthTrack("late", [100.0, 110.0], [0.0, 0.0], [0.0, 0.0])})
    empty = tracks_factory([], scan_times=list(range(11)))
    line = compare(empty, empty, truth).targets[0]
    assert line.n_instants == 0 and line.ahed is None
