"""The camera renderer: the lidar's :class:`~seatwin.world.scene.Scene` rasterised by OpenGL (moderngl, EGL).

One scene, shared with the lidar: the static harbour meshes are uploaded once in the world
frame (NED), each vessel's mesh once in its body frame and posed at the frame's time by a model
matrix (the same ``yaw_matrix(heading)`` and position :meth:`Scene.vessel_mesh_at` uses).

Per frame, a full-screen pass draws the sky and the sea: each pixel's ray is intersected with
the calm water plane z = 0 (the plane the lidar cuts its rays at), shaded with a Fresnel mix of
deep-water colour and the reflected sky plus a sun glint, and written to the depth buffer at
that intersection's depth, so hulls and quays below the waterline are hidden by the water. The
meshes are then drawn with flat, sun-lit (Lambert) shading and a light distance haze. Two
targets: colour (written as **BGR**, so the read-back bytes are ``bgr8`` as they are) and the
object id (−1 for sky and water). Depth is a 24-bit buffer (thesis 4.1.2, Table 4.1:
near 8 cm, far 10 km).

The projection is the pinhole ``K`` of the camera (OpenCV pixel convention: pixel (0, 0)'s
centre at (0, 0)); image row 0 (the top) is the framebuffer's first row, so nothing is flipped.
"""

from __future__ import annotations

import time as _time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError
from seatwin.geo import yaw_matrix
from seatwin.render.context import create_context, release_collected
from seatwin.render.materials import object_colour

_MESH_VS = """
#version 330
uniform mat4 view_proj;
uniform mat4 model;
in vec3 in_pos;
in vec3 in_normal;
in vec3 in_color;
in float in_id;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
flat out float v_id;
invariant gl_Position;
void main() {
    vec4 w = model * vec4(in_pos, 1.0);
    v_world = w.xyz;
    v_normal = mat3(model) * in_normal;
    v_color = in_color;
    v_id = in_id;
    gl_Position = view_proj * w;
}
"""

_COMMON_FS = """
uniform vec3 sun_dir;      // unit vector towards the sun (NED)
uniform vec3 cam_pos;      // camera centre (NED)
uniform float haze_dist;   // [m]
const vec3 HORIZON = vec3(0.80, 0.85, 0.90);
const vec3 ZENITH = vec3(0.30, 0.50, 0.82);
vec3 sky(vec3 d) {
    float up = clamp(-d.z, 0.0, 1.0);
    vec3 c = mix(HORIZON, ZENITH, pow(up, 0.6));
    float s = max(dot(d, sun_dir), 0.0);
    return c + vec3(1.0, 0.95, 0.8) * (pow(s, 800.0) * 1.5 + pow(s, 12.0) * 0.12);
}
vec3 haze(vec3 c, float dist) {
    return mix(c, HORIZON, clamp(1.0 - exp(-dist / haze_dist), 0.0, 0.85));
}
"""

_MESH_FS = (
    "#version 330\n"
    + _COMMON_FS
    + """
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
flat in float v_id;
layout(location = 0) out vec4 f_color;
layout(location = 1) out float f_id;
void main() {
    if (v_world.z > 0.0) discard;   // below the waterline: the opaque sea hides it (and the solo pass too)
    vec3 n = normalize(v_normal);
    vec3 to_cam = cam_pos - v_world;
    if (dot(n, to_cam) < 0.0) n = -n;   // two-sided: meshes need not be consistently wound
    float lambert = max(dot(n, sun_dir), 0.0);
    float sky_light = 0.5 + 0.5 * max(-n.z, 0.0);
    vec3 c = v_color * (0.40 * sky_light + 0.75 * lambert + 0.15);
    c = haze(c, length(to_cam));
    f_color = vec4(clamp(c, 0.0, 1.0).bgr, 1.0);
    f_id = v_id;
}
"""
)

_BG_VS = """
#version 330
in vec2 in_vert;
void main() { gl_Position = vec4(in_vert, 0.0, 1.0); }
"""

