"""Each use-case as one typed library call: what the CLI, the sweep, the fidelity method, benchmarks and tests call.

* :func:`simulate_run` — a scenario → a recording (:mod:`.simulate`);
* :func:`track_recording`, :func:`track_scans` — a recording or scans → tracks (:mod:`.track`);
* :func:`evaluate_run` — tracks vs ground truth (:mod:`.evaluate`);
* :func:`compare_runs` — a real vs a synthetic dataset (:mod:`.compare`);
* :func:`run_demo` — the whole loop on built-in data (:mod:`.demo`).

Imports are lazy (``seatwin.pipeline.track`` loads no numpy until called), so the CLI starts fast.
"""

from __future__ import annotations

from typing import Any

_EXPORTS = {
    "simulate_run": "seatwin.pipeline.simulate",
    "TrackOptions": "seatwin.pipeline.track",
    "TrackingResult": "seatwin.pipeline.track",
    "track_recording": "seatwin.pipeline.track",
    "track_scans": "seatwin.pipeline.track",
    "evaluate_run": "seatwin.pipeline.evaluate",
    "CompareResult": "seatwin.pipeline.compare",
    "compare_runs": "seatwin.pipeline.compare",
    "load_run": "seatwin.pipeline.compare",
    "DemoResult": "seatwin.pipeline.demo",
    "run_demo": "seatwin.pipeline.demo",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        import importlib

        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'seatwin.pipeline' has no attribute {name!r}")
