"""Depth buffers for sensor modelling (thesis 4.1): projection, spherical projection filter,
numerical error, and the depth-buffer lidar range model.

* :mod:`.projection` — the camera, 4.3–4.9 and the back-projection 4.37–4.42.
* :mod:`.filter` — the spherical projection filter ``M`` (4.10–4.19) and the legacy grid.
* :mod:`.errors` — the numerical error 4.20–4.36.
* :mod:`.table` — Table 4.1 recomputed, with its inconsistencies as warnings.
* :mod:`.model` — :class:`DepthBufferLidar`: per-beam depth-buffer points.
* :mod:`.lidar_range` — ``range_model(scene, batch)`` for ``Lidar(range_model="depthbuffer")``.
* :mod:`.plane` — a beam intersected with its pixel's surface plane, the edge test.
* :mod:`.plane_range` — ``plane_range_model`` for ``Lidar(range_model="depthbuffer-plane")``: the
  depth buffers rasterised by OpenGL (:mod:`seatwin.render.depthnormal`).
* :mod:`.verify` — part of the thesis's claim checked against exact ray casting (``seatwin errors --verify``).

The ray-casting and rendering parts (``range_model``, ``legacy_range_model``, ``plane_range_model``) load lazily, so the pure
math imports without the engine.
"""

from __future__ import annotations

from typing import Any

from seatwin.sensors.depthbuffer.model import DepthBufferConfig, DepthBufferHits, DepthBufferLidar
from seatwin.sensors.depthbuffer.projection import DepthCamera

__all__ = [
    "DepthBufferConfig",
    "DepthBufferHits",
    "DepthBufferLidar",
    "DepthCamera",
    "legacy_range_model",
    "plane_range_model",
    "range_model",
]


def __getattr__(name: str) -> Any:
    if name in ("range_model", "legacy_range_model", "make_range_model", "depthbuffer_ranges"):
        from seatwin.sensors.depthbuffer import lidar_range

        return getattr(lidar_range, name)
    if name in ("plane_range_model", "make_plane_range_model", "plane_ranges"):
        from seatwin.sensors.depthbuffer import plane_range

        return getattr(plane_range, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
