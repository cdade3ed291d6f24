"""Child process for the SIGKILL test: records sweeps forever, prints how many are flushed."""

import sys

from seatwin.recording import RecordingWriter, VesselPose
from seatwin.rng import frame_rng

run_dir, fmt = sys.argv[1], sys.argv[2]
w = RecordingWriter(run_dir, fmt, flush_interval_s=0.5, manifest_wall_s=0.0, seed=1)
n = 2000
rng = frame_rng(0, "test/killed-writer", 0)
k = 0
while True:
    t = 1.6e9 + 0.1 * k
    w.write_sweep(
        "/lidar/points",
        "lidar",
        t,
        rng.normal(size=n),
        rng.normal(size=n),
        rng.normal(size=n),
        rng.random(n),
        rng.integers(0, 16, n),
        rng.random(n) * 0.1,
    )
    w.write_ground_truth(t, [VesselPose("own", 0.1 * k, 0.0, 0.0, ownship=True)])
    k += 1
    if k % 5 == 1 and k > 1:  # a flush happened at the 0.5 s boundary before this sweep's write
        print(k, flush=True)
