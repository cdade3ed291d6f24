"""The tracker on the Ravnkloa shore-radar recordings (real clutter, no ground truth).

    .venv/bin/python benchmarks/tracking_ravnkloa.py [../shared/data/ravnkloa]

Each ``radar-2023/*.csv`` is imported (``seatwin import ravnkloa-radar --map RASTER``) and
tracked (``seatwin track``, preset ``ravnkloa``: land plots masked with the raster, plots within
3 m merged). Without ground truth the number of tracks is judged against the data itself:

* ``plots_per_scan`` / ``water_plots_per_scan``: plots before and after the land mask and merging;
* ``recurring_plots_per_scan``: water plots with a water plot of the previous scan within 5 m —
  objects seen scan after scan (moored boats, buoys, quay edges the raster misses, boats under
  way), which a tracker *should* hold as tracks;
* ``confirmed_tracks`` (over the file), ``confirmed_per_scan`` (mean and max at one time),
  ``stationary`` (median speed < 0.5 m/s) vs ``moving`` confirmed tracks, the fastest track's
  median speed, and confirmed tracks whose mean position is on land.

Plausible: confirmed tracks per scan ≈ recurring plots per scan (not more: clutter that does not
recur must not make tracks), moving tracks at harbour speeds (< 5 m/s), none on land.
Prints a table and, on its last line, JSON.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def summarise(csv: Path, mask_path: Path, tmp: Path) -> dict:
    from seatwin.perception.datasets import RAVNKLOA_RADAR_POSITION, import_ravnkloa_radar, read_ravnkloa_radar
    from seatwin.perception.map_mask import RasterMask
    from seatwin.perception.radar import RadarPlots, radar_scan
    from seatwin.pipeline import track_recording

    rd = tmp / csv.stem
    import_ravnkloa_radar(csv, rd, "mcap", map_path=str(mask_path))
    tr = track_recording(rd).tracks
    mask = RasterMask.load(mask_path)
    ds = read_ravnkloa_radar(csv)
    sn, se = RAVNKLOA_RADAR_POSITION
    scans = [radar_scan(p, t, sn, se, mask, RadarPlots(merge_distance=3.0)) for t, p in zip(ds.time, ds.plots)]
    water = [s.positions() for s in scans]
    recurring = []  # water plots with a water plot of the previous scan within 5 m
    for prev, cur in zip(water[:-1], water[1:]):
        if len(prev) and len(cur):
            d = np.hypot(cur[:, None, 0] - prev[None, :, 0], cur[:, None, 1] - prev[None, :, 1])
            recurring.append(int((d.min(axis=1) <= 5.0).sum()))
        else:
            recurring.append(0)
    conf = tr.confirmed
    ids = np.unique(tr.track_id[conf])
    speeds, on_land = [], 0
    for i in ids:
        m = conf & (tr.track_id == i)
        speeds.append(float(np.median(np.hypot(tr.state[m, 1], tr.state[m, 3]))))
        mean = tr.state[m][:, [0, 2]].mean(axis=0)
        on_land += int(not mask.is_water(mean[0], mean[1]))
    speeds_a = np.array(speeds)
    _, per_scan = np.unique(tr.time[conf], return_counts=True)
    return {
        "file": csv.name,
        "scans": len(scans),
        "plots_per_scan": round(float(np.mean([len(p) for p in ds.plots])), 1),
        "water_plots_per_scan": round(float(np.mean([len(w) for w in water])), 1),
        "recurring_plots_per_scan": round(float(np.mean(recurring)), 1),
        "tracks": int(len(np.unique(tr.track_id))),
        "confirmed_tracks": int(len(ids)),
        "confirmed_per_scan_mean": round(float(per_scan.sum() / len(tr.scan_times)), 1),
        "confirmed_per_scan_max": int(per_scan.max()) if per_scan.size else 0,
        "stationary": int((speeds_a < 0.5).sum()),
        "moving": int((speeds_a >= 0.5).sum()),
        "max_median_speed_mps": round(float(speeds_a.max()), 2) if speeds_a.size else 0.0,
        "on_land": on_land,
    }


def main(folder: Path) -> list[dict]:
    mask_path = folder / "ravnkloa_radar_base_map.yaml"
    files = sorted((folder / "radar-2023").glob("*.csv"))
    if not files:
        raise SystemExit(f"no radar-2023/*.csv under {folder}")
    with tempfile.TemporaryDirectory() as tmp:
        return [summarise(f, mask_path, Path(tmp)) for f in files]


if __name__ == "__main__":
    folder = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT.parent / "shared" / "data" / "ravnkloa"
    rows = main(folder)
    keys = list(rows[0])
    print(" ".join(f"{k}" for k in keys))
    for r in rows:
        print(" ".join(str(r[k]) for k in keys))
    print(json.dumps(rows))