_BG_FS = (
    "#version 330\n"
    + _COMMON_FS
    + """
uniform mat3 ray_mat;      // (u, v, 1) pixel → world ray direction (optical z = 1)
uniform float near;
uniform float far;
layout(location = 0) out vec4 f_color;
layout(location = 1) out float f_id;
void main() {
    vec3 d = ray_mat * vec3(gl_FragCoord.x - 0.5, gl_FragCoord.y - 0.5, 1.0);
    vec3 nd = normalize(d);
    f_id = -1.0;
    float t = d.z > 1e-9 ? -cam_pos.z / d.z : 1e30;   // optical depth of the water hit
    if (t <= 0.0 || t >= far) {
        f_color = vec4(clamp(sky(nd), 0.0, 1.0).bgr, 1.0);
        gl_FragDepth = 1.0;
        return;
    }
    vec3 p = cam_pos + t * d;
    float amp = exp(-t / 40.0);   // ripples fade with distance (no moiré beyond a few pixels per wave)
    vec3 n = normalize(vec3(amp * (0.04 * sin(0.9 * p.x + 0.4 * p.y) + 0.02 * sin(2.3 * p.y - 1.7 * p.x)),
                            amp * (0.04 * cos(1.1 * p.y - 0.3 * p.x) + 0.02 * cos(2.9 * p.x + 1.3 * p.y)), -1.0));
    float cosi = max(dot(-nd, n), 0.0);
    float fresnel = 0.02 + 0.98 * pow(1.0 - cosi, 5.0);
    vec3 r = reflect(nd, n);
    r.z = min(r.z, -0.001);
    vec3 deep = vec3(0.04, 0.13, 0.16) * (0.6 + 0.4 * max(-sun_dir.z, 0.0));
    vec3 c = mix(deep, sky(r), fresnel);
    c += vec3(1.0, 0.95, 0.85) * pow(max(dot(r, sun_dir), 0.0), 300.0) * 1.2;
    c = haze(c, length(p - cam_pos));
    f_color = vec4(clamp(c, 0.0, 1.0).bgr, 1.0);
    float ndc = ((far + near) / (far - near) * t - 2.0 * far * near / (far - near)) / t;
    gl_FragDepth = 0.5 * ndc + 0.5;
}
"""
)


_REMAP_FS = """
#version 330
uniform sampler2D image;   // the pinhole render (BGR)
uniform sampler2D source;  // per output pixel: where it samples the pinhole render [texture coordinates]; < 0: outside
out vec4 f_color;
void main() {
    vec2 st = texelFetch(source, ivec2(gl_FragCoord.xy), 0).xy;
    f_color = st.x < 0.0 ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(texture(image, st).rgb, 1.0);
}
"""


def projection_matrix(k: ArrayLike, width: int, height: int, near: float, far: float) -> NDArray[np.float64]:
    """OpenGL clip matrix of a pinhole camera ``K`` in its optical frame (x right, y down, z forward).

    Pixel (u, v) (OpenCV convention, centres at integers) lands at window coordinates
    (u + ½, v + ½), so image row 0 is the framebuffer's row 0; depth z = near → −1, far → +1.
    """
    k = np.asarray(k, float)
    fx, fy, cx, cy, s = k[0, 0], k[1, 1], k[0, 2], k[1, 2], k[0, 1]
    p = np.zeros((4, 4))
    p[0, 0], p[0, 1], p[0, 2] = 2 * fx / width, 2 * s / width, 2 * (cx + 0.5) / width - 1
    p[1, 1], p[1, 2] = 2 * fy / height, 2 * (cy + 0.5) / height - 1
    p[2, 2], p[2, 3] = (far + near) / (far - near), -2 * far * near / (far - near)
    p[3, 2] = 1.0
    return p


def sun_direction(azimuth_deg: float, elevation_deg: float) -> NDArray[np.float64]:
    """Unit NED vector towards a sun at ``azimuth_deg`` (clockwise from north) and ``elevation_deg``."""
    a, e = np.radians(azimuth_deg), np.radians(elevation_deg)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), -np.sin(e)])


def _flat_vertices(vertices: NDArray[np.float32], faces: NDArray[np.int32], colour: NDArray[np.float32], oid: int) -> bytes:
    """Interleaved (position, face normal, colour, id) float32 records of every triangle corner."""
    tri = vertices[faces].astype(np.float64)  # (F, 3, 3)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
    out = np.empty((len(faces), 3, 10), np.float32)
    out[..., 0:3] = tri
    out[..., 3:6] = n[:, None, :]
    out[..., 6:9] = colour
    out[..., 9] = oid
    return out.tobytes()


