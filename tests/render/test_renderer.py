"""The EGL renderer: projection, the scene it draws (sky, sea, vessels), depth, determinism, a missing EGL."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.errors import InputError
from seatwin.render import DEBIAN_PACKAGES, SceneRenderer, projection_matrix, sun_direction
from seatwin.sensors.camera import rig_mounts


@pytest.fixture(scope="module")
def setup(camera_rig: tuple) -> tuple:
    return camera_rig


def test_projection_matrix_maps_pixels_like_k() -> None:
    k = np.array([[350.0, 0.0, 305.5], [0.0, 350.0, 255.5], [0.0, 0.0, 1.0]])
    p = projection_matrix(k, 612, 512, 0.08, 10_000.0)
    pt = np.array([3.0, -2.0, 40.0, 1.0])
    clip = p @ pt
    ndc = clip[:3] / clip[3]
    u = (ndc[0] + 1) / 2 * 612 - 0.5  # window → OpenCV pixel (centres at integers)
    v = (ndc[1] + 1) / 2 * 512 - 0.5
    assert u == pytest.approx(350 * 3 / 40 + 305.5)
    assert v == pytest.approx(350 * -2 / 40 + 255.5)
    near = p @ np.array([0, 0, 0.08, 1.0])
    far = p @ np.array([0, 0, 10_000.0, 1.0])
    assert near[2] / near[3] == pytest.approx(-1.0) and far[2] / far[3] == pytest.approx(1.0)


def test_sun_direction_hand_values() -> None:
    np.testing.assert_allclose(sun_direction(90.0, 30.0), [0.0, math.cos(math.radians(30)), -0.5], atol=1e-12)


def test_sky_above_sea_below_and_vessel_ids(setup: tuple) -> None:
    sc, scene, cfg, info, r = setup
    t = sc.start + 40.0
    p = scene.pose(sc.ownship.name, t)
    m = {x.name: x for x in rig_mounts(cfg)}["right"]
    rot, c = m.world_pose(float(p.north), float(p.east), float(p.heading))
    f = r.render(t, rot, c, solo=["Havfruen"])
    assert f.bgr.shape == (512, 612, 3) and f.bgr.dtype == np.uint8
    # bottom rows look down at the sea (15° pitch, 72° VFOV), the top row at the sky: both background
    assert (f.ids[-1] == -1).all() and (f.ids[0] == -1).all()
    sky, sea = f.bgr[0].astype(int), f.bgr[-1].astype(int)
    assert sky[:, 0].mean() > sky[:, 2].mean()  # BGR: the sky is blue
    assert sea.mean() < sky.mean()  # the sea below is darker than the sky
    hv = scene.vessel_ids["Havfruen"]
    assert (f.ids == hv).sum() == f.unoccluded["Havfruen"] > 100  # alone in the view: nothing hides it
    assert sc.ownship.name not in [scene.objects[i].name for i in np.unique(f.ids) if i >= 0]


def _one_frame(r: SceneRenderer, sc, scene, cfg):
    t = sc.start + 40.0
    p = scene.pose(sc.ownship.name, t)
    m = {x.name: x for x in rig_mounts(cfg)}["right"]
    return r.render(t, *m.world_pose(float(p.north), float(p.east), float(p.heading)))


def _on_a_new_thread(fn):  # noqa: ANN001, ANN202
    """``fn()`` on a thread of its own, so with an EGL context of its own (one per thread)."""
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(1) as pool:
        return pool.submit(fn).result()


def test_gl_objects_are_freed_with_their_renderer(setup: tuple) -> None:
    import gc

    from seatwin.render import release_collected

    sc, scene, cfg, info, _ = setup

    def build_drop_and_release() -> tuple[int, int]:
        r = SceneRenderer(scene, info.k, 64, 48, exclude=[sc.ownship.name])
        ctx, r.self_cycle = r.ctx, r  # only the collector can free it
        del r
        gc.collect()
        return release_collected(ctx), release_collected(ctx)

    first, second = _on_a_new_thread(build_drop_and_release)
    assert first > 10 and second == 0  # programs, buffers, vertex arrays, textures, framebuffers; then none


def test_garbage_collected_on_another_thread_leaves_its_gl_objects_alone(setup: tuple) -> None:
    """Regression (CI, 2026-11-26): a renderer collected by Python on a gRPC worker thread released its
    GL objects in *that* thread's context, deleting the worker renderer's same-numbered buffers (zero ids)."""
    import gc

    sc, scene, cfg, info, reference = setup
    expected = _one_frame(reference, sc, scene, cfg)

    def build() -> SceneRenderer:
        return SceneRenderer(scene, info.k, cfg.width, cfg.height, exclude=[sc.ownship.name])

    dropped = _on_a_new_thread(build)  # a fresh context: its object numbers match the next one's
    dropped.self_cycle = dropped
    del dropped

    def build_collect_render():  # noqa: ANN202
        r = build()
        gc.collect()  # the other thread's garbage, collected here
        return _one_frame(r, sc, scene, cfg)

    got = _on_a_new_thread(build_collect_render)
    np.testing.assert_array_equal(got.ids, expected.ids)
    np.testing.assert_array_equal(got.bgr, expected.bgr)


def test_rendering_is_deterministic(setup: tuple) -> None:
    sc, scene, cfg, info, r = setup
    t = sc.start + 12.3
    p = scene.pose(sc.ownship.name, t)
    rot, c = rig_mounts(cfg)[1].world_pose(float(p.north), float(p.east), float(p.heading))
    a, b = r.render(t, rot, c), r.render(t, rot, c)
    assert a.bgr.tobytes() == b.bgr.tobytes() and (a.ids == b.ids).all()


def test_a_missing_egl_names_the_debian_packages(monkeypatch: pytest.MonkeyPatch) -> None:
    import moderngl

    from seatwin.render import context

    def fail(*a: object, **k: object) -> None:
        raise Exception("libEGL.so: cannot open shared object file")  # noqa: TRY002 - what glcontext raises

    monkeypatch.setattr(moderngl, "create_context", fail)
    with pytest.raises(InputError) as exc:
        context.create_context(shared=False)
    msg = str(exc.value)
    assert DEBIAN_PACKAGES in msg and "\n" not in msg and "libEGL" in msg


def test_missing_egl_on_the_cli_exits_2(monkeypatch: pytest.MonkeyPatch, tmp_path, capsys) -> None:  # noqa: ANN001
    from seatwin.cli.main import run
    from seatwin.render import context

    def fail(shared: bool = True) -> None:
        raise InputError("EGL", f"cannot create a headless OpenGL context; install the Debian packages {DEBIAN_PACKAGES}")

    monkeypatch.setattr(context, "create_context", fail)
    import seatwin.render.renderer as rr

    monkeypatch.setattr(rr, "create_context", fail)
    assert run(["camera", "snapshot", "ferry_crossing", "-o", str(tmp_path / "s")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and DEBIAN_PACKAGES in err[0]


def test_gpu_distortion_matches_the_cpu_reference(setup: tuple) -> None:
    from seatwin.sensors.camera import DistortionMap
    from seatwin.sensors.camera.intrinsics import source_pixels

    sc, scene, cfg, info, _ = setup
    r = SceneRenderer(scene, info.k, cfg.width, cfg.height, exclude=[sc.ownship.name])
    t = sc.start + 40.0
    p = scene.pose(sc.ownship.name, t)
    rot, c = rig_mounts(cfg)[2].world_pose(float(p.north), float(p.east), float(p.heading))
    pinhole = r.render(t, rot, c)
    d = (-0.25, 0.08, 0.001, -0.002, 0.0)
    r.set_distortion(*source_pixels(info.k, d, cfg.width, cfg.height))
    gpu = r.render(t, rot, c)
    cpu = DistortionMap.build(info.k, d, cfg.width, cfg.height).apply(pinhole.bgr)
    diff = np.abs(gpu.bgr.astype(int) - cpu.astype(int))
    assert np.percentile(diff, 99) <= 3 and diff.mean() < 0.6
    assert not (gpu.bgr == pinhole.bgr).all()
    assert (gpu.ids == pinhole.ids).all()  # the id image stays the pinhole one
    r.set_distortion(None)
    assert r.render(t, rot, c).bgr.tobytes() == pinhole.bgr.tobytes()
    r.release()
