"""The out-of-process agent transport's cost per step: CPU of seatwin's process and of the agent's, and wall time.

The agent is docs/examples/agents/grpc_agent.py (ground truth in, a set-point out: the agent's own work is a few
hundred floating-point operations, so what is measured is the transport). Each run is made twice, ``--steps`` steps
and ``--short`` steps, and the difference is divided by the difference in steps, so the start-up (launching Python,
importing grpc, the server) is not counted; the same for the same policy in process (the test's ``InProcessTwin``).
``--one-call``: the example agent sends each command with ``Act`` (answered with the next observation: one call a
step). ``--agent reference-lidar``: seatwin's reference agent on simulated lidar instead, hosted in the agent process
by ``seatwin.api.agent_host`` (one call a step; every sweep crosses the wire as Gemini's ``LidarStreamingRequest``).
Prints JSON on its last line.

    PYTHONPATH=src .venv/bin/python benchmarks/agent_link.py --steps 2000
    PYTHONPATH=src .venv/bin/python benchmarks/agent_link.py --agent reference-lidar --steps 300
"""

from __future__ import annotations

import argparse
import json
import resource
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "api"))

from test_agent_link import EXAMPLE, HOST, InProcessTwin  # noqa: E402

from seatwin.agents import make_agent  # noqa: E402
from seatwin.api.agent_link import RemoteAgent  # noqa: E402
from seatwin.encounters import encounter_scenario, space  # noqa: E402
from seatwin.verification import run_closed_loop  # noqa: E402


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def measure(scenario: object, steps: int, mode: str, remote: bool, lidar: bool, one_call: bool) -> dict[str, float]:
    """Own CPU, the agent process's CPU (its whole life) and wall time of one run of ``steps`` steps."""
    duration = (steps - 1) * 0.1
    c0, k0, w0 = time.process_time(), _children_cpu(), time.perf_counter()
    if remote:
        example = [sys.executable, str(EXAMPLE), "{address}", "--mode", mode, *(["--one-call"] if one_call else [])]
        argv = [sys.executable, "-c", HOST, "{address}", "lidar"] if lidar else example
        with RemoteAgent("bench", ("lidar",) if lidar else ("truth",), command=argv) as agent:
            rec = run_closed_loop(scenario, agent, duration=duration)
    else:
        agent = make_agent("reference", sensors=("lidar",)) if lidar else InProcessTwin(mode)
        rec = run_closed_loop(scenario, agent, duration=duration)
    assert rec.time.size == steps, (rec.time.size, steps)
    return {"cpu_s": time.process_time() - c0, "agent_cpu_s": _children_cpu() - k0, "wall_s": time.perf_counter() - w0}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--short", type=int, default=20)
    ap.add_argument("--mode", default="velocity")
    ap.add_argument("--agent", choices=("example", "reference-lidar"), default="example")
    ap.add_argument("--one-call", action="store_true", help="the example agent sends its commands with Act")
    a = ap.parse_args()
    lidar = a.agent == "reference-lidar"
    sp = space("head_on", tcpa=(150.0, 150.0), run_out=60.0)
    scenario = encounter_scenario(sp.encounter([0.5] * sp.dimension), "bench", "none", 1)[0]
    out: dict[str, object] = {"steps": a.steps, "short": a.short, "agent": a.agent}
    out |= {"mode": None if lidar else a.mode, "one_call": a.one_call or lidar}
    for remote in (False, True):
        long, short = (measure(scenario, n, a.mode, remote, lidar, a.one_call) for n in (a.steps, a.short))
        n = a.steps - a.short
        per = {f"{k}_per_step_ms": 1000 * (long[k] - short[k]) / n for k in long}
        out["grpc" if remote else "in_process"] = {**per, "long": long, "short": short}
        print(("grpc" if remote else "in process"), {k: round(v, 4) for k, v in per.items()}, flush=True)
    g, p = out["grpc"], out["in_process"]
    assert isinstance(g, dict) and isinstance(p, dict)
    out["overhead_per_step_ms"] = {
        "seatwin_cpu": g["cpu_s_per_step_ms"] - p["cpu_s_per_step_ms"],
        "agent_cpu": g["agent_cpu_s_per_step_ms"],
        "wall": g["wall_s_per_step_ms"] - p["wall_s_per_step_ms"],
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
