"""The errors figures write their maths as maths: no literal carets or subscripts (issue 25, item 12)."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest


def test_every_label_with_a_sub_or_superscript_is_mathtext(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from matplotlib.figure import Figure

    from seatwin.sensors.depthbuffer.plots import write_error_plots

    texts: list[str] = []
    save = Figure.savefig

    def collect(fig: Figure, *args: Any, **kwargs: Any) -> None:
        for ax in fig.axes:
            texts.extend([ax.get_title(), ax.get_xlabel(), ax.get_ylabel()])
            legend = ax.get_legend()
            texts.extend(t.get_text() for t in (legend.get_texts() if legend else []))
        save(fig, *args, **kwargs)  # mathtext is parsed here: a bad expression raises

    monkeypatch.setattr(Figure, "savefig", collect)
    written = write_error_plots(tmp_path)
    assert len(written) == 4 and all(p.stat().st_size > 0 for p in written)
    assert any("$" in t for t in texts)
    for text in texts:
        outside = re.sub(r"\$[^$]*\$", "", text)
        assert "^" not in outside and not re.search(r"\b\w_\w", outside), text
