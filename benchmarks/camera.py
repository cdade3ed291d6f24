"""Camera rig speed: 3 cameras at 5 Hz, 612 × 512 bgr8, rendered (moderngl, EGL) and recorded (MCAP).

A run of ``ferry_crossing`` with ``--sensors camera`` through the one simulation loop
(:func:`seatwin.sim.run.simulate_scenario`): ``realtime_factor`` = simulated / wall seconds
(target ≥ 2 on the 2-core CPU with Mesa llvmpipe). Baseline in the same process: the same run
with ground truth only, so ``camera_share`` is the part of the wall time the cameras cost.
The cost split sums each stage over every image (render = drawing until the GL finished,
read-back, labels, distortion, encode = serialising and writing the three topics per camera);
``distorted`` repeats the run with plumb-bob distortion on. Prints JSON on the last line.
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
from pathlib import Path


def _run(sensors: tuple[str, ...], duration: float, **changes: object) -> tuple[object, dict]:
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sim import run as sim_run
    from seatwin.sim.camera import CameraSensor

    sc = builtin_scenario("ferry_crossing")
    seen: dict = {}
    original = sim_run.scenario_sensors

    def capture_sensors(scenario: object, settings: object) -> list:
        out = original(scenario, settings)  # type: ignore[arg-type]
        seen["camera"] = next((s for s in out if isinstance(s, CameraSensor)), None)
        return out

    sim_run.scenario_sensors = capture_sensors  # type: ignore[assignment]
    try:
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            res = sim_run.simulate_scenario(
                sc, Path(tmp) / "run", start=sc.start + 20.0, duration=duration, progress=False, sensors=sensors, **changes
            )
            seen["total_wall_s"] = time.perf_counter() - t0
    finally:
        sim_run.scenario_sensors = original  # type: ignore[assignment]
    return res, seen


def main() -> None:
    from seatwin.render import create_context, renderer_name

    duration = float(sys.argv[1]) if len(sys.argv) > 1 else 20.0
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sim.loop import simulate
    from seatwin.sim.sensors import GroundTruthSensor

    _run(("camera",), 1.0)  # warm-up: EGL context, shader compilation, imports
    sc = builtin_scenario("ferry_crossing")
    with tempfile.TemporaryDirectory() as tmp:
        # baseline: ground truth only (the loop and the bag without any sensor)
        t0 = time.perf_counter()
        simulate([GroundTruthSensor(sc)], Path(tmp) / "gt", sc.start + 20.0, sc.start + 20.0 + duration, progress=False)
        gt_wall = time.perf_counter() - t0
    res, seen = _run(("camera",), duration)
    cam = seen["camera"]
    images = cam.timing.images
    split = cam.timing.as_dict()
    res_d, seen_d = _run(("camera",), duration / 4, camera_distortion=(-0.25, 0.08, 0.0, 0.0, 0.0))
    td = seen_d["camera"].timing
    out = {
        "renderer": renderer_name(create_context()),
        "cameras": len(cam.mounts),
        "width": cam.config.width,
        "height": cam.config.height,
        "rate_hz": cam.rate_hz,
        "simulated_s": res.simulated_s,
        "wall_s": res.wall_s,
        "realtime_factor": res.realtime_factor,
        "target_realtime_factor": 2.0,
        "meets_target": res.realtime_factor >= 2.0,
        "frames_per_s_per_camera": images / len(cam.mounts) / res.wall_s,
        "images": images,
        "ms_per_image": {k[:-2]: 1000 * v / images for k, v in split.items() if k.endswith("_s")},
        "baseline_ground_truth_only_wall_s": gt_wall,
        "camera_share": 1.0 - gt_wall / res.wall_s,
        "recording_share": res.recording_share,
        "distorted": {
            "realtime_factor": res_d.realtime_factor,
            "ms_per_image_distortion": 1000 * td.distortion_s / max(td.images, 1),
        },
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
