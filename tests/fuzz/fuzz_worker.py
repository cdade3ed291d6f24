"""A reader process for ``measure_escapes.py --families``: reads one mutant per request, in bounded memory.

Requests on stdin, one JSON line each: ``{"target": name, "path": file}``; one JSON line back:
``{"escape": "<type> at <file>:<line>" or null, "detail": text, "peak_mib": the mutant's own peak
resident memory, "seconds": its time}``. The peak is the kernel's high-water mark, reset before
each mutant (``/proc/self/clear_refs``). The parent sets the address-space limit and kills the
process when a mutant runs past its time.
"""

from __future__ import annotations

import contextlib
import json
import sys
import time
import traceback
from pathlib import Path

sys.path[:0] = [str(Path(__file__).parent), str(Path(__file__).parents[1] / "groundtruth")]

from fuzz_helpers import escape  # noqa: E402


def _hwm_kib() -> int:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1])
    return 0


def _reset_hwm() -> None:
    with contextlib.suppress(OSError):
        Path("/proc/self/clear_refs").write_text("5")


def main() -> None:
    for line in sys.stdin:
        req = json.loads(line)
        _reset_hwm()
        t0 = time.perf_counter()
        exc = escape(req["target"], Path(req["path"]), refused := [])
        seconds = time.perf_counter() - t0
        key = detail = None
        if exc is not None:
            frame = traceback.extract_tb(exc.__traceback__)[-1] if exc.__traceback__ else None
            where = f"{Path(frame.filename).name}:{frame.lineno}" if frame else "?"
            key = f"{type(exc).__name__} at {where}"
            detail = f"{type(exc).__name__}: {exc}"[:500]
        peak = round(_hwm_kib() / 1024, 1)
        out = {"escape": key, "refused": bool(refused), "detail": detail, "peak_mib": peak, "seconds": round(seconds, 3)}
        sys.stdout.write(json.dumps(out) + "\n")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
