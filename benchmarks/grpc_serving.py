"""Gemini gRPC lock-step serving: real-time factor, CPU time of both processes, median ``DoStep`` latency.

Parts (``--parts``, default all), each over ``--steps`` steps (default 2000) of a long scenario —
``ferry_crossing`` (75 s) played forwards and backwards (the time reflected, so every pose is one of
the scenario's and the motion is continuous) — loopback only, the client in another process (as an
OSP/Gemini client is):

* ``transport``: the steps to a ``DoStep`` that does nothing (one worker, ``serve``'s options): the
  CPU time of both processes per ``DoStep`` (target ≤ 0.6 ms) and the median round trip.
* ``served``: ``serve`` with lidar + radar (the default harbour, ray casting), at 0.1 s and 0.01 s
  steps: real-time factor = simulated seconds / wall time of the stepping (targets ≥ 10× at 0.1 s,
  ≥ 5× at 0.01 s), CPU seconds of the server and the client, the median ``DoStep`` latency, and
  ``cpu_realtime_factor`` = simulated seconds / both processes' CPU seconds (the two alternate, so
  this is what the wall time comes to on an unloaded machine, less the idle wake-ups).
* ``cameras``: the same with the camera rig too, at 0.01 s steps (target ≥ 1×).
* ``direct``: :class:`~seatwin.api.lockstep.LockstepSimulation` stepped in this process (no gRPC) vs
  ``simulate`` of the same window, samples and settings (lidar + radar), CPU time (target ≤ 20 % over
  ``simulate``), at both step sizes.
* ``growth``: the CPU cost of a step (ground truth of 3 vessels, no sensor: the lock-step's own
  bookkeeping), the median of the 500 steps before 200 s, 2000 s and 3600 s of one 0.1 s-step run
  (process and stepping-thread CPU), and that hour-old run's steps interleaved with a new run's at 200 s
  (and, as a control of the machine's noise, two new runs at 200 s interleaved).

Each part prints a JSON line; the last line is all of them. ``python benchmarks/grpc_serving.py [--steps N]
[--parts served,transport]``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent import futures
from pathlib import Path

SCENARIO = "ferry_crossing"
SENSORS = ("lidar", "radar")
SAME = {"seed": 0, "harbour": "default", "lidar_mode": "raycast", "lidar_preset": "vlp16", "fmt": "mcap"}
SAME["ground_truth_rate_hz"] = 10.0


def _poses(n_steps: int, step_s: float) -> tuple[float, list[tuple[float, list[tuple[float, float, float]]]]]:
    """``n_steps`` steps of ``step_s``: (seconds since start, poses in ``DEFAULT_VESSELS`` order), ping-pong replay."""
    import numpy as np

    from seatwin.api.lockstep import DEFAULT_VESSELS
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario(SCENARIO)
    span = sc.end - sc.start - 1.0
    out = []
    for k in range(n_steps):
        rel = round(k * step_s, 6)
        phase = rel % (2 * span)
        t = sc.start + (phase if phase <= span else 2 * span - phase)
        poses = []
        for name in DEFAULT_VESSELS:
            s = sc.state_at(name, t)
            poses.append((float(s.north), float(s.east), float(np.rad2deg(s.heading)) % 360.0))
        out.append((rel, poses))
    return sc.start, out


def _scenario_of(start: float, steps: list) -> object:
    """The steps as a scenario (``simulate``'s input for the same samples)."""
    import numpy as np

    from seatwin.api.lockstep import DEFAULT_VESSELS
    from seatwin.scenario import Trajectory
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario(SCENARIO)
    t = start + np.array([rel for rel, _ in steps])
    vessels = []
    by_name = {v.name: v for v in sc.vessels}
    for i, name in enumerate(DEFAULT_VESSELS):
        p = np.array([poses[i] for _, poses in steps])
        traj = Trajectory(t, p[:, 0], p[:, 1], np.unwrap(np.deg2rad(p[:, 2])), source="benchmark")
        v = by_name[name]
        vessels.append(type(v)(v.name, v.role, traj, v.model, v.dimensions))
    return type(sc)(sc.name, vessels, origin=sc.origin, seed=0, environment=dict(sc.environment), source="benchmark")


CLIENT = """
import json, statistics, sys, time
from seatwin.api.client import SimulationClient
address, path, step_s = sys.argv[1], sys.argv[2], float(sys.argv[3])
start, steps = json.load(open(path))
lat = []
with SimulationClient(address) as c:
    c.set_start_time(repr(start))
    c.step(steps[0][1], steps[0][0], step_s)  # connection set up
    cpu0, t0 = time.process_time(), time.perf_counter()
    for rel, poses in steps[1:]:
        s = time.perf_counter()
        c.step(poses, rel, step_s)
        lat.append(time.perf_counter() - s)
    wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
print(json.dumps({"wall_s": wall, "client_cpu_s": cpu, "median_latency_ms": 1e3 * statistics.median(lat)}))
"""


def _drive(address: str, start: float, steps: list, step_s: float, tmp: Path) -> dict:
    """The client in its own process; this process's CPU time over the same interval (the server's)."""
    path = tmp / "steps.json"
    path.write_text(json.dumps([start, steps]))
    cpu0, t0 = time.process_time(), time.perf_counter()
    out = subprocess.run(
        [sys.executable, "-c", CLIENT, address, str(path), str(step_s)], check=True, capture_output=True, text=True
    )
    res = json.loads(out.stdout.strip().splitlines()[-1])
    res["server_cpu_s"] = time.process_time() - cpu0  # includes the few ms before the client's first step
    res["outer_wall_s"] = time.perf_counter() - t0
    return res


def transport(n_steps: int, tmp: Path) -> dict:
    import grpc

    from seatwin.api.proto import simulation_pb2, simulation_pb2_grpc
    from seatwin.api.server import SERVE_MAX_MESSAGE_BYTES, bind, server_options

    class Noop(simulation_pb2_grpc.SimulationServicer):
        def DoStep(self, request: object, context: object) -> object:  # noqa: N802
            return simulation_pb2.StepResponse(success=True)

        def SetStartTime(self, request: object, context: object) -> object:  # noqa: N802
            return simulation_pb2.SetStartTimeResponse(success=True)

    start, steps = _poses(n_steps + 1, 0.1)
    server = grpc.server(futures.ThreadPoolExecutor(max_workers=1), options=server_options(SERVE_MAX_MESSAGE_BYTES))
    simulation_pb2_grpc.add_SimulationServicer_to_server(Noop(), server)
    port = bind(server, "127.0.0.1", 0)
    server.start()
    try:
        r = _drive(f"127.0.0.1:{port}", start, steps, 0.1, tmp)
    finally:
        server.stop(None)
    cpu_ms = 1e3 * (r["client_cpu_s"] + r["server_cpu_s"]) / n_steps
    return {
        "part": "transport",
        "steps": n_steps,
        "cpu_ms_per_dostep": round(cpu_ms, 3),
        "client_cpu_ms_per_dostep": round(1e3 * r["client_cpu_s"] / n_steps, 3),
        "server_cpu_ms_per_dostep": round(1e3 * r["server_cpu_s"] / n_steps, 3),
        "median_latency_ms": round(r["median_latency_ms"], 3),
        "target_met": cpu_ms <= 0.6,
    }


def served(n_steps: int, step_s: float, sensors: tuple[str, ...], tmp: Path, target: float) -> dict:
    from seatwin.api.server import serve

    start, steps = _poses(n_steps + 1, step_s)
    run = tmp / f"served-{'-'.join(sensors)}-{step_s:g}"
    h = serve(run, port=0, sensors=sensors, **SAME)
    try:
        r = _drive(h.address, start, steps, step_s, tmp)
    finally:
        res = h.stop()
    simulated = n_steps * step_s
    rtf = simulated / r["wall_s"]
    return {
        "part": "served",
        "sensors": list(sensors),
        "step_s": step_s,
        "steps": n_steps,
        "simulated_s": round(simulated, 3),
        "wall_s": round(r["wall_s"], 3),
        "realtime_factor": round(rtf, 2),
        # Lock-step alternates: the two processes' CPU time, back to back, bounds the wall time on a quiet machine.
        "cpu_realtime_factor": round(simulated / (r["server_cpu_s"] + r["client_cpu_s"]), 2),
        "server_cpu_s": round(r["server_cpu_s"], 3),
        "client_cpu_s": round(r["client_cpu_s"], 3),
        "median_latency_ms": round(r["median_latency_ms"], 3),
        "frames": res.frames,
        "target": target,
        "target_met": rtf >= target,
    }


def direct(n_steps: int, step_s: float, tmp: Path, repeats: int = 1) -> dict:
    """``repeats`` interleaved pairs (the order alternating, after one warm-up of each): the median of the
    per-pair CPU ratios, so a shared machine's load drifting during the part cancels out."""
    from seatwin.api.lockstep import LockstepSettings, LockstepSimulation
    from seatwin.pipeline.simulate import simulate_run

    start, steps = _poses(n_steps + 1, step_s)
    scenario = _scenario_of(start, steps)
    duration = n_steps * step_s
    kw = {"start": start, "progress": False, "sensors": SENSORS, **SAME}
    runs = iter(range(10**6))

    def simulate_cpu() -> tuple[float, dict]:
        cpu0 = time.process_time()
        ref = simulate_run(scenario, tmp / f"ref-{step_s:g}-{next(runs)}", duration=duration, **kw)
        return time.process_time() - cpu0, ref.frames

    def lockstep_cpu(n: int | None = None) -> tuple[float, dict]:
        cpu0 = time.process_time()
        sim = LockstepSimulation(tmp / f"direct-{step_s:g}-{next(runs)}", LockstepSettings(sensors=SENSORS, **SAME))
        sim.set_start_time(repr(start))
        for rel, poses in steps[:n]:
            sim.step(poses, rel, step_s)
        res = sim.close()
        return time.process_time() - cpu0, res.frames

    simulate_run(scenario, tmp / f"warm-{step_s:g}", duration=min(1.0, duration), **kw)
    lockstep_cpu(min(len(steps), 20))
    pairs = []
    for r in range(repeats):
        if r % 2:
            lock_cpu, lock_frames = lockstep_cpu()
            sim_cpu, ref_frames = simulate_cpu()
        else:
            sim_cpu, ref_frames = simulate_cpu()
            lock_cpu, lock_frames = lockstep_cpu()
        pairs.append((sim_cpu, lock_cpu, lock_frames == ref_frames))
    over = statistics.median(lock / sim - 1.0 for sim, lock, _ in pairs)
    return {
        "part": "direct",
        "step_s": step_s,
        "steps": n_steps,
        "repeats": repeats,
        "simulate_cpu_s": [round(sim, 3) for sim, _, _ in pairs],
        "lockstep_cpu_s": [round(lock, 3) for _, lock, _ in pairs],
        "cpu_overhead": round(over, 3),
        "cpu_overhead_each": [round(lock / sim - 1.0, 3) for sim, lock, _ in pairs],
        "frames_equal": all(eq for _, _, eq in pairs),
        "frames": lock_frames,
        "target_met": over <= 0.20,
    }


def growth(tmp: Path) -> dict:
    """One 0.1 s-step run to 3600 s: the median CPU of the 500 steps before each mark (the process's, and the
    stepping thread's alone, which leaves out any other thread of the process); then, to take the machine's
    drift out, 500 steps of that hour-old run interleaved with 500 of a new run at 200 s (median ratio)."""
    from seatwin.api.lockstep import LockstepSettings, LockstepSimulation

    marks = (200.0, 2000.0, 3600.0)
    n = int(marks[-1] / 0.1) + 1
    start, steps = _poses(n + 500, 0.1)

    def new_run(name: str) -> LockstepSimulation:
        sim = LockstepSimulation(tmp / name, LockstepSettings(sensors=(), **SAME))
        sim.set_start_time(repr(start))
        return sim

    sim = new_run("growth")
    stamps, threads = [], []
    for k in range(n):
        rel = steps[k][0]
        c0, h0 = time.process_time(), time.thread_time()
        sim.step(steps[k][1], rel, 0.1)
        stamps.append(time.process_time() - c0)
        threads.append(time.thread_time() - h0)
    out: dict = {"part": "growth", "step_s": 0.1}
    for m in marks:
        k = int(round(m / 0.1))
        out[f"us_per_step_at_{m:g}s"] = round(1e6 * statistics.median(stamps[k - 500 : k]), 1)
        out[f"thread_us_per_step_at_{m:g}s"] = round(1e6 * statistics.median(threads[k - 500 : k]), 1)
    out["ratio_3600_vs_200"] = round(out["us_per_step_at_3600s"] / out["us_per_step_at_200s"], 3)
    young = new_run("growth-young")
    k0 = int(round(marks[0] / 0.1)) - 500
    for k in range(k0):
        young.step(steps[k][1], steps[k][0], 0.1)

    def interleaved(a: LockstepSimulation, ka: int, b: LockstepSimulation, kb: int) -> tuple[float, float]:
        """500 steps of each, alternately (the order alternating too): median stepping-thread CPU of each."""
        us: tuple[list[float], list[float]] = ([], [])
        for j in range(500):
            pair = ((a, ka + j, us[0]), (b, kb + j, us[1]))
            for run, k, into in pair if j % 2 else pair[::-1]:
                h0 = time.thread_time()
                run.step(steps[k][1], steps[k][0], 0.1)
                into.append(time.thread_time() - h0)
        return statistics.median(us[0]), statistics.median(us[1])

    old_us, young_us = interleaved(sim, n, young, k0)
    out["interleaved_us_at_3600s_vs_200s"] = [round(1e6 * x, 1) for x in (old_us, young_us)]
    out["interleaved_ratio_3600_vs_200"] = round(old_us / young_us, 3)
    # Control: two new runs at 200 s, interleaved the same way — the ratio the machine's noise alone gives.
    twin = new_run("growth-twin")
    for k in range(k0 + 500):
        twin.step(steps[k][1], steps[k][0], 0.1)
    a_us, b_us = interleaved(young, k0 + 500, twin, k0 + 500)
    out["control_ratio_200_vs_200"] = round(a_us / b_us, 3)
    for run in (sim, young, twin):
        run.close()
    out |= scheduling(marks)
    return out


def scheduling(marks: tuple[float, ...]) -> dict:
    """The frame scheduling alone, per step (lidar 10 Hz, radar 0.4 Hz, ground truth 10 Hz; no frame due): all the
    frame times since the start (``frame_times``, what a step cost before) vs only those not run yet
    (``frame_times_from``). Median of 300 repetitions each: pure functions, so the machine's load matters less."""
    from seatwin.sim import timing

    t0 = 1.6e9
    rates = ((10.0, 0.0), (0.4, 0.0), (10.0, 0.0))
    out = {}
    for m in marks:
        t1 = t0 + m + 0.05
        firsts = [len(timing.periodic_times(t0, t1, r, p)) for r, p in rates]
        for name, fn in (
            ("all", lambda t1=t1: [timing.periodic_times(t0, t1, r, p) for r, p in rates]),
            ("from", lambda t1=t1, ks=firsts: [timing.periodic_times_from(t0, t1, r, p, k) for (r, p), k in zip(rates, ks)]),
        ):
            if name == "from" and not hasattr(timing, "periodic_times_from"):
                continue
            reps = []
            for _ in range(300):
                c0 = time.perf_counter()
                fn()
                reps.append(time.perf_counter() - c0)
            out[f"schedule_{name}_us_at_{m:g}s"] = round(1e6 * statistics.median(reps), 1)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--parts", default="transport,served,cameras,direct,growth")
    ap.add_argument("--repeats", type=int, default=3, help="interleaved simulate/lock-step pairs of the direct part")
    ap.add_argument("--direct-steps-s", default="0.1,0.01", help="step sizes of the direct part [s]")
    args = ap.parse_args()
    parts = set(args.parts.split(","))
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)

        def emit(r: dict) -> None:
            print(json.dumps(r), flush=True)
            results.append(r)

        if "transport" in parts:
            emit(transport(args.steps, tmp))
        if "served" in parts:
            emit(served(args.steps, 0.1, SENSORS, tmp, 10.0))
            emit(served(args.steps, 0.01, SENSORS, tmp, 5.0))
        if "cameras" in parts:
            emit(served(args.steps, 0.01, (*SENSORS, "camera"), tmp, 1.0))
        if "direct" in parts:
            for step_s in args.direct_steps_s.split(","):
                emit(direct(args.steps, float(step_s), tmp, args.repeats))
        if "growth" in parts:
            emit(growth(tmp))
    print(json.dumps(results))


if __name__ == "__main__":
    main()
