"""Benchmark: one ground-truth step serialised (``GroundTruthEncoder.step``: 3 vessels' PoseStamped and Odometry,
the ownship's NavSatFix from a precomputed LLH, one /tf), µs per step, best of 5 × 2000 calls.

``--legacy`` calls the API of recordings before REP-105 frames (entries (pose, body frame, with fix)), for a
comparison with an older tree: ``git archive 4812cc9 src | tar -x -C /tmp/old`` then
``PYTHONPATH=/tmp/old/src python benchmarks/ground_truth_step.py --legacy``.
Prints JSON on its last line.
"""

from __future__ import annotations

import argparse
import json
import timeit

import numpy as np

from seatwin.recording import TopicConfig
from seatwin.recording.fast_cdr import GroundTruthEncoder
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sim.poses import PoseTable


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--legacy", action="store_true")
    args = ap.parse_args()
    sc = builtin_scenario("ferry_crossing")
    t = sc.start + 10.0
    poses = PoseTable.from_scenario(sc, np.array([t])).poses(0)
    enc, tp = GroundTruthEncoder("mcap"), TopicConfig()
    if args.legacy:
        entries = [(v, tp.body(v.name), v.ownship) for v in poses]
    else:
        entries = [
            (
                v,
                (
                    tp.body(v.name),
                    tp.frame("gnss_frame", v.name) if v.ownship else None,
                    tp.frame("odom_frame", v.name),
                    tp.frame("base_frame", v.name),
                ),
            )  # noqa: E501
            for v in poses
        ]

    def step() -> None:
        enc.step(t, tp.world_frame, entries, sc.origin)  # type: ignore[arg-type]

    step()
    best = min(timeit.repeat(step, number=2000, repeat=5)) / 2000
    print(json.dumps({"vessels": len(poses), "legacy": args.legacy, "step_us": round(best * 1e6, 2)}))


if __name__ == "__main__":
    main()
