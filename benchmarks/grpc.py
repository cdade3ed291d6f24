"""Gemini gRPC lock-step speed, loopback only: ``DoStep`` round trips per second and the cost of lock-step.

1. ``dostep_per_s``: a client built from the .proto files sends ``ferry_crossing``'s poses (700 steps, three
   vessels, 10 Hz) to ``seatwin serve`` with no ownship sensor (ground truth only, recorded to MCAP);
   target ≥ 1000/s. Baseline in the same process: the same requests to a gRPC server whose
   ``DoStep`` does nothing (``noop_per_s``: what gRPC itself costs).
2. ``lockstep_overhead``: the lidar on (VLP-16, ray casting), ``duration`` simulated seconds driven
   step by step (10 Hz) through ``serve`` by a client in another process (as an OSP/Gemini client
   is; wall = serve's set-up + the client's stepping loop + finishing the bag) vs ``seatwin simulate``
   (:func:`seatwin.pipeline.simulate_run`) of the same window in one call — apples to apples: the same
   sensors (ground truth at 10 Hz + the lidar), seed, harbour, range model and bag format (MCAP), and
   the same frames (``frames_equal``); overhead = wall(serve) / wall(simulate) − 1, target ≤ 0.20.
   Its parts: ``lockstep_direct_overhead`` — :class:`~seatwin.api.lockstep.LockstepSimulation` stepped
   in this process without gRPC (the server's own cost), and ``transport_share`` — the steps' round
   trips to a do-nothing ``DoStep`` server from another process (``noop_xproc_per_s``), as a share of
   ``simulate``'s wall. ``lockstep_inprocess_overhead``: ``serve`` with the client in this process
   (client and server then share one interpreter lock).

Each figure is the best of 3 runs (interleaved). Bounded loops; prints JSON on the last line.
``python benchmarks/grpc.py [steps] [duration]``.
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
from concurrent import futures
from pathlib import Path

# This file is named grpc.py: keep its folder off the import path so that ``import grpc`` is the library.
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]


REPEATS = 3


def _requests(n_steps: int, offset: float = 2.0) -> tuple[float, list[tuple[float, list]]]:
    from seatwin.api.client import scenario_steps
    from seatwin.api.lockstep import DEFAULT_VESSELS
    from seatwin.scenario.builtin import builtin_scenario

    sc = builtin_scenario("ferry_crossing")
    start = sc.start + offset
    steps = list(scenario_steps(sc, DEFAULT_VESSELS, start, (n_steps - 1) / 10.0))
    return start, steps


def _drive(address: str, start: float, steps: list) -> float:
    from seatwin.api.client import SimulationClient

    with SimulationClient(address) as c:
        c.set_start_time(start)
        c.step(steps[0][1], steps[0][0], 0.1)  # connection set up
        t0 = time.perf_counter()
        for rel, poses in steps[1:]:
            c.step(poses, rel, 0.1)
        return time.perf_counter() - t0


CLIENT = """
import json, sys, time
from seatwin.api.client import SimulationClient
address, path = sys.argv[1], sys.argv[2]
start, steps = json.load(open(path))
with SimulationClient(address) as c:
    c.set_start_time(start)
    c.step(steps[0][1], steps[0][0], 0.1)
    t0 = time.perf_counter()
    for rel, poses in steps[1:]:
        c.step(poses, rel, 0.1)
    print(time.perf_counter() - t0)
"""


def _drive_from_another_process(address: str, start: float, steps: list, tmp: Path) -> float:
    """The client in its own process (as an OSP/Gemini client is): its stepping loop's wall time."""
    import subprocess

    path = tmp / "steps.json"
    path.write_text(json.dumps([start, steps]))
    out = subprocess.run([sys.executable, "-c", CLIENT, address, str(path)], check=True, capture_output=True, text=True)
    return float(out.stdout.strip().splitlines()[-1])


def _noop_rate(start: float, steps: list, tmp: Path | None = None) -> float:
    """Round trips/s to a ``DoStep`` that does nothing (one worker thread, as ``serve``); the client in
    this process, or in another one when ``tmp`` is given."""
    import grpc

    from seatwin.api.proto import simulation_pb2, simulation_pb2_grpc
    from seatwin.api.server import SERVER_OPTIONS, bind

    class Noop(simulation_pb2_grpc.SimulationServicer):
        def DoStep(self, request: object, context: object) -> object:  # noqa: N802
            return simulation_pb2.StepResponse(success=True)

        def SetStartTime(self, request: object, context: object) -> object:  # noqa: N802
            return simulation_pb2.SetStartTimeResponse(success=True)

    server = grpc.server(futures.ThreadPoolExecutor(max_workers=1), options=SERVER_OPTIONS)
    simulation_pb2_grpc.add_SimulationServicer_to_server(Noop(), server)
    port = bind(server, "127.0.0.1", 0)
    server.start()
    try:
        address = f"127.0.0.1:{port}"
        wall = _drive(address, start, steps) if tmp is None else _drive_from_another_process(address, start, steps, tmp)
    finally:
        server.stop(None)
    return (len(steps) - 1) / wall


