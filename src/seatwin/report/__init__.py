"""The comparison report: a self-contained HTML page with the thesis's figures (5.3–5.5, 5.7, 5.10)."""

from seatwin.report.html import Clouds, ScenarioResult, render_report, write_comparison_report, write_report

__all__ = ["Clouds", "ScenarioResult", "render_report", "write_comparison_report", "write_report"]
