"""Benchmark: the JIPDA tracker in a crowded marina — bounded cost per scan (issue 14).

    .venv/bin/python benchmarks/tracking_dense.py [--scans N] [--boats N] [--clutter N]

Problem: 60 moored boats in a row along east, 2 m apart (a 118 m pontoon), stationary;
**Cartesian plots** (north/east, as from lidar cluster centroids), σ = 0.3 m per axis,
P_D = 0.9; 100 clutter plots per scan uniform over the 200 m × 200 m square around the row
(λ = 2.5·10⁻³ /m²); 1 s between scans, 100 scans. Tracker: q = 0.01 m²/s³ (moored boats),
χ² gate P_G = 0.99, default track management (two-point initiation within v_max·ΔT = 10 m, so
clutter starts tentative tracks every scan, and new tracks' wide gates span several boats).
Fixed seed; one thread (BLAS pinned to 1); times are ``time.process_time`` of this process.

* ``worst_scan_s``: the slowest ``JIPDATracker.step`` over the run (target ≤ 0.05 s);
* ``max_rss_mb``: peak resident memory of this process (``resource.getrusage``; target ≤ 500);
* ``confirmed_tracks``: confirmed live tracks after the last scan; ``boats_confirmed``: boats
  with a confirmed track within 1 m, one track per boat (target ≥ 55 of 60);
  ``false_confirmed``: confirmed tracks matched to no boat;
* ``baseline_worst_scan_s`` and ``ratio_vs_sparse``: the same run with the boats 50 m apart
  (no shared gates: every association in closed form) — what crowding costs;
* ``association``: how many clusters each method solved over the run (exact enumeration,
  exact forward–backward, belief propagation);
* ``stress``: the same row with σ = 0.5 m and q = 0.05 m²/s³: every boat's gate holds its
  neighbours' plots, the whole row is one cluster in every scan (the old enumeration needed
  seconds per scan from 20 boats on) and belief propagation solves it. Its cost must meet the
  same targets; its tracking quality is poor (tracks settle between boats: a measurement
  4σ from two boats is ambiguous for any JPDA-type tracker) and is reported, not targeted.

Prints a table and, on its last line, the JSON.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import resource  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from scipy.optimize import linear_sum_assignment  # noqa: E402

from seatwin.perception import MeasurementKind, Scan  # noqa: E402
from seatwin.rng import frame_rng  # noqa: E402
from seatwin.tracking import JIPDATracker, TrackerConfig, association  # noqa: E402

PD, HALF = 0.9, 100.0


def config(clutter: int, sigma: float, q: float) -> TrackerConfig:
    return TrackerConfig(
        name="dense",
        q_north=q,
        q_east=q,
        gate_g=None,
        gate_probability=0.99,
        sensors={
            "lidar": dict(
                r_range=1.0,
                r_bearing=1e-4,
                r_cartesian=sigma**2,
                p_detect=PD,
                clutter_density=max(clutter, 1) / (2 * HALF) ** 2,
            )
        },
    )


def boats(n: int, spacing: float) -> np.ndarray:
    east = (np.arange(n) - (n - 1) / 2) * spacing
    return np.column_stack((np.zeros(n), east))


def scans(truth: np.ndarray, n_scans: int, clutter: int, sigma: float, seed: int = 14) -> list[Scan]:
    out = []
    for k in range(n_scans):
        rng = frame_rng(seed, "bench/tracking_dense", k)
        det = truth[rng.random(truth.shape[0]) < PD]
        z = det + rng.standard_normal(det.shape) * sigma
        c = rng.uniform(-HALF, HALF, (clutter, 2))
        z = np.concatenate((z, c))[rng.permutation(det.shape[0] + clutter)]
        out.append(Scan(time=1.0e9 + k, sensor="lidar", kind=MeasurementKind.CARTESIAN, z=z))
    return out


class _Counting:
    """Counts which association method solved each shared cluster (wraps the module functions)."""

    def __init__(self) -> None:
        self.counts = {"enumeration": 0, "forward_backward": 0, "belief_propagation": 0}
        self._fb, self._bp, self._en = association.frontier_marginals, association.bp_marginals, association._enumerate  # noqa: SLF001

    def __enter__(self) -> _Counting:
        def fb(*a: object, **k: object) -> object:
            out = self._fb(*a, **k)
            if out is not None:
                self.counts["forward_backward"] += 1
            return out

        def bp(*a: object, **k: object) -> object:
            self.counts["belief_propagation"] += 1
            return self._bp(*a, **k)

        def en(*a: object, **k: object) -> object:
            self.counts["enumeration"] += 1
            return self._en(*a, **k)

        association.frontier_marginals, association.bp_marginals, association._enumerate = fb, bp, en  # noqa: SLF001
        return self

    def __exit__(self, *exc: object) -> None:
        association.frontier_marginals, association.bp_marginals, association._enumerate = self._fb, self._bp, self._en  # noqa: SLF001


def run(truth: np.ndarray, sc: list[Scan], cfg: TrackerConfig) -> tuple[float, float, JIPDATracker]:
    tr = JIPDATracker(cfg)
    times = []
    for s in sc:
        t0 = time.process_time()
        tr.step(s)
        times.append(time.process_time() - t0)
    return max(times), float(np.mean(times)), tr


def matched_boats(truth: np.ndarray, tr: JIPDATracker, radius: float = 1.0) -> tuple[int, int]:
    """(boats with a confirmed track within ``radius``, one per boat; confirmed tracks matched to none)."""
    pos = tr.x[tr.confirmed][:, (0, 2)]
    if not pos.size:
        return 0, 0
    d = np.hypot(truth[:, None, 0] - pos[None, :, 0], truth[:, None, 1] - pos[None, :, 1])
    rows, cols = linear_sum_assignment(np.where(d <= radius, d, 1e6))
    ok = d[rows, cols] <= radius
    return int(ok.sum()), int(pos.shape[0] - ok.sum())


def scenario(n_boats: int, n_scans: int, clutter: int, sigma: float, q: float) -> dict:
    cfg = config(clutter, sigma, q)
    truth = boats(n_boats, 2.0)
    with _Counting() as counting:
        worst, mean, tr = run(truth, scans(truth, n_scans, clutter, sigma), cfg)
    n_ok, n_false = matched_boats(truth, tr)
    return {
        "worst_scan_s": round(worst, 4),
        "mean_scan_s": round(mean, 4),
        "confirmed_tracks": int(tr.confirmed.sum()),
        "boats_confirmed": n_ok,
        "false_confirmed": n_false,
        "live_tracks_end": int(tr.r.size),
        "association": counting.counts,
        "sigma_m": sigma,
        "q": q,
    }


def main() -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scans", type=int, default=100)
    ap.add_argument("--boats", type=int, default=60)
    ap.add_argument("--clutter", type=int, default=100, help="clutter plots per scan (default 100)")
    args = ap.parse_args()
    res = scenario(args.boats, args.scans, args.clutter, 0.3, 0.01)
    stress = scenario(args.boats, args.scans, args.clutter, 0.5, 0.05)
    sparse = boats(args.boats, 50.0)
    base_worst, base_mean, _ = run(sparse, scans(sparse, args.scans, args.clutter, 0.3), config(args.clutter, 0.3, 0.01))
    rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    res.update(
        {
            "max_rss_mb": round(rss_mb, 1),
            "baseline_worst_scan_s": round(base_worst, 4),
            "baseline_mean_scan_s": round(base_mean, 4),
            "ratio_vs_sparse": round(res["worst_scan_s"] / base_worst, 2),
            "measurements": "cartesian",
            "boats": args.boats,
            "clutter_per_scan": args.clutter,
            "n_scans": args.scans,
            "stress": stress,
            "targets": {"worst_scan_s": 0.05, "max_rss_mb": 500, "boats_confirmed": 55},
        }
    )
    return res


if __name__ == "__main__":
    res = main()
    print(
        f"{res['boats']} boats 2 m apart + {res['clutter_per_scan']} clutter/scan: worst scan {res['worst_scan_s'] * 1e3:.1f} ms "
        f"(mean {res['mean_scan_s'] * 1e3:.1f} ms; boats 50 m apart: {res['baseline_worst_scan_s'] * 1e3:.1f} ms), "
        f"peak RSS {res['max_rss_mb']} MB, boats confirmed {res['boats_confirmed']}/{res['boats']} "
        f"({res['false_confirmed']} false confirmed); clusters solved: {res['association']}"
    )
    st = res["stress"]
    print(
        f"stress (σ = 0.5 m, one cluster per scan): worst scan {st['worst_scan_s'] * 1e3:.1f} ms, boats confirmed "
        f"{st['boats_confirmed']}/{res['boats']} ({st['false_confirmed']} false); clusters solved: {st['association']}"
    )
    print(json.dumps(res))
