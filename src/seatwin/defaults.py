"""Defaults that the library and the command line share, in a module that imports nothing: the CLI shows
them in ``--help`` without loading the library (``tests/cli/test_startup.py``).

:mod:`seatwin.sim.settings` and :mod:`seatwin.recording.config` re-export them where they belong.
"""

from __future__ import annotations

from typing import Literal

DEFAULT_SENSORS: tuple[Literal["lidar", "radar", "camera"], ...] = ("lidar", "camera")
"""The ownship sensors every entry point records unless told otherwise (``simulate``, ``simulate_run``,
``serve``, ``cosim export|run``, CLI and library alike): the thesis's twin, the VLP-16 and the three cameras."""

RosDistro = Literal["humble", "iron", "jazzy", "kilted"]
ROS_DISTROS: dict[str, int] = {"humble": 5, "iron": 7, "jazzy": 9, "kilted": 9}
"""ROS 2 distribution → the rosbag2 metadata version its ``ros2 bag`` writes (``BagMetadata::version`` in
rosbag2's ``bag_metadata.hpp`` on each distro's branch; docs/architecture/recording.md has what each reads).
A bag is written in its distro's version."""
DEFAULT_ROS_DISTRO: RosDistro = "humble"
"""The oldest supported LTS: Humble reads no metadata of version 9 (its QoS lists), and every later distro reads 5."""
