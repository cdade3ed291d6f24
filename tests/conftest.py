"""Shared test fixtures and markers.

Markers (``pyproject.toml``): ``slow`` — over about a second, or end to end on ``../shared/data``;
``make test-fast`` (``pytest -m "not slow"``) leaves them out. ``shared_data`` — set here on
every test that uses the :func:`shared_data` fixture (``-m "not shared_data"`` leaves them out).
"""

from __future__ import annotations

from pathlib import Path

import pytest

SHARED = Path(__file__).resolve().parents[1].parent / "shared"
SHARED_DATA = SHARED / "data"


@pytest.fixture
def shared_data() -> Path:
    """``../shared/data`` (real recordings); skips the test when it is absent."""
    if not SHARED_DATA.is_dir():
        pytest.skip(f"real data not available: {SHARED_DATA} is absent (tests that read ../shared/data skip)")
    return SHARED_DATA


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark every test that uses the ``shared_data`` fixture ``shared_data``."""
    for item in items:
        if "shared_data" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.shared_data)


@pytest.fixture(scope="module")
def camera_rig() -> tuple:
    """The ferry crossing's scene, the default camera, its CameraInfo fields and a renderer (ownship not drawn)."""
    from seatwin.render import SceneRenderer
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sensors.camera import CameraConfig, camera_info_fields
    from seatwin.world.scene import Scene

    sc = builtin_scenario("ferry_crossing")
    scene = Scene.from_scenario(sc)
    cfg = CameraConfig()
    info = camera_info_fields(cfg)
    return sc, scene, cfg, info, SceneRenderer(scene, info.k, cfg.width, cfg.height, exclude=[sc.ownship.name])


def _standard_count(bag: Path) -> int:
    """Messages in ``bag`` (a rosbag2 folder or a ROS 1 .bag) as rosbags' ``AnyReader`` reads them; for MCAP
    the ``mcap`` reader must find the same count in the file's summary (a finished file)."""
    from rosbags.highlevel import AnyReader

    with AnyReader([Path(bag)]) as reader:
        n = sum(1 for _ in reader.messages())
    for mcap_file in Path(bag).glob("*.mcap") if Path(bag).is_dir() else ():
        from mcap.reader import make_reader

        with mcap_file.open("rb") as f:
            summary = make_reader(f).get_summary()
        assert summary is not None and summary.statistics is not None, f"{mcap_file}: no summary"
        assert summary.statistics.message_count == n
    return n


@pytest.fixture
def standard_readers():
    """``count(bag) -> int``: open a bag with the standard readers (rosbags ``AnyReader``; ``mcap``'s summary)."""
    return _standard_count