@dataclass
class RenderTiming:
    """Seconds spent so far: drawing (until the GPU finished) and reading the frames back."""

    render_s: float = 0.0
    readback_s: float = 0.0
    distortion_s: float = 0.0
    frames: int = 0


@dataclass(frozen=True)
class RenderedFrame:
    """One rendered view: ``bgr`` H×W×3 uint8, ``ids`` H×W int32 object ids (−1: sky or water)."""

    bgr: NDArray[np.uint8]
    ids: NDArray[np.int32]
    unoccluded: dict[str, int] = field(default_factory=dict)
    """Pixels each vessel asked for in ``solo`` covers in the image when drawn alone (no occluders)."""


class SceneRenderer:
    """Rasterises ``scene`` (a :class:`~seatwin.world.scene.Scene`) through pinhole cameras of one size and ``K``.

    ``exclude``: vessels never drawn (the ownship carrying the cameras). ``sun`` = (azimuth,
    elevation) in degrees.
    """

    def __init__(
        self,
        scene: Any,
        k: ArrayLike,
        width: int,
        height: int,
        *,
        near: float = 0.08,
        far: float = 10_000.0,
        exclude: Sequence[str] = (),
        sun: tuple[float, float] = (200.0, 35.0),
        haze_m: float = 2500.0,
        ctx: Any = None,
    ):
        import moderngl

        if width < 1 or height < 1:
            raise InputError("camera", f"image size must be positive, got {width}×{height}")
        self.scene, self.width, self.height = scene, int(width), int(height)
        self.k = np.asarray(k, float)
        self.near, self.far = float(near), float(far)
        self.exclude = set(exclude)
        self.ctx = ctx if ctx is not None else create_context()
        release_collected(self.ctx)
        self.timing = RenderTiming()
        ctx = self.ctx
        self.proj = projection_matrix(self.k, self.width, self.height, self.near, self.far)
        self.mesh_prog = ctx.program(vertex_shader=_MESH_VS, fragment_shader=_MESH_FS)
        self.bg_prog = ctx.program(vertex_shader=_BG_VS, fragment_shader=_BG_FS)
        sun_dir = sun_direction(*sun)
        for prog in (self.mesh_prog, self.bg_prog):
            prog["sun_dir"].value = tuple(float(x) for x in sun_dir)
            prog["haze_dist"].value = float(haze_m)
        self.bg_prog["near"].value = self.near
        self.bg_prog["far"].value = self.far
        tri = np.array([-1.0, -1.0, 3.0, -1.0, -1.0, 3.0], np.float32)
        self._bg_vbo = ctx.buffer(tri.tobytes())
        self._bg_vao = ctx.vertex_array(self.bg_prog, [(self._bg_vbo, "2f", "in_vert")])
        fmt = ("3f 3f 3f 1f", "in_pos", "in_normal", "in_color", "in_id")
        static = b"".join(
            _flat_vertices(m.vertices, m.faces, object_colour(o.label, o.name), m.object_id)
            for m, o in zip(scene.static_meshes, scene.objects, strict=False)
        )
        self._static = None
        if static:
            vbo = ctx.buffer(static)
            self._static = (vbo, ctx.vertex_array(self.mesh_prog, [(vbo, *fmt)]))
        self._vessels: dict[str, tuple[Any, Any]] = {}
        # Moored boats are part of the static mesh; their own buffers measure their pixels drawn alone.
        self._moored: dict[str, tuple[Any, Any]] = {}
        for m, o in zip(scene.static_meshes, scene.objects, strict=False):
            if o.label == "moored_boat":
                vbo = ctx.buffer(_flat_vertices(m.vertices, m.faces, object_colour(o.label, o.name), m.object_id))
                self._moored[o.name] = (vbo, ctx.vertex_array(self.mesh_prog, [(vbo, *fmt)]))
        for name in scene.vessel_names:
            if name in self.exclude:
                continue
            m = scene.vessel_models[name].mesh
            oid = scene.vessel_ids[name]
            data = _flat_vertices(
                np.asarray(m.vertices, np.float32), np.asarray(m.faces, np.int32), object_colour("vessel", name), oid
            )
            vbo = ctx.buffer(data)
            self._vessels[name] = (vbo, ctx.vertex_array(self.mesh_prog, [(vbo, *fmt)]))
        size = (self.width, self.height)
        self._colour = ctx.texture(size, 4)
        self._colour.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self._colour.repeat_x = self._colour.repeat_y = False
        self._ids = ctx.renderbuffer(size, components=1, dtype="f4")
        self._depth = ctx.depth_renderbuffer(size)  # GL_DEPTH_COMPONENT24
        self.fbo = ctx.framebuffer(color_attachments=[self._colour, self._ids], depth_attachment=self._depth)
        self._solo_depth = ctx.depth_renderbuffer(size)
        self.solo_fbo = ctx.framebuffer(depth_attachment=self._solo_depth)
        self._query = ctx.query(samples=True)
        self._remap: tuple[Any, ...] | None = None

    def set_distortion(self, source_u: NDArray[np.float64] | None, source_v: NDArray[np.float64] | None = None) -> None:
        """Resample every rendered image on the GPU: output pixel (row, col) takes the (bilinear) colour
        of the pinhole render at pixel ``(source_u, source_v)[row, col]`` (NaN or outside: black).
        ``None`` switches it off. The object-id image stays the pinhole one."""
        import moderngl

        if self._remap is not None:
            for obj in self._remap:
                obj.release()
            self._remap = None
        if source_u is None:
            return
        su, sv = np.asarray(source_u, float), np.asarray(source_v, float)
        w, h = self.width, self.height
        inside = np.isfinite(su) & np.isfinite(sv) & (su >= -0.5) & (su <= w - 0.5) & (sv >= -0.5) & (sv <= h - 0.5)
        st = np.stack([np.where(inside, (su + 0.5) / w, -1.0), np.where(inside, (sv + 0.5) / h, -1.0)], axis=-1)
        ctx = self.ctx
        src = ctx.texture((w, h), 2, np.ascontiguousarray(st, np.float32).tobytes(), dtype="f4")
        src.filter = (moderngl.NEAREST, moderngl.NEAREST)
        prog = ctx.program(vertex_shader=_BG_VS, fragment_shader=_REMAP_FS)
        prog["image"].value = 0
        prog["source"].value = 1
        vao = ctx.vertex_array(prog, [(self._bg_vbo, "2f", "in_vert")])
        out = ctx.renderbuffer((w, h), components=4)
        fbo = ctx.framebuffer(color_attachments=[out])
        self._remap = (fbo, out, vao, prog, src)

    # ------------------------------------------------------------------ matrices
    def view_proj(self, rotation: ArrayLike, position: ArrayLike) -> NDArray[np.float64]:
        """Clip-from-world matrix of a camera whose optical frame has ``rotation`` (optical → world) at ``position``."""
        r = np.asarray(rotation, float)
        c = np.asarray(position, float)
        view = np.eye(4)
        view[:3, :3] = r.T
        view[:3, 3] = -r.T @ c
        return self.proj @ view

    def vessel_model(self, name: str, t: float) -> NDArray[np.float64] | None:
        """World-from-body matrix of vessel ``name`` at ``t`` (None outside its trajectory)."""
        try:
            p = self.scene.pose(name, t)
        except InputError:
            return None
        m = np.eye(4)
        m[:3, :3] = yaw_matrix(float(p.heading))
        m[:3, 3] = [float(p.north), float(p.east), 0.0]
        return m

    @staticmethod
    def _mat(prog: Any, name: str, m: NDArray[np.float64]) -> None:
        prog[name].write(np.ascontiguousarray(np.asarray(m, np.float32).T).tobytes())

    # ------------------------------------------------------------------ drawing
    def render(self, t: float, rotation: ArrayLike, position: ArrayLike, solo: Sequence[str] = ()) -> RenderedFrame:
        """Render the scene at time ``t`` from a camera (optical frame ``rotation`` → world, centre ``position``).

        ``solo``: vessels (and moored boats, :attr:`seatwin.world.scene.Scene.moored_boats`) whose unoccluded
        pixel count (drawn alone) is also measured, by an occlusion query (for the labels' visible fraction).
        """
        import moderngl

        ctx = self.ctx
        release_collected(ctx)
        t0 = _time.perf_counter()
        r = np.asarray(rotation, float)
        c = np.asarray(position, float)
        vp = self.view_proj(r, c)
        kinv = np.linalg.inv(self.k)
        for prog in (self.mesh_prog, self.bg_prog):
            prog["cam_pos"].value = tuple(float(x) for x in c)
        self._mat(self.mesh_prog, "view_proj", vp)
        self.bg_prog["ray_mat"].write(np.ascontiguousarray((r @ kinv).astype(np.float32).T).tobytes())
        models = {n: self.vessel_model(n, t) for n in self._vessels}

        self.fbo.use()
        ctx.viewport = (0, 0, self.width, self.height)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.CULL_FACE)
        self.fbo.clear(depth=1.0)
        ctx.depth_func = "1"  # the sky/sea pass writes every pixel and its depth
        self._bg_vao.render(moderngl.TRIANGLES)
        ctx.depth_func = "<"
        eye = np.eye(4)
        if self._static is not None:
            self._mat(self.mesh_prog, "model", eye)
            self._static[1].render(moderngl.TRIANGLES)
        for name, (_, vao) in self._vessels.items():
            m = models[name]
            if m is not None:
                self._mat(self.mesh_prog, "model", m)
                vao.render(moderngl.TRIANGLES)
        unoccluded: dict[str, int] = {}
        for name in solo:
            if name in self._moored:
                unoccluded[name] = self._solo_pixels(name, eye)
                continue
            m = models.get(name)
            if m is None:
                unoccluded[name] = 0
                continue
            unoccluded[name] = self._solo_pixels(name, m)
        ctx.finish()
        t1 = _time.perf_counter()
        colour_fbo = self.fbo
        if self._remap is not None:
            fbo, _, vao, _, src = self._remap
            fbo.use()
            ctx.disable(moderngl.DEPTH_TEST)
            self._colour.use(0)
            src.use(1)
            vao.render(moderngl.TRIANGLES)
            ctx.enable(moderngl.DEPTH_TEST)
            ctx.finish()
            colour_fbo = fbo
        t_remap = _time.perf_counter()
        self.fbo.use()
        bgr = np.frombuffer(colour_fbo.read(components=3, attachment=0, alignment=1), np.uint8)
        ids = np.frombuffer(self.fbo.read(components=1, attachment=1, dtype="f4", alignment=1), np.float32)
        out = RenderedFrame(
            bgr.reshape(self.height, self.width, 3),
            ids.reshape(self.height, self.width).astype(np.int32),
            unoccluded,
        )
        t2 = _time.perf_counter()
        self.timing.render_s += t1 - t0
        self.timing.distortion_s += t_remap - t1
        self.timing.readback_s += t2 - t_remap
        self.timing.frames += 1
        return out

    def _solo_pixels(self, name: str, model: NDArray[np.float64]) -> int:
        """Pixels vessel ``name`` covers drawn alone: a depth pre-pass, then an ``==`` pass counted by a query."""
        import moderngl

        ctx = self.ctx
        vao = (self._moored[name] if name in self._moored else self._vessels[name])[1]
        self.solo_fbo.use()
        self.solo_fbo.clear(depth=1.0)
        self._mat(self.mesh_prog, "model", model)
        ctx.depth_func = "<"
        vao.render(moderngl.TRIANGLES)
        ctx.depth_func = "=="
        with self._query:
            vao.render(moderngl.TRIANGLES)
        ctx.depth_func = "<"
        self.fbo.use()
        return int(self._query.samples)

    def release(self) -> None:
        """Free this renderer's GL objects (the shared context stays)."""
        self.set_distortion(None)
        for obj in (self.fbo, self.solo_fbo, self._colour, self._ids, self._depth, self._solo_depth, self._bg_vao, self._bg_vbo):
            obj.release()
        for vbo, vao in ([self._static] if self._static else []) + list(self._vessels.values()) + list(self._moored.values()):
            vao.release()
            vbo.release()
        self.mesh_prog.release()
        self.bg_prog.release()
