"""Coverage of the bearing-bias interval under a drifting bearing offset, with and without the long-memory rule
(issue 22, item 2; docs/fidelity-score.md, *Long memory*).

A recording is a per-scan series of bearing errors [deg]: the known model's noise (bias −1°, σ 0.6°, the target
detected in a scan with probability 0.85, NaN otherwise; ``radar_score_checks.py``'s known model) plus an AR(1)
offset (coefficient φ, stationary σ; :func:`seatwin.fidelity.controlled.drift_offsets`, independent per recording)
— the statistical problem of ``radar_score_checks.py calibration``'s drifting variant without its radar
simulation (the offset turns every plot about the antenna, so it adds to the bearing error of the nearest plot).
Pair i: recordings ``2i`` (A, "real") and ``2i + 1`` (B, "model"). Covered: the 95 % interval of B − A holds 0;
A's interval holds the true value (−1°, the clipped mean of a symmetric law).

    .venv/bin/python benchmarks/drift_calibration.py PAIRS PHI SIGMA [SCANS] [BASE]
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np

from seatwin.evaluation.plot_terms import clipped_mean, signed_term
from seatwin.evaluation.score import ScoreOptions
from seatwin.fidelity.controlled import drift_offsets

BIAS, SIGMA, PD = -1.0, 0.6, 0.85


def recording(index: int, scans: int, phi: float, sigma: float) -> np.ndarray:
    """One recording's bearing errors [deg] per scan (NaN: not detected)."""
    rng = np.random.default_rng(index)
    x = BIAS + rng.normal(0.0, SIGMA, scans) + drift_offsets(scans, index + 7_000_000, phi, sigma)
    x[rng.random(scans) >= PD] = np.nan
    return x


def main(pairs: int, phi: float, sigma: float, scans: int = 238, base: int = 1000) -> dict:
    t0 = time.perf_counter()
    out: dict = {"pairs": pairs, "phi": phi, "sigma": sigma, "scans": scans, "base": base}
    recs = [recording(base + k, scans, phi, sigma) for k in range(2 * pairs)]
    for rule, memory in (("old", False), ("new", True)):
        o = ScoreOptions(n_boot=400, seed=0, long_memory=memory)
        diff = side = 0
        widths, factors = [], []
        for p in range(pairs):
            t = signed_term("bearing bias", "°", [recs[2 * p]], [recs[2 * p + 1]], clipped_mean, o)
            diff += t.difference_ci[0] <= 0.0 <= t.difference_ci[1]
            side += t.real_ci[0] <= BIAS <= t.real_ci[1]
            widths.append(t.difference_ci[1] - t.difference_ci[0])
            factors.append(t.counts.get("memory_inflation_real", 1.0))
        out[rule] = {
            "difference_covers_0": diff / pairs,
            "a_covers_true": side / pairs,
            "mean_width": float(np.mean(widths)),
            "mean_inflation": float(np.mean(factors)),
        }
        print(f"{rule} rule: diff covers 0 {diff}/{pairs}, A covers −1° {side}/{pairs}, mean width {np.mean(widths):.3f}°")
    out["seconds"] = round(time.perf_counter() - t0, 1)
    print(json.dumps(out))
    return out


if __name__ == "__main__":
    a = sys.argv[1:]
    main(int(a[0]), float(a[1]), float(a[2]), *(int(v) for v in a[3:5]))
