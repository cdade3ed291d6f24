"""Signals, killed runs and a hostile ``serve`` client (issue 20, sections 4–5), measured on real processes.

* ``serve`` (``--sensors none``) against a client built from the .proto files: how long it takes to
  refuse a 100 MB ``DoStep`` (6.2 M poses) and a step at last + 1e5 s, and the server's peak memory
  (VmHWM) before and after; that the next valid step is still taken.
* ``simulate ferry_crossing --sensors lidar,camera`` stopped by SIGTERM once it has recorded camera
  frames: seconds from the signal to the process's exit, exit status, every camera topic's count.
* ``bag repair`` of a ``simulate`` run killed with SIGKILL (each format): messages kept, seconds.

    .venv/bin/python benchmarks/signals.py

Last line: JSON.
"""

from __future__ import annotations

import json
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CLI = [sys.executable, "-c", "from seatwin.cli.main import main; main()"]


def _vm_hwm_mb(pid: int) -> float:
    text = Path(f"/proc/{pid}/status").read_text()
    return int(re.search(r"VmHWM:\s+(\d+) kB", text).group(1)) / 1024  # type: ignore[union-attr]


def hostile_serve(tmp: Path) -> dict:
    import grpc

    from seatwin.api.client import SimulationClient
    from seatwin.api.proto import simulation_pb2

    proc = subprocess.Popen(
        [*CLI, "serve", "--port", "0", "--out", str(tmp / "serve"), "--sensors", "none"], stdout=subprocess.PIPE, text=True
    )
    address = re.search(r"on (127\.0\.0\.1:\d+)", proc.stdout.readline()).group(1)  # type: ignore[union-attr]
    ok = [(0.0, 0.0, 0.0), (10.0, 0.0, 90.0), (20.0, 5.0, 180.0)]
    out: dict = {}
    try:
        with SimulationClient(address) as c:
            c.set_start_time(1.6e9)
            c.step(ok, 0.0, 0.1)
            out["rss_before_mb"] = round(_vm_hwm_mb(proc.pid), 1)
            pose = simulation_pb2.StepRequest(VesselPoses=[simulation_pb2.Pose(north=1.0, east=2.0, heading=3.0)])
            big = pose.SerializeToString() * 6_200_000  # 105 MB: the bytes of a 6.2 M-pose StepRequest, built at once
            raw = c.channel.unary_unary("/GeminiOSPInterface.Simulation/DoStep")  # bytes in, bytes out
            t0 = time.perf_counter()
            try:
                raw(big, timeout=300)
            except grpc.RpcError as exc:
                out["big_request"] = {
                    "mb": round(len(big) / 1e6, 1),
                    "code": exc.code().name,
                    "refused_s": round(time.perf_counter() - t0, 3),
                }
            t0 = time.perf_counter()
            try:
                c.step(ok, 0.1 + 1e5, 0.1)
            except grpc.RpcError as exc:
                out["time_jump"] = {
                    "code": exc.code().name,
                    "refused_s": round(time.perf_counter() - t0, 4),
                    "details": exc.details(),
                }
            out["next_valid_step_taken"] = c.step(ok, 0.1, 0.1)
            out["rss_after_mb"] = round(_vm_hwm_mb(proc.pid), 1)
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.communicate(timeout=60)
    out["exit_status"] = proc.returncode
    return out


def _wait_camera(run_dir: Path, proc: subprocess.Popen, n: int = 2) -> None:
    for _ in range(1200):
        try:
            topics = json.loads((run_dir / "manifest.json").read_text())["topics"]
        except (OSError, ValueError, KeyError):
            topics = {}
        if proc.poll() is not None or topics.get("/camera/front/image_raw", {}).get("count", 0) >= n:
            return
        time.sleep(0.1)


def sigterm_simulate(tmp: Path, fmt: str) -> dict:
    run_dir = tmp / f"sim-{fmt}"
    proc = subprocess.Popen(
        [*CLI, "simulate", "ferry_crossing", "--out", str(run_dir), "--sensors", "lidar,camera", "--format", fmt, "-q"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    _wait_camera(run_dir, proc)
    t0 = time.perf_counter()
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    exit_s = time.perf_counter() - t0
    m = json.loads((run_dir / "manifest.json").read_text())
    cams = sorted({v["count"] for t, v in m["topics"].items() if t.startswith("/camera/")})
    return {
        "exit_status": proc.returncode,
        "signal_to_exit_s": round(exit_s, 2),
        "stderr": err.strip().splitlines()[-1],
        "error": m["error"],
        "camera_topic_counts": cams,
    }


def repair_killed(tmp: Path, fmt: str) -> dict:
    from seatwin.recording import open_bag
    from seatwin.recording.repair import repair_bag

    run_dir = tmp / f"killed-{fmt}"
    proc = subprocess.Popen(
        [*CLI, "simulate", "ferry_crossing", "--out", str(run_dir), "--sensors", "lidar,camera", "--format", fmt, "-q"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    _wait_camera(run_dir, proc, n=6)
    proc.kill()
    proc.wait()
    t0 = time.perf_counter()
    result = repair_bag(run_dir)
    repair_s = time.perf_counter() - t0
    from rosbags.highlevel import AnyReader

    from seatwin.recording.storage import bag_path

    with AnyReader([bag_path(result.out, fmt)]) as reader:
        n_any = sum(1 for _ in reader.messages())
    with open_bag(result.out) as bag:
        recovered = bag.recovered
    return {
        "messages": result.messages,
        "anyreader_messages": n_any,
        "repair_s": round(repair_s, 2),
        "recovered_after": recovered,
    }


def main() -> None:
    tmp = Path(tempfile.mkdtemp(prefix="seatwin-signals-"))
    try:
        out = {"serve": hostile_serve(tmp)}
        if "--serve-only" in sys.argv:
            print(json.dumps(out))
            return
        out["simulate_sigterm"] = {fmt: sigterm_simulate(tmp, fmt) for fmt in ("mcap", "sqlite3", "ros1")}
        out["repair_sigkill"] = {fmt: repair_killed(tmp, fmt) for fmt in ("mcap", "sqlite3", "ros1")}
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
