"""Benchmark: JIPDA tracker scans per second, and the speed-up over Stone Soup's JPDA.

    .venv/bin/python benchmarks/tracking.py [--scans N]

Problem: 3 targets (CV, q = 0.3 m²/s³) in a 1 km × 1 km square, Cartesian plots (σ = 3 m),
P_D = 0.9, on average 10 uniform clutter plots per scan, 1 s between scans — simulated with
:func:`seatwin.tracking.simulate.simulate` (fixed seed). One thread (BLAS pinned to 1); times
are CPU time of this process (``time.process_time``), so other load on a shared machine does
not count against either tracker.

* ``scans_per_s``: our whole tracker (prediction, gating, exact JIPDA association, mixture
  update, existence, initiation and termination from scratch), best of 7 runs.
* ``speedup_vs_stonesoup``: Stone Soup 1.x ``JPDA`` + ``PDAHypothesiser`` + ``DistanceGater`` +
  Kalman predictor/updater with the same CV and measurement models and the same gate, on the
  same scans, with its three tracks given from the start (no initiation: less work than ours),
  per-track Gaussian-mixture reduction as in Stone Soup's JPDA tutorial; its best of 3 runs
  per scan over our best of 7 per scan on the same scans, measured in this process.
* ``clutter_scaling``: our scans/s at 0, 10, 30, 100 clutter plots per scan.

Prints a short table and, on its last line, the JSON.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import datetime as dt  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from seatwin.perception import MeasurementKind, Scan  # noqa: E402
from seatwin.tracking import JIPDATracker, TrackerConfig  # noqa: E402
from seatwin.tracking.simulate import SimulatedRun, simulate  # noqa: E402

AREA = (-500.0, 500.0, -500.0, 500.0)
Q, R, PD, PG = 0.3, 9.0, 0.9, 0.99


def config(clutter_mean: float) -> TrackerConfig:
    return TrackerConfig(
        name="bench",
        q_north=Q,
        q_east=Q,
        gate_g=None,
        gate_probability=PG,
        sensors={
            "radar": dict(
                r_range=R, r_bearing=1e-4, r_cartesian=R, p_detect=PD, clutter_density=max(clutter_mean, 0.1) / 1000.0**2
            )
        },
    )


def problem(n_scans: int, clutter_mean: float) -> SimulatedRun:
    return simulate(
        n_scans=n_scans,
        dt=1.0,
        n_targets=3,
        q=Q,
        r_cartesian=R,
        kind=MeasurementKind.CARTESIAN,
        p_detect=PD,
        clutter_mean=clutter_mean,
        area=AREA,
        seed=11,
    )


def time_ours(scans: list[Scan], cfg: TrackerConfig, repeats: int = 7) -> float:
    """Best seconds per scan over ``repeats`` fresh runs."""
    best = np.inf
    for _ in range(repeats):
        tr = JIPDATracker(cfg)
        t0 = time.process_time()
        for s in scans:
            tr.step(s)
        best = min(best, (time.process_time() - t0) / len(scans))
    return best


def time_stonesoup(scans: list[Scan], truth0: np.ndarray, clutter_mean: float) -> float:
    """Seconds per scan of Stone Soup's JPDA on the same scans (tracks given from the start)."""
    from scipy.stats import chi2
    from stonesoup.dataassociator.probability import JPDA
    from stonesoup.functions import gm_reduce_single
    from stonesoup.gater.distance import DistanceGater
    from stonesoup.hypothesiser.probability import PDAHypothesiser
    from stonesoup.measures import Mahalanobis
    from stonesoup.models.measurement.linear import LinearGaussian
    from stonesoup.models.transition.linear import CombinedLinearGaussianTransitionModel, ConstantVelocity
    from stonesoup.predictor.kalman import KalmanPredictor
    from stonesoup.types.array import StateVectors
    from stonesoup.types.detection import Detection
    from stonesoup.types.state import GaussianState
    from stonesoup.types.track import Track
    from stonesoup.types.update import GaussianStateUpdate
    from stonesoup.updater.kalman import KalmanUpdater

    t0 = dt.datetime(2020, 9, 15, 12)
    trans = CombinedLinearGaussianTransitionModel([ConstantVelocity(Q), ConstantVelocity(Q)])
    meas = LinearGaussian(4, (0, 2), np.eye(2) * R)
    predictor, updater = KalmanPredictor(trans), KalmanUpdater(meas)
    hyp = PDAHypothesiser(
        predictor, updater, clutter_spatial_density=max(clutter_mean, 0.1) / 1000.0**2, prob_detect=PD, prob_gate=PG
    )
    jpda = JPDA(DistanceGater(hyp, measure=Mahalanobis(), gate_threshold=float(np.sqrt(chi2.ppf(PG, 2)))))
    tracks = {Track([GaussianState(x.reshape(4, 1), np.diag([9.0, 4.0, 9.0, 4.0]), timestamp=t0)]) for x in truth0}
    base = scans[0].time
    # Detections built before timing (our tracker gets ready-made Scan objects too).
    frames = []
    for s in scans[1:]:
        ts = t0 + dt.timedelta(seconds=s.time - base)
        frames.append((ts, {Detection(z.reshape(2, 1), timestamp=ts, measurement_model=meas) for z in s.z}))
    start = time.process_time()
    for ts, dets in frames:
        hypotheses = jpda.associate(tracks, dets, ts)
        for track, multi in hypotheses.items():
            states, weights = [], []
            for h in multi:
                states.append(h.prediction if not h else updater.update(h))
                weights.append(float(h.probability))
            means = StateVectors([st.state_vector for st in states])
            covars = np.stack([st.covar for st in states], axis=2)
            m, c = gm_reduce_single(means, covars, np.asarray(weights))
            track.append(GaussianStateUpdate(m, c, multi, ts))
    return (time.process_time() - start) / len(frames)


def main() -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scans", type=int, default=300, help="scans per run (default 300)")
    ap.add_argument("--stonesoup-scans", type=int, default=150, help="scans timed for Stone Soup (default 150)")
    args = ap.parse_args()
    run = problem(args.scans, 10.0)
    cfg = config(10.0)
    ours = time_ours(run.scans, cfg)
    n_ss = min(args.stonesoup_scans, args.scans)
    ours_same = time_ours(run.scans[:n_ss], cfg)
    ss = min(time_stonesoup(run.scans[:n_ss], run.truth[0], 10.0) for _ in range(3))
    scaling = {}
    for c in (0.0, 10.0, 30.0, 100.0):
        r = problem(args.scans, c)
        scaling[str(int(c))] = round(1.0 / time_ours(r.scans, config(c), repeats=3), 1)
    mean_meas = float(np.mean([s.z.shape[0] for s in run.scans]))
    return {
        "scans_per_s": round(1.0 / ours, 1),
        "speedup_vs_stonesoup": round(ss / ours_same, 1),
        "stonesoup_scans_per_s": round(1.0 / ss, 1),
        "ours_scans_per_s_same_scans": round(1.0 / ours_same, 1),
        "measurements_per_scan": round(mean_meas, 2),
        "clutter_scaling_scans_per_s": scaling,
        "n_scans": args.scans,
        "n_scans_stonesoup": n_ss,
    }


if __name__ == "__main__":
    res = main()
    print(
        f"ours: {res['scans_per_s']} scans/s ({res['measurements_per_scan']} measurements/scan); "
        f"Stone Soup JPDA: {res['stonesoup_scans_per_s']} scans/s; speed-up ×{res['speedup_vs_stonesoup']}"
    )
    print("scans/s by mean clutter per scan:", res["clutter_scaling_scans_per_s"])
    print(json.dumps(res))
