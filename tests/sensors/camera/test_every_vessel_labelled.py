"""Every vessel a camera sees — moving or moored — has a label, checked with a projection written here.

The camera's pinhole and pose are written out in this test (not taken from the label code): focal length
from the horizontal field of view, the rig's azimuth and downward pitch, the mount height. A vessel counts as
seen when at least half of its projected box lies inside the image and the rendered object-id image shows it
(≥ 20 pixels, and at least half of the pixels it covers drawn alone: not occluded).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.layout import DEFAULT_LAYOUT
from seatwin.sensors.camera import ground_truth_boxes, rig_mounts


def _camera(cfg, psi: float, az_deg: float, north: float, east: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(K, optical → world rotation, centre) written from the camera's specification."""
    f = (cfg.width / 2) / math.tan(math.radians(cfg.hfov_deg) / 2)
    k = np.array([[f, 0, (cfg.width - 1) / 2], [0, f, (cfg.height - 1) / 2], [0, 0, 1.0]])
    b, p = psi + math.radians(az_deg), math.radians(cfg.pitch_down_deg)
    z = np.array([math.cos(b) * math.cos(p), math.sin(b) * math.cos(p), math.sin(p)])  # optical axis (NED, down +)
    x = np.array([-math.sin(b), math.cos(b), 0.0])  # image right
    rot = np.column_stack([x, np.cross(z, x), z])
    return k, rot, np.array([north, east, -cfg.height_m])


def _box_inside_fraction(corners: np.ndarray, k: np.ndarray, rot: np.ndarray, c: np.ndarray, w: int, h: int) -> float:
    cam = (corners - c) @ rot
    if (cam[:, 2] <= 0.1).any():
        return 0.0
    uv = (cam @ k.T)[:, :2] / cam[:, 2:3]
    x0, y0 = uv.min(axis=0)
    x1, y1 = uv.max(axis=0)
    area = (x1 - x0) * (y1 - y0)
    ix = max(0.0, min(x1, w - 0.5) - max(x0, -0.5))
    iy = max(0.0, min(y1, h - 0.5) - max(y0, -0.5))
    return ix * iy / area if area > 0 else 0.0


def _corners(north: float, east: float, heading: float, length: float, beam: float, height: float) -> np.ndarray:
    ca, sa = math.cos(heading), math.sin(heading)
    out = []
    for a in (-0.5, 0.5):
        for s in (-0.5, 0.5):
            dn, de = a * length * ca - s * beam * sa, a * length * sa + s * beam * ca
            out += [(north + dn, east + de, 0.0), (north + dn, east + de, -height)]
    return np.asarray(out)


@pytest.mark.slow
def test_every_visible_vessel_moving_or_moored_has_a_label(camera_rig: tuple) -> None:
    sc, scene, cfg, info, r = camera_rig
    own = sc.ownship.name
    moored = {m.name: m for m in DEFAULT_LAYOUT.moored_boats}
    assert set(scene.moored_boats) == set(moored)
    seen_moored, seen_moving, checked = set(), set(), 0
    for t in np.arange(sc.start, sc.end, 8.0):
        st = sc.ownship.trajectory.state_at(float(t))
        n0, e0, psi = float(st.north), float(st.east), float(st.heading)
        for mount in rig_mounts(cfg):
            k, rot, c = _camera(cfg, psi, mount.azimuth_deg, n0, e0)
            wanted = {}
            for v in sc.vessels:
                if v.name == own or not (v.trajectory.start <= t <= v.trajectory.end):
                    continue
                s = v.trajectory.state_at(float(t))
                m = scene.vessel_models[v.name]
                wanted[v.name] = _corners(float(s.north), float(s.east), float(s.heading), m.length, m.beam, m.height)
            for name, b in moored.items():
                wanted[name] = _corners(b.north, b.east, math.radians(b.heading_deg), b.length, b.beam, b.height)
            # The renderer's pose of the camera is the rig's; the test's own pose must agree with it.
            rot_rig, c_rig = mount.world_pose(n0, e0, psi)
            np.testing.assert_allclose(rot_rig, rot, atol=1e-9)
            np.testing.assert_allclose(c_rig, c, atol=1e-6)
            frame = r.render(float(t), rot, c, solo=[n for n in wanted])
            labels = {
                b.instance
                for b in ground_truth_boxes(
                    scene, float(t), rot, c, k, None, cfg.width, cfg.height, frame.ids, frame.unoccluded, exclude=(own,)
                )
            }
            ids = {o.name: o.id for o in scene.objects}
            for name, corners in wanted.items():
                pixels = int((frame.ids == ids[name]).sum())
                alone = frame.unoccluded.get(name, 0)
                if _box_inside_fraction(corners, k, rot, c, cfg.width, cfg.height) < 0.5 or pixels < 20 or pixels < 0.5 * alone:
                    continue
                assert name in labels, f"{name} is seen by the {mount.name} camera at t = {t - sc.start:.0f} s but not labelled"
                (seen_moored if name in moored else seen_moving).add(name)
                checked += 1
    assert seen_moving and len(seen_moored) >= 2 and checked >= 10  # the check is not empty


@pytest.mark.parametrize("camera", ["left"])
def test_the_moored_boat_in_the_left_camera_is_labelled_with_its_box(camera_rig: tuple, camera: str) -> None:
    """The issue's case: at the start of the ferry crossing a moored boat is in the left camera."""
    sc, scene, cfg, info, r = camera_rig
    own = sc.ownship.name
    mount = next(m for m in rig_mounts(cfg) if m.name == camera)
    for t in np.arange(sc.start, sc.end, 4.0):
        st = sc.ownship.trajectory.state_at(float(t))
        rot, c = mount.world_pose(float(st.north), float(st.east), float(st.heading))
        frame = r.render(float(t), rot, c, solo=list(scene.moored_boats))
        boxes = ground_truth_boxes(
            scene, float(t), rot, c, info.k, None, cfg.width, cfg.height, frame.ids, frame.unoccluded, exclude=(own,)
        )
        moored = [b for b in boxes if b.instance in scene.moored_boats]
        if moored:
            b = moored[0]
            ys, xs = np.nonzero(frame.ids == b.object_id)
            assert b.label == "vessel" and b.visible_pixels == len(xs) > 0
            assert xs.min() >= b.x_min - 1 and xs.max() <= b.x_max + 1 and ys.min() >= b.y_min - 1 and ys.max() <= b.y_max + 1
            assert 0.0 < b.visible_fraction <= 1.0
            return
    pytest.fail("no moored boat labelled in the left camera over the whole scenario")
