"""The whole loop on built-in data, end to end: the use-case behind ``seatwin demo``.

1. the built-in scenarios and their plots;
2. a built-in scenario simulated twice, in a window where both targets come within lidar range
   (ferry_crossing: 25–55 s, 25–70 m away): the exact ray-cast lidar with realistic degradations
   (range noise, range dissipation) as the stand-in for reality (seed ``seed``), and the thesis's
   depth-buffer lidar as the simulator (seed ``seed + 1``: no shared random draws, as with real data);
3. the same JIPDA tracker on both, with both thesis tunings;
4. the real-vs-synthetic comparison (AHED, COVDIFF) and the HTML report.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from seatwin.pipeline.compare import CompareResult


DEMO_OFFSET_S = 25.0
"""The demo's window starts this many seconds into the scenario: in ferry_crossing both targets are then
25–70 m from the ownship for 30 s (from the start they are 150 m away, where the lidar sees Finn too rarely)."""


@dataclass
class DemoResult:
    """Where the demo wrote everything."""

    figures: Path
    reality: Path
    simulator: Path
    comparison_json: Path
    report: Path
    comparison: CompareResult


DEMO_OUTPUTS = ("scenarios", "reality", "simulator", "report", "comparison.json")
"""What the demo writes into its folder."""


def run_demo(
    out: str | Path = "runs/demo",
    *,
    scenario: str = "ferry_crossing",
    offset: float = DEMO_OFFSET_S,
    duration: float = 30.0,
    seed: int = 1,
    step: Callable[[str], None] | None = None,
    progress: bool = False,
    overwrite: bool = False,
) -> DemoResult:
    """Run the demo into ``out`` (an earlier demo there is refused, or with ``overwrite`` replaced; other files
    stay): ``duration`` seconds from ``offset`` seconds after the scenario's start, the stand-in for reality with
    ``seed``, the simulator with ``seed + 1``; ``step(title)`` announces each step."""
    from seatwin.evaluation import CompareOptions
    from seatwin.outputs import check_output_folder, remove_outputs, write_text_atomic
    from seatwin.pipeline.compare import compare_runs
    from seatwin.pipeline.simulate import simulate_run
    from seatwin.scenario.builtin import builtin_names, builtin_scenario
    from seatwin.scenario.plot import plot_scenario

    out = Path(out)
    announce = step or (lambda _title: None)
    remove_outputs(check_output_folder(out, "out", DEMO_OUTPUTS, overwrite=overwrite))
    figures = out / "scenarios"
    figures.mkdir(parents=True, exist_ok=True)
    announce("plot the built-in scenarios")
    for name in builtin_names():
        plot_scenario(builtin_scenario(name), figures / f"{name}.png")
    announce("simulate the stand-in for reality (exact ray casting, range noise, range dissipation)")
    window = {"start_offset": offset, "duration": duration, "progress": progress, "sensors": ("lidar",)}
    simulate_run(scenario, out / "reality", seed=seed, range_noise=0.05, dissipation=True, **window)
    announce("simulate with the thesis's depth-buffer lidar (another seed)")
    simulate_run(scenario, out / "simulator", seed=seed + 1, lidar_mode="depthbuffer", **window)
    announce("track both with the thesis tunings and compare")
    result = compare_runs(
        [out / "reality"],
        [out / "simulator"],
        out / "reality",
        tunings=("synthetic", "real"),
        options=CompareOptions(),
        report_dir=out / "report",
    )
    json_path = out / "comparison.json"
    write_text_atomic(json_path, json.dumps(result.to_json(), indent=2) + "\n")
    assert result.report is not None
    return DemoResult(figures, out / "reality", out / "simulator", json_path, result.report, result)
