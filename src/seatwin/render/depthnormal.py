"""Depth and surface normals of the scene, rasterised for the depth-buffer lidar (thesis 4.1).

The same scene and meshes as :class:`~seatwin.render.renderer.SceneRenderer` (static harbour in
the world frame, vessels in their body frames posed by a model matrix at the render time), drawn
by OpenGL (moderngl, headless EGL) with a caller-given clip-from-world matrix — the depth-buffer
lidar passes the thesis's projection 4.5 so that framebuffer pixel ``(i, j)`` *is* the thesis's
discrete pixel ``(x^d, y^d)`` (4.8 is GL's viewport transform) and the window depth is
``z^d / N_c,d``. Two targets: a 24-bit depth texture and an RGBA32F texture holding each
pixel's flat (face) normal in the world frame and its object id (−1: nothing).

Nothing below the waterline is drawn (fragments with z > 0 are discarded): the lidar's rays are
cut at the calm water, which gives no return, and a ray from above crosses z = 0 once.

Only the pixels a caller asks for are read back: :meth:`DepthNormalRenderer.sample` runs a
gather pass that copies the depth, normal and id of a list of pixels into a small target.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.render.context import create_context, release_collected
from seatwin.render.renderer import SceneRenderer, _flat_vertices

_VS = """
#version 330
uniform mat4 clip_from_world;
uniform mat4 model;
uniform vec4 view_axis;   // (a, d): the view depth of world point w is dot(a, w) + d
in vec3 in_pos;
in vec3 in_normal;
in float in_id;
out vec3 v_world;
out float v_depth;
flat out vec3 v_normal;
flat out float v_id;
void main() {
    vec4 w = model * vec4(in_pos, 1.0);
    v_world = w.xyz;
    v_depth = dot(view_axis.xyz, w.xyz) + view_axis.w;
    v_normal = mat3(model) * in_normal;
    v_id = in_id;
    gl_Position = clip_from_world * w;
}
"""

_FS = """
#version 330
in vec3 v_world;
in float v_depth;
flat in vec3 v_normal;
flat in float v_id;
layout(location = 0) out vec4 f_normal_id;
layout(location = 1) out float f_depth;
void main() {
    if (v_world.z > 0.0) discard;   // below the calm water: the lidar's rays never get there
    f_normal_id = vec4(v_normal, v_id);
    f_depth = v_depth;
}
"""

_QUAD_VS = """
#version 330
in vec2 in_vert;
void main() { gl_Position = vec4(in_vert, 0.0, 1.0); }
"""

_GATHER_FS = """
#version 330
uniform isampler2D pixels;     // per output texel: the framebuffer pixel to copy
uniform sampler2D depth;
uniform sampler2D normal_id;
uniform sampler2D linear;
layout(location = 0) out vec4 o_normal_id;
layout(location = 1) out vec2 o_depth;
void main() {
    ivec2 p = texelFetch(pixels, ivec2(gl_FragCoord.xy), 0).xy;
    o_normal_id = texelFetch(normal_id, p, 0);
    o_depth = vec2(texelFetch(depth, p, 0).r, texelFetch(linear, p, 0).r);
}
"""

_CALIBRATE_FS = """
#version 330
layout(location = 0) out vec4 f_normal_id;
layout(location = 1) out float f_depth;
void main() {
    gl_FragDepth = 0.5 + gl_FragCoord.x / 512.0;   // window depths 0.5 … 1 across 256 pixels
    f_normal_id = vec4(0.0, 0.0, 0.0, -1.0);
    f_depth = 0.0;
}
"""

_GATHER_WIDTH = 4096


@dataclass(frozen=True)
class PixelSamples:
    """Per requested pixel: what the depth-buffer lidar reads."""

    window: NDArray[np.float64]
    """Window depth ``z^d / N_c,d`` ∈ [0, 1] from the 24-bit depth buffer (1: nothing drawn)."""
    linear: NDArray[np.float64]
    """View depth ``−z^v`` [m] as a float32 target holds it (0 where nothing was drawn)."""
    normal: NDArray[np.float32]
    """World-frame unit (face) normal."""
    object_id: NDArray[np.int32]
    """−1 where nothing was drawn."""


_CALIBRATION_PIXELS = 256


class DepthNormalRenderer:
    """Rasterises ``scene`` into a ``width × height`` depth buffer plus normal/id image.

    ``exclude``: vessels never drawn (the sensor's carrier).
    """

    def __init__(self, scene: Any, width: int, height: int, *, exclude: Sequence[str] = (), ctx: Any = None):
        if width < 1 or height < 1:
            raise InputError("depth buffer", f"image size must be positive, got {width}×{height}")
        self.scene, self.width, self.height = scene, int(width), int(height)
        self.exclude = set(exclude)
        self.ctx = ctx if ctx is not None else create_context()
        release_collected(self.ctx)
        limit = int(self.ctx.info.get("GL_MAX_TEXTURE_SIZE", 16384))
        if max(self.width, self.height) > limit:
            raise InputError("depth buffer", f"{self.width}×{self.height} exceeds the GL limit of {limit} pixels per side")
        ctx = self.ctx
        self.prog = ctx.program(vertex_shader=_VS, fragment_shader=_FS)
        fmt = ("3f 3f 1f", "in_pos", "in_normal", "in_id")

        def upload(vertices: NDArray[np.float32], faces: NDArray[np.int32], oid: int) -> Any:
            rec = np.frombuffer(_flat_vertices(vertices, faces, np.zeros(3, np.float32), oid), np.float32).reshape(-1, 10)
            vbo = ctx.buffer(np.ascontiguousarray(rec[:, [0, 1, 2, 3, 4, 5, 9]]).tobytes())
            return vbo, ctx.vertex_array(self.prog, [(vbo, *fmt)])

        self._static = [upload(m.vertices, m.faces, m.object_id) for m in scene.static_meshes if len(m.faces)]
        self._vessels: dict[str, tuple[Any, Any]] = {}
        for name in scene.vessel_names:
            if name not in self.exclude:
                m = scene.vessel_models[name].mesh
                self._vessels[name] = upload(
                    np.asarray(m.vertices, np.float32), np.asarray(m.faces, np.int32), scene.vessel_ids[name]
                )
        size = (self.width, self.height)
        self._normal_id = ctx.texture(size, 4, dtype="f4")
        self._linear = ctx.texture(size, 1, dtype="f4")
        self._depth = ctx.depth_texture(size)  # GL_DEPTH_COMPONENT24
        self._depth.compare_func = ""  # read values, not shadow comparisons
        for tex in (self._normal_id, self._linear, self._depth):
            tex.repeat_x = tex.repeat_y = False
        self.fbo = ctx.framebuffer(color_attachments=[self._normal_id, self._linear], depth_attachment=self._depth)
        self._gather = ctx.program(vertex_shader=_QUAD_VS, fragment_shader=_GATHER_FS)
        for unit, name in enumerate(("pixels", "depth", "normal_id", "linear")):
            self._gather[name].value = unit
        self._quad_vbo = ctx.buffer(np.array([-1.0, -1.0, 3.0, -1.0, -1.0, 3.0], np.float32).tobytes())
        self._quad = ctx.vertex_array(self._gather, [(self._quad_vbo, "2f", "in_vert")])
        self.renders = 0
        self.depth_read_scale = 1.0
        self.depth_read_scale = self._calibrate()

    def _calibrate(self) -> float:
        """How the driver reads back the depth it stored: ``read = scale · stored``.

        Mesa's llvmpipe stores a 24-bit depth ``d`` as ``round(d · 2^24)`` but reads level ``k`` as
        ``k / (2^24 − 1)``: one level too far near the far plane. Known window depths are written
        (``gl_FragDepth``, the rasteriser's own store) and read back; the mean offset, in levels per
        unit depth, is 1 for that driver and 0 for one that stores and reads alike.
        """
        import moderngl

        ctx = self.ctx
        prog = ctx.program(vertex_shader=_QUAD_VS, fragment_shader=_CALIBRATE_FS)
        vao = ctx.vertex_array(prog, [(self._quad_vbo, "2f", "in_vert")])
        try:
            self.fbo.use()
            ctx.viewport = (0, 0, min(_CALIBRATION_PIXELS, self.width), 1)
            ctx.enable(moderngl.DEPTH_TEST)
            ctx.depth_func = "1"
            vao.render(moderngl.TRIANGLES)
            ctx.depth_func = "<"
        finally:
            vao.release()
            prog.release()
        x = np.arange(min(_CALIBRATION_PIXELS, self.width))
        read = self.sample(x, np.zeros_like(x)).window
        stored = 0.5 + (x + 0.5) / 512.0
        levels = float(np.mean((read - stored) / stored)) * 2.0**24
        return 2.0**24 / (2.0**24 - 1.0) if levels > 0.5 else 1.0

    vessel_model = SceneRenderer.vessel_model  # the camera renderer's posing: world-from-body at t, None outside the track

    @staticmethod
    def _mat(prog: Any, name: str, m: NDArray[np.float64]) -> None:
        prog[name].write(np.ascontiguousarray(np.asarray(m, np.float32).T).tobytes())

    def render(self, clip_from_world: ArrayLike, t: float, view_axis: ArrayLike = (0.0, 0.0, 0.0, 0.0)) -> None:
        """Draw the scene at time ``t`` through the 4×4 ``clip_from_world`` matrix (OpenGL clip space).

        ``view_axis`` = ``(a, d)``: the linear depth stored besides the depth buffer is ``a·w + d``
        for world point ``w`` (the camera's forward axis and ``−a·centre``), in float32.
        """
        import moderngl

        ctx = self.ctx
        release_collected(ctx)
        self.fbo.use()
        ctx.viewport = (0, 0, self.width, self.height)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.CULL_FACE)
        ctx.depth_func = "<"
        self.fbo.clear(0.0, 0.0, 0.0, -1.0, depth=1.0)
        self._mat(self.prog, "clip_from_world", np.asarray(clip_from_world, float))
        self.prog["view_axis"].value = tuple(float(v) for v in np.asarray(view_axis, float))
        self._mat(self.prog, "model", np.eye(4))
        for _, vao in self._static:
            vao.render(moderngl.TRIANGLES)
        for name, (_, vao) in self._vessels.items():
            m = self.vessel_model(name, t)
            if m is not None:
                self._mat(self.prog, "model", m)
                vao.render(moderngl.TRIANGLES)
        self.renders += 1

    def sample(self, x: ArrayLike, y: ArrayLike) -> PixelSamples:
        """What the last :meth:`render` holds at framebuffer pixels ``(x, y)`` (column, row from the bottom)."""
        import moderngl

        xi = np.asarray(x, np.int64).reshape(-1)
        yi = np.asarray(y, np.int64).reshape(-1)
        n = xi.size
        if n == 0:
            return PixelSamples(np.zeros(0), np.zeros(0), np.zeros((0, 3), np.float32), np.zeros(0, np.int32))
        if xi.min() < 0 or yi.min() < 0 or xi.max() >= self.width or yi.max() >= self.height:
            raise ValueError("pixels outside the image")
        ctx = self.ctx
        w = min(n, _GATHER_WIDTH)
        h = math.ceil(n / w)
        coords = np.zeros((h * w, 2), np.int32)
        coords[:n, 0], coords[:n, 1] = xi, yi
        src = ctx.texture((w, h), 2, coords.tobytes(), dtype="i4")
        src.filter = (moderngl.NEAREST, moderngl.NEAREST)
        out_n = ctx.texture((w, h), 4, dtype="f4")
        out_d = ctx.texture((w, h), 2, dtype="f4")
        fbo = ctx.framebuffer(color_attachments=[out_n, out_d])
        try:
            fbo.use()
            ctx.viewport = (0, 0, w, h)
            ctx.disable(moderngl.DEPTH_TEST)
            src.use(0)
            self._depth.use(1)
            self._normal_id.use(2)
            self._linear.use(3)
            self._quad.render(moderngl.TRIANGLES)
            nid = np.frombuffer(fbo.read(components=4, attachment=0, dtype="f4", alignment=1), np.float32).reshape(-1, 4)[:n]
            dep = np.frombuffer(fbo.read(components=2, attachment=1, dtype="f4", alignment=1), np.float32).reshape(-1, 2)[:n]
        finally:
            ctx.enable(moderngl.DEPTH_TEST)
            for obj in (fbo, out_n, out_d, src):
                obj.release()
        window = dep[:, 0].astype(np.float64)
        return PixelSamples(
            np.where(window < 1.0, window / self.depth_read_scale, 1.0),
            dep[:, 1].astype(np.float64),
            np.ascontiguousarray(nid[:, :3]),
            np.rint(nid[:, 3]).astype(np.int32),
        )

    def release(self) -> None:
        """Free this renderer's GL objects (the shared context stays)."""
        for vbo, vao in self._static + list(self._vessels.values()):
            vao.release()
            vbo.release()
        for obj in (self.fbo, self._normal_id, self._linear, self._depth, self._quad, self._quad_vbo, self._gather, self.prog):
            obj.release()
