# ruff: noqa: ANN001, ANN003, ANN201, ANN202, ANN204
"""The ``ScenarioPlayer`` FMU (FMI 2.0 co-simulation, built by ``pythonfmu``; OSP's scenario generator of thesis Fig. 4.17).

Outputs each vessel's ``<name>.north``, ``<name>.east`` [m] and ``<name>.heading`` [deg clockwise from
north] in the scenario's NED frame at the end of each step (the pose at ``t`` after initialisation),
and ``start_time`` (the scenario's POSIX start). Its resources hold the scenario, exported by
``seatwin cosim export`` as ``scenario.json`` (vessels, start, duration) and ``samples.csv`` (seconds
since the start, then north, east, heading per vessel), interpolated linearly (heading unwrapped),
as seatwin interpolates trajectories. Standard library only: it runs in any pythonfmu host.
"""

import bisect
import csv
import json
import os

from pythonfmu import Fmi2Causality, Fmi2Initial, Fmi2Slave, Fmi2Variability, Real


def _unwrap_deg(values):
    out, offset, prev = [], 0.0, None
    for v in values:
        if prev is not None:
            d = v - prev
            if d > 180.0:
                offset -= 360.0
            elif d < -180.0:
                offset += 360.0
        out.append(v + offset)
        prev = v
    return out


class ScenarioPlayer(Fmi2Slave):
    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.author = "seatwin"
        self.description = "Plays a scenario: every vessel's north, east [m] and heading [deg] per step (NED)."
        with open(os.path.join(self.resources, "scenario.json"), encoding="utf-8") as f:
            meta = json.load(f)
        self.vessels = list(meta["vessels"])
        self.start_time = float(meta["start"])
        self.duration = float(meta["duration"])
        with open(os.path.join(self.resources, "samples.csv"), encoding="utf-8", newline="") as f:
            rows = [[float(x) for x in r] for r in list(csv.reader(f))[1:]]
        self._t = [r[0] for r in rows]
        self._cols = [[r[1 + k] for r in rows] for k in range(3 * len(self.vessels))]
        for i in range(len(self.vessels)):
            self._cols[3 * i + 2] = _unwrap_deg(self._cols[3 * i + 2])
        self._pose = [0.0] * (3 * len(self.vessels))
        self._at(0.0)
        # Every output is known exactly before initialisation (the embedded scenario at t = 0), so each is
        # initial="exact" with that start value, and ModelStructure needs no InitialUnknowns (FMI 2.0 §2.2.8).
        # The start time is a constant of the embedded scenario.
        self.register_variable(
            Real(
                "start_time",
                causality=Fmi2Causality.output,
                variability=Fmi2Variability.constant,
                initial=Fmi2Initial.exact,
                getter=lambda: self.start_time,
            )
        )
        for i, name in enumerate(self.vessels):
            for j, q in enumerate(("north", "east", "heading")):
                k = 3 * i + j
                var = Real(f"{name}.{q}", causality=Fmi2Causality.output, initial=Fmi2Initial.exact)
                var.getter = lambda k=k: self._pose[k]
                self.register_variable(var)

    def _at(self, t):
        ts = self._t
        t = min(max(t, ts[0]), ts[-1])
        i = max(1, min(len(ts) - 1, bisect.bisect_right(ts, t)))
        w = (t - ts[i - 1]) / (ts[i] - ts[i - 1])
        for k, col in enumerate(self._cols):
            v = col[i - 1] + w * (col[i] - col[i - 1])
            self._pose[k] = v % 360.0 if k % 3 == 2 else v

    def exit_initialization_mode(self):
        self._at(0.0)

    def do_step(self, current_time, step_size):
        self._at(current_time + step_size)
        return True