def _direct(run_dir: Path, start: float, steps: list, settings: dict) -> float:
    """Wall of :class:`LockstepSimulation` stepped in this process (no gRPC): set-up, steps, finishing the bag."""
    from seatwin.api.lockstep import LockstepSettings, LockstepSimulation

    t0 = time.perf_counter()
    sim = LockstepSimulation(run_dir, LockstepSettings(**settings))
    sim.set_start_time(repr(start))
    for rel, poses in steps:
        sim.step(poses, rel)
    sim.close()
    return time.perf_counter() - t0


def main() -> None:
    from seatwin.api.server import serve
    from seatwin.pipeline.simulate import simulate_run

    n_steps = int(sys.argv[1]) if len(sys.argv) > 1 else 700
    duration = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
    out: dict = {"loopback": True, "steps": n_steps, "duration_s": duration}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        start, steps = _requests(n_steps)
        out["noop_per_s"] = round(max(_noop_rate(start, steps) for _ in range(REPEATS)), 1)
        walls = []
        for r in range(REPEATS):
            h = serve(tmp / f"gt{r}", port=0, sensors=())
            try:
                walls.append(_drive(h.address, start, steps))
            finally:
                res = h.stop()
        out["dostep_per_s"] = round((len(steps) - 1) / min(walls), 1)
        out["dostep_vs_noop"] = round(out["dostep_per_s"] / out["noop_per_s"], 3)
        out["dostep_target_met"] = out["dostep_per_s"] >= 1000.0
        out["gt_frames"] = res.frames.get("ground_truth", 0)

        start, steps = _requests(int(round(duration * 10)) + 1, offset=20.0)
        # The same run both ways: sensors, rates, seed, harbour, range model, preset, bag format.
        same = {"sensors": ("lidar",), "seed": 0, "harbour": "default", "lidar_mode": "raycast", "lidar_preset": "vlp16"}
        same |= {"fmt": "mcap", "ground_truth_rate_hz": 10.0}
        simulate_run("ferry_crossing", tmp / "warm", start=start, duration=1.0, progress=False, **same)  # warm-up (BVH, imports)
        ref_walls, served_walls, direct_walls, inproc_walls, noop_walls = [], [], [], [], []
        for r in range(REPEATS):  # interleaved, best of each (a shared machine's load comes and goes)
            t0 = time.perf_counter()
            ref = simulate_run("ferry_crossing", tmp / f"ref{r}", start=start, duration=duration, progress=False, **same)
            ref_walls.append(time.perf_counter() - t0)
            # serve's set-up + the client's stepping loop (another process) + finishing the bag
            t0 = time.perf_counter()
            h = serve(tmp / f"served{r}", port=0, **same)
            setup = time.perf_counter() - t0
            try:
                loop = _drive_from_another_process(h.address, start, steps, tmp)
            finally:
                t0 = time.perf_counter()
                served = h.stop()
                finish = time.perf_counter() - t0
            served_walls.append(setup + loop + finish)
            direct_walls.append(_direct(tmp / f"direct{r}", start, steps, same))
            t0 = time.perf_counter()
            h = serve(tmp / f"inproc{r}", port=0, **same)
            try:
                _drive(h.address, start, steps)
            finally:
                h.stop()
            inproc_walls.append(time.perf_counter() - t0)
            noop_walls.append((len(steps) - 1) / _noop_rate(start, steps, tmp))
        ref_wall, served_wall = min(ref_walls), min(served_walls)
        out["simulate_wall_s"] = round(ref_wall, 4)
        out["lockstep_wall_s"] = round(served_wall, 4)
        out["lockstep_overhead"] = round(served_wall / ref_wall - 1.0, 3)
        out["lockstep_target_met"] = out["lockstep_overhead"] <= 0.20
        out["lockstep_direct_wall_s"] = round(min(direct_walls), 4)
        out["lockstep_direct_overhead"] = round(min(direct_walls) / ref_wall - 1.0, 3)
        out["noop_xproc_per_s"] = round((len(steps) - 1) / min(noop_walls), 1)
        out["transport_share"] = round(min(noop_walls) / ref_wall, 3)
        out["lockstep_inprocess_overhead"] = round(min(inproc_walls) / ref_wall - 1.0, 3)
        out["frames_equal"] = served.frames == ref.frames
        out["frames"] = served.frames
    print(json.dumps(out))


if __name__ == "__main__":
    main()
