"""Encounters placed in a harbour: per family and TCPA range, how many encounters found a place on water and how many
draws were refused (a path off the water) before each placement.

    PYTHONPATH=src .venv/bin/python benchmarks/encounter_placement.py --harbour ravnkloa --encounters 10

Encounter i of a family is the i-th point of a Latin hypercube (seed 0), placed with seed i (as ``seatwin verify``
does). Prints one line per (family, TCPA range) and the JSON on the last line.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from seatwin.encounters import NoPlacementError, latin_hypercube, place, space


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--harbour", default="ravnkloa")
    ap.add_argument("--encounters", type=int, default=10)
    ap.add_argument("--families", nargs="+", default=["crossing_give_way", "crossing_stand_on", "head_on", "overtaking", "multi"])
    a = ap.parse_args()
    out = []
    for family in a.families:
        for tcpa in (None, (20.0, 35.0)):
            sp = space(family, tcpa=tcpa)
            rejected, not_placed = [], 0
            c0 = time.process_time()
            for i, u in enumerate(latin_hypercube(sp.dimension, a.encounters, 0)):
                try:
                    rejected.append(place(sp.encounter(u), a.harbour, i, 0.0)[0].rejected)
                except NoPlacementError:
                    not_placed += 1
            row = {
                "family": family,
                "tcpa": list(tcpa) if tcpa else "family's (50-100 s)",
                "placed": len(rejected),
                "not_placed_in_3000_draws": not_placed,
                "rejected_median": statistics.median(rejected) if rejected else None,
                "rejected_max": max(rejected, default=None),
                "cpu_s": round(time.process_time() - c0, 2),
            }
            out.append(row)
            print(row, flush=True)
    print(json.dumps({"harbour": a.harbour, "encounters": a.encounters, "rows": out}))


if __name__ == "__main__":
    main()
