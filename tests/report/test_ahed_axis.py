"""The compare report's AHED bars use an axis that shows them (issue 25, item 12: fixed at 0–1, 0.01 was invisible)."""

from __future__ import annotations

import pytest

from seatwin.report.figures import ahed_axis_top


@pytest.mark.parametrize(
    "values,top",
    [([0.004, 0.012, None], 1.3 * 0.012), ([0.4, 0.9], 1.0), ([0.0001], 0.01), ([None], 1.0), ([0.2], 0.26)],
)
def test_axis_top_follows_the_largest_defined_value(values, top):
    assert ahed_axis_top(values) == pytest.approx(top)


def test_small_ahed_bars_fill_the_axis(monkeypatch):
    """The figure's tallest bar reaches three quarters of its axis."""
    import seatwin.report.figures as figures

    shown = {}
    monkeypatch.setattr(figures, "to_png", lambda fig: shown.setdefault("top", fig.axes[0].get_ylim()[1]) and b"")
    rows = [{"scenario": "s", "target": t, "tuning": "synthetic", "ahed": v} for t, v in (("A", 0.004), ("B", 0.012))]
    figures.ahed_figure(rows, "small AHED")
    assert 0.012 / shown["top"] > 0.75
