"""Rasterising the world for the cameras: OpenGL through moderngl on a headless EGL context.

:class:`SceneRenderer` draws the lidar's :class:`~seatwin.world.scene.Scene` (same meshes, same
poses) with sky, sun-lit sea and a 24-bit depth buffer; :func:`create_context` gives one line
naming the Debian packages when EGL or GL is missing. See ``docs/architecture/camera.md``.
"""

from seatwin.render.context import DEBIAN_PACKAGES, create_context, release_collected, renderer_name
from seatwin.render.renderer import RenderedFrame, SceneRenderer, projection_matrix, sun_direction

__all__ = [
    "DEBIAN_PACKAGES",
    "RenderedFrame",
    "SceneRenderer",
    "create_context",
    "projection_matrix",
    "release_collected",
    "renderer_name",
    "sun_direction",
]
