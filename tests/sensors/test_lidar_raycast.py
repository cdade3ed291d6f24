"""The ``raycast`` range model's culling changes nothing: it equals brute force over every vessel."""

from __future__ import annotations

import numpy as np

from seatwin.scenario.model import Trajectory
from seatwin.sensors.lidar import Lidar
from seatwin.sensors.lidar_config import MILLIAMPERE_LIDAR_MOUNT, VLP16
from seatwin.sensors.rangemodel import raycast_ranges
from seatwin.world.harbour import harbour_from_layout
from seatwin.world.scene import Scene
from seatwin.world.vessels import finn, havfruen, milliampere

T0 = 1.6e9


def zigzag(n0, e0, vn, ve, turn) -> Trajectory:
    t = T0 + np.arange(0.0, 3.0, 0.1)
    k = np.arange(len(t))
    # Velocity flips every sample: a knot inside every sweep tests the motion bound.
    wob = np.where(k % 2 == 0, 0.0, 1.5)
    return Trajectory(t, n0 + vn * (t - T0) + wob, e0 + ve * (t - T0) - wob, turn * (t - T0))


def brute_force(scene: Scene, batch) -> tuple[np.ndarray, np.ndarray]:
    h = scene.static_caster.cast(batch.origins, batch.directions, batch.max_range)
    rng, oid = h.range.copy(), h.object_id.copy()
    t = batch.column_times[batch.column]
    for name in scene.vessel_names:
        if name in batch.exclude:
            continue
        p = scene.pose(name, t)
        c, s = np.cos(p.heading), np.sin(p.heading)
        rel_n, rel_e = batch.origins[:, 0] - p.north, batch.origins[:, 1] - p.east
        o = np.stack([c * rel_n + s * rel_e, -s * rel_n + c * rel_e, batch.origins[:, 2]], axis=1)
        d = batch.directions
        db = np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1], d[:, 2]], axis=1)
        vh = scene.vessel_caster(name).cast(o, db, batch.max_range)
        closer = vh.range < rng
        rng[closer], oid[closer] = vh.range[closer], vh.object_id[closer]
    return rng, oid


def test_culled_raycast_equals_brute_force() -> None:
    vessels = {
        "own": (milliampere(), zigzag(0.0, 0.0, 1.0, 0.5, 0.3)),
        "havfruen": (havfruen(), zigzag(12.0, 6.0, -4.0, 0.0, -0.5)),
        "finn": (finn(), zigzag(-8.0, -5.0, 3.0, 6.0, 1.0)),
        "far": (finn(), zigzag(300.0, 0.0, 0.0, 0.0, 0.0)),
    }
    scene = Scene(harbour_from_layout(), vessels)
    lid = Lidar(scene, VLP16.with_(drop_probability=0.5), MILLIAMPERE_LIDAR_MOUNT, platform="own")
    seen: set[int] = set()
    for k, start in enumerate(T0 + np.array([0.0, 0.35, 1.05, 2.2])):
        batch = lid.beams(float(start), k)
        res = raycast_ranges(scene, batch)
        rng, oid = brute_force(scene, batch)
        np.testing.assert_array_equal(res.object_id, oid)
        hit = oid >= 0
        np.testing.assert_allclose(res.range[hit], rng[hit], rtol=0, atol=2e-5)
        seen.update(np.unique(res.object_id).tolist())
    assert {scene.vessel_ids["havfruen"], scene.vessel_ids["finn"]} <= seen
