"""Do the Ravnkloa shore radar's detections line up with the land raster unrotated? (issue 21)

All detections of the eight radar-2023 recordings, rotated about the radar (north −8 m, east 0) by
each angle, against the raw raster (its own frame, no alignment): the share on land, the share within
3 m of a land edge, and the angular gap between the detections' boundary (99.5th percentile of
bearing, 180–250°) and the south-west quay edge in 10 m range bins from 80 to 150 m.

    .venv/bin/python benchmarks/ravnkloa_radar_alignment.py
"""

from __future__ import annotations

import numpy as np


def main() -> None:
    from scipy.ndimage import map_coordinates

    from seatwin.layout.alignment import Alignment, signed_distance
    from seatwin.layout.harbours import RAVNKLOA_RASTER, find_data_file
    from seatwin.layout.raster import read_land_raster

    path = find_data_file(RAVNKLOA_RASTER, "the Ravnkloa land raster")
    raster = read_land_raster(path)
    sd = signed_distance(raster.water, raster.resolution)
    files = sorted((path.parent / "radar-2023").glob("*.csv"))
    det = np.vstack([np.loadtxt(f, delimiter=",", skiprows=1, ndmin=2) for f in files])
    print(f"{len(det)} detections from {len(files)} recordings")
    print(
        "| detections rotated about the radar | on raster land | within 3 m of a land edge | gap to the SW quay edge, 80…150 m |"
    )
    print("| --- | --- | --- | --- |")
    for phi in (4.0, 3.0, 0.0, -3.0, -8.0, -16.375, -20.0):
        n, e = Alignment(phi, -8.0, 0.0).to_map(det[:, 1], det[:, 2])
        d = map_coordinates(
            sd,
            [(n - raster.origin_north) / raster.resolution - 0.5, (e - raster.origin_east) / raster.resolution - 0.5],
            order=1,
            cval=-50.0,
        )
        rng, brg = np.hypot(n + 8.0, e), np.degrees(np.arctan2(e, n + 8.0)) % 360
        gaps = []
        for r0 in range(80, 150, 10):
            bs = np.arange(180.0, 250.0, 0.05)
            rr = r0 + 5.0
            land = ~raster.is_water(-8.0 + rr * np.cos(np.radians(bs)), rr * np.sin(np.radians(bs)), outside=False)
            sel = (rng >= r0) & (rng < r0 + 10) & (brg > 180) & (brg < 250)
            gaps.append(bs[np.argmax(land)] - np.percentile(brg[sel], 99.5))
        on_land, near_edge = 100 * np.mean(d <= 0), 100 * np.mean(np.abs(d) <= 3)
        print(f"| {phi:+.1f}° | {on_land:.2f} % | {near_edge:.2f} % | {gaps[0]:.1f} … {gaps[-1]:.1f}° |")


if __name__ == "__main__":
    main()
