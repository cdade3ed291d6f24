"""Lidar perception + tracking on simulated VLP-16 sweeps of a built-in scenario (seatwin.sensors)."""

from __future__ import annotations

import numpy as np

from seatwin.evaluation import Tracks, evaluate
from seatwin.evaluation.truth import truth_from_scenario
from seatwin.perception.frames import Mount, sensor_pose
from seatwin.perception.lidar import lidar_scan
from seatwin.perception.map_mask import LayoutMask
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sensors.lidar import lidar_for_scenario, sweep_starts
from seatwin.tracking import JIPDATracker, TrackTable, load_tuning


def test_tracks_simulated_lidar_targets() -> None:
    sc = builtin_scenario("ferry_crossing")
    lid = lidar_for_scenario(sc)
    sweeps = lid.sweeps(list(sweep_starts(sc)[:300:3]))  # 100 sweeps over 30 s
    mount = Mount(tuple(lid.mount.translation), lid.mount.rotation())
    tracker = JIPDATracker(load_tuning("synthetic"))
    parts = []
    for s in sweeps:
        p = lid.scene.pose(lid.platform, np.array([s.stamp]))
        pose = sensor_pose(float(p.north[0]), float(p.east[0]), float(p.heading[0]), mount)
        parts.append(tracker.step(lidar_scan(s.xyz.astype(float), s.stamp, pose, LayoutMask())))
    tab = TrackTable.concatenate(parts)
    tracks = Tracks(
        tab.time, tab.track_id, tab.existence, tab.x, tab.P, tab.confirmed, scan_times=np.array([s.stamp for s in sweeps])
    )
    ev = evaluate(tracks, truth_from_scenario(sc), gate=10.0)
    ids = {o.name: i for i, o in enumerate(lid.scene.objects)}
    summaries = {s.target: s for s in ev.summaries}
    assert set(summaries) == {"Havfruen", "Finn"}  # every target but the ownship
    # Fraction of sweeps in which the lidar sees a target (at least 3 returns off it).
    seen = {name: np.mean([np.count_nonzero(s.object_id == ids[name]) >= 3 for s in sweeps]) for name in summaries}
    # In these 30 s Havfruen crosses the lidar's view for about a third of the sweeps; Finn stays out of it.
    assert seen["Havfruen"] >= 0.3 and seen["Finn"] == 0.0, seen
    havfruen = summaries["Havfruen"]
    assert havfruen.n_instants == len(sweeps)
    # tracked (nearly) whenever the lidar sees it, by one track, and accurately
    assert havfruen.coverage >= 0.8 * seen["Havfruen"] - 0.05, (havfruen.coverage, seen)
    assert havfruen.n_valid >= 20
    assert havfruen.track_switches == 0 and len(havfruen.track_ids) == 1, havfruen.track_ids
    assert havfruen.rmse_position < 2.0
    # a target the lidar never sees is never tracked (no clutter track wanders onto it)
    assert summaries["Finn"].n_valid == 0 and summaries["Finn"].coverage == 0.0
