"""Encounters placed at Ravnkloa's canal crossing (the real land raster): every path on water for the whole run,
refused draws counted, the grounding verdict live, and ``seatwin verify`` with ``harbour: ravnkloa``."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from seatwin.agents.interface import SetPoint
from seatwin.cli.main import run
from seatwin.encounters import encounter_scenario, place, space
from seatwin.encounters.place import ENCOUNTER_AREAS, NoPlacementError
from seatwin.layout import harbour_map
from seatwin.scenario.on_water import is_water_in
from seatwin.verification import judge, run_closed_loop

SHORT = (20.0, 35.0)
"""TCPA range [s] of encounters that fit the canal."""


@pytest.mark.parametrize("family", ["crossing_give_way", "crossing_stand_on", "head_on"])
def test_ravnkloa_encounters_sail_on_water_at_the_canal_crossing(shared_data, family):
    raster = harbour_map("ravnkloa")
    area = ENCOUNTER_AREAS["ravnkloa"]
    sp = space(family, tcpa=SHORT)
    rejected = []
    for seed in range(4):
        e = sp.encounter(np.random.default_rng(seed).random(sp.dimension))
        pl, p = place(e, "ravnkloa", seed, 0.0)
        for q in (p.ownship, *p.targets):
            assert is_water_in(raster, q.north, q.east).all()  # every 10 Hz sample, the whole scenario
        k = int(np.argmin(np.abs(p.ownship.time - e.targets[0].tcpa)))
        assert math.hypot(p.ownship.north[k] - area.north, p.ownship.east[k] - area.east) <= area.radius + 1.0
        assert place(e, "ravnkloa", seed, 0.0)[0] == pl  # deterministic, refusals included
        rejected.append(pl.rejected)
    assert sum(rejected) > 0  # draws with a path on land were refused and counted


def test_an_encounter_too_long_for_the_canal_is_refused_by_name(shared_data):
    e = space("multi").encounter([0.5, 0.5, 1.0, 0.5, 1.0, 0.5, 1.0, 0.5, 1.0])  # 100 s to the CPAs, fast targets
    with pytest.raises(NoPlacementError, match="no place on water.*ravnkloa|ravnkloa.*no place on water"):
        place(e, "ravnkloa", 0, 0.0, tries=200)


class ToLand:
    """Sails at 2.5 m/s for a point on Fosenkaia's quay (south-east of the crossing)."""

    name, sensors = "to_land", ("truth",)
    north, east = -150.0, 120.0

    def reset(self, mission):
        pass

    def step(self, time, frames, navigation):
        return SetPoint(2.5, math.atan2(self.east - navigation.east, self.north - navigation.north))

    def tracks(self):
        return []


def test_grounding_is_live_on_the_ravnkloa_raster(shared_data):
    raster = harbour_map("ravnkloa")
    assert not is_water_in(raster, np.array([ToLand.north]), np.array([ToLand.east]))[0]
    sp = space("crossing_give_way", tcpa=SHORT)
    scenario, _ = encounter_scenario(sp.encounter([0.5] * 5), "ground", "ravnkloa", 2)
    rec = run_closed_loop(scenario, ToLand())
    assert judge(rec, harbour_map("none")).passed  # open water: no grounding to find
    v = judge(rec, raster)
    assert v.grounding and not v.passed and any(r.startswith("grounding at") for r in v.reasons)


def test_seatwin_verify_in_ravnkloa_reports_placements(shared_data, tmp_path):
    spec = tmp_path / "v.yaml"
    spec.write_text(
        "agents: [perfect]\nfamilies: [crossing_give_way]\nencounters: 2\ntcpa: [20, 35]\nharbour: ravnkloa\nworst: 0\n"
    )
    out = tmp_path / "out"
    assert run(["verify", str(spec), "--out", str(out), "--workers", "0", "--no-progress"]) == 0
    rows = list(csv.DictReader((out / "results.csv").open()))
    assert len(rows) == 2 and all(r["placed"] == "True" and int(r["placement_rejected"]) >= 0 for r in rows)
    assert all(r["grounding"] in ("True", "False") for r in rows)
    placement = json.loads((out / "verify.json").read_text())["placement"]
    fam = placement["families"]["crossing_give_way"]
    assert placement["harbour"] == "ravnkloa" and fam["placed"] == 2 and fam["not_placed"] == 0
    assert fam["rejected_draws"] == sum(int(r["placement_rejected"]) for r in rows)
