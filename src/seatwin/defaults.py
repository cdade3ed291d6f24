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

Compression = Literal["zstd", "zstd-file", "lz4", "bz2", "none"]
COMPRESSIONS: dict[str, tuple[str, ...]] = {
    "mcap": ("lz4", "zstd", "none"),
    "sqlite3": ("none", "zstd", "zstd-file"),
    "ros1": ("lz4", "bz2", "none"),
}
"""Bag format → the compressions seatwin writes, its default first: MCAP chunks (lz4, zstd), ROS 1 chunks (lz4,
bz2; what ``rosbag record --lz4|--bz2`` writes), SQLite3 rosbag2's own zstd compression (``zstd``: each message,
``ros2 bag record --compression-mode message --compression-format zstd``; ``zstd-file``: the whole ``.db3`` once
it is closed, ``--compression-mode file``; none by default, as rosbag2's). lz4 is MCAP's default because it meets
both size and speed (the 30 s default run 75 MB at +6 % CPU over no compression, on a quiet 16-core host); zstd
makes it 49 MB at +21 % CPU (docs/validation.md, "Bag size")."""
DEFAULT_COMPRESSION: dict[str, str] = {fmt: names[0] for fmt, names in COMPRESSIONS.items()}
"""The compression a bag gets when none is asked for: lz4 (MCAP, ROS 1), none (SQLite3)."""
ZSTD_LEVEL = 1
"""zstd level of compressed MCAP chunks: zstd's fastest regular level (rosbag2's ``zstd_fast`` preset), ~9× on
seatwin's raw camera images at ~2 ms an image (level 3: ~10×, ~40 % more time; docs/validation.md)."""

ImageFormat = Literal["raw", "jpeg", "png"]
IMAGE_FORMATS: tuple[str, ...] = ("raw", "jpeg", "png")
"""Camera images as ``sensor_msgs/Image`` (raw, the thesis's bgr8) or ``sensor_msgs/CompressedImage`` (jpeg, png)
on ``<image topic>/compressed`` (image_transport's convention)."""
DEFAULT_IMAGE_FORMAT: ImageFormat = "raw"
"""Raw bgr8, as the thesis records: with lz4 chunks the default run is already below 80 MB."""
JPEG_QUALITY = 90
"""Pillow's JPEG quality for ``--image-format jpeg``, fixed (Pillow's default is 75)."""
