"""Coverage of the radar plot-level terms' intervals, by simulation (docs/validation.md, issue 22 item 2).

    .venv/bin/python benchmarks/plot_terms_calibration.py [PAIRS] [SCANS] [POWER_PAIRS] [WORKERS]

A known radar model (``KNOWN``, the controlled test's) makes ``2 × PAIRS`` recordings of the same scene
(:func:`seatwin.fidelity.synthetic.orbit_dataset`: target circling at 150–450 m, ``SCANS`` scans 2.5 s apart;
default 60 pairs of 200 scans, joyride's length) with independent seeds. Each pair (A as "real", B as
"model") gives every term of :func:`seatwin.evaluation.plot_terms.radar_plot_terms`. Two coverages per term,
nominal 95 %:

* **difference**: the share of pairs whose 95 % interval of ``B − A`` holds 0 — the true difference of two
  recordings of one model (what "resolved" tests: a calibrated interval calls a correct model off in 5 %);
* **one side**: the share of pairs whose 95 % interval of A's own statistic holds the pooled value (the
  statistic over all ``2 × PAIRS`` recordings together, the best estimate of the model's true value).

Then the first ``POWER_PAIRS`` (default 20) pairs with B made by a wrong model (bearing bias +1°,
bearing σ × 2, range σ × 2, Pd cap
0.85 → 0.65): the share of pairs in which the matching term is resolved (power at this length).
Prints a table and, on its last line, the figures as JSON.
"""

from __future__ import annotations

import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from seatwin.evaluation.plot_terms import RadarPlotSample, radar_plot_sample, radar_plot_terms
from seatwin.evaluation.score import ScoreOptions
from seatwin.fidelity.joyride import RADAR_CLUTTER_GATE_M, TARGET, antenna_positions, truth_of
from seatwin.fidelity.synthetic import orbit_dataset
from seatwin.sensors.radar.config import RadarConfig

KNOWN = RadarConfig(
    noise={"range_sigma_m": 6.0, "range_bias_m": 0.0, "bearing_sigma_deg": 0.6, "bearing_bias_deg": -1.0},
    clutter={"kind": "uniform", "density_per_km2": 1.0},
    detection={"snr_ref_db": 15.0, "pd_max": 0.85},
    max_range_m=1000.0,
)
AREA_KM2 = float(np.pi * (KNOWN.max_range_m**2 - KNOWN.min_range_m**2) / 1e6)


def _noise(**update: float) -> RadarConfig:
    return KNOWN.model_copy(update={"noise": KNOWN.noise.model_copy(update=update)})


WRONG = {
    "bearing_bias": ("bearing bias +1°", _noise(bearing_bias_deg=KNOWN.noise.bearing_bias_deg + 1.0)),
    "bearing_sigma": ("bearing σ × 2", _noise(bearing_sigma_deg=2 * KNOWN.noise.bearing_sigma_deg)),
    "range_sigma": ("range σ × 2", _noise(range_sigma_m=2 * KNOWN.noise.range_sigma_m)),
    "pd_250_500m": (
        "Pd cap 0.85 → 0.65",
        KNOWN.model_copy(update={"detection": KNOWN.detection.model_copy(update={"pd_max": 0.65})}),
    ),
}


def sample(config: RadarConfig, scans: int, seed: int) -> RadarPlotSample:
    data = orbit_dataset(config, n=scans, seed=seed)
    return radar_plot_sample(data.time, antenna_positions(data, config), data.plots, truth_of(data), TARGET, RADAR_CLUTTER_GATE_M)


def main(pairs: int = 60, scans: int = 200, power_pairs: int = 20, workers: int = 2) -> dict:
    t0 = time.perf_counter()
    opts = ScoreOptions(n_boot=400, seed=0)
    with ProcessPoolExecutor(workers) as pool:
        reps = list(pool.map(sample, [KNOWN] * (2 * pairs), [scans] * (2 * pairs), range(1000, 1000 + 2 * pairs)))
        wrongs = {
            k: list(pool.map(sample, [cfg] * power_pairs, [scans] * power_pairs, range(5000, 5000 + power_pairs)))
            for k, (_, cfg) in WRONG.items()
        }
    pooled = radar_plot_terms(reps, reps, AREA_KM2, ScoreOptions(n_boot=1))
    names = [k for k, v in pooled.items() if v.real is not None]
    cover_diff = {k: 0 for k in names}
    cover_side = {k: 0 for k in names}
    blocks: dict[str, list[int]] = {k: [] for k in names}
    for p in range(pairs):
        terms = radar_plot_terms([reps[2 * p]], [reps[2 * p + 1]], AREA_KM2, opts)
        for k in names:
            t = terms[k]
            cover_diff[k] += int(t.difference_ci[0] <= 0.0 <= t.difference_ci[1])
            cover_side[k] += int(t.real_ci[0] <= pooled[k].real <= t.real_ci[1])
            blocks[k].append(t.block)
    power = {}
    for k, (label, _) in WRONG.items():
        hits = sum(int(radar_plot_terms([reps[2 * p]], [w], AREA_KM2, opts)[k].resolved) for p, w in enumerate(wrongs[k]))
        power[k] = (label, hits / power_pairs)
    print(f"{pairs} pairs of {scans}-scan recordings of one radar model; nominal 95 % intervals, n_boot {opts.n_boot}")
    print(f"{'term':<22} {'pooled value':>12} {'diff. covers 0':>15} {'A covers pooled':>16} {'block (median)':>15}")
    for k in names:
        print(
            f"{k:<22} {pooled[k].real:>12.4g} {cover_diff[k] / pairs:>15.1%} {cover_side[k] / pairs:>16.1%} "
            f"{np.median(blocks[k]):>15.0f}"
        )
    print(f"Power (share of {power_pairs} pairs resolved, true model vs a wrong one):")
    for k, (label, share) in power.items():
        print(f"  {label:<22} term {k:<16} {share:.1%}")
    out = {
        "pairs": pairs,
        "power_pairs": power_pairs,
        "scans": scans,
        "coverage_difference": {k: cover_diff[k] / pairs for k in names},
        "coverage_one_side": {k: cover_side[k] / pairs for k in names},
        "power": {k: share for k, (_, share) in power.items()},
        "seconds": round(time.perf_counter() - t0, 1),
    }
    print(json.dumps(out))
    return out


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:5]))
