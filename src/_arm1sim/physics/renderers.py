"""Camera frame backends of the render processes: one ``render(...) -> (rgba, depth)`` each.

- ``tiny``: pybullet's TinyRenderer (ER_TINY_RENDERER), single-threaded software
  rasterising inside pybullet; the reference picture.
- ``egl``: pybullet's own EGL plugin (ER_BULLET_HARDWARE_OPENGL) on whatever
  OpenGL the machine's EGL gives: Mesa's llvmpipe (multi-threaded, CPU) without
  a GPU. The plugin only draws bodies loaded after it, so it is loaded when the
  world is built (``open_world``); its sky is OpenGL's grey-blue, painted
  TinyRenderer's white here where nothing was drawn.
- ``gl``: an OpenGL context of our own through moderngl's headless EGL (also
  llvmpipe on the CPU), drawing the bodies' visual shapes as pybullet lists them
  with TinyRenderer's lighting (ambient 0.6, diffuse 0.35, light from
  (-50, 30, 100)); no pixel or depth round trip through pybullet. It reads STL meshes
  (what the project's models use); a world with another mesh (OBJ, DAE) is drawn by
  TinyRenderer, said once on stderr.

The backend is chosen by ``ARM1_RENDERER`` (``tiny``, ``egl`` or ``gl``) in the
world's environment, inherited by its render processes; unset means DEFAULT.
Every backend gives RGBA (height x width x 4, uint8, top row first) and
pybullet's depth buffer (height x width, float32, OpenGL window z in [0, 1]).
"""

from __future__ import annotations

import math
import os
import pkgutil
import sys
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, cast

import numpy as np
import pybullet as p

from ..description.camera_sensor import CameraSensor
from .camera_geometry import projection_matrix, sensor_pose, view_matrix
from .world import World

ENV = 'ARM1_RENDERER'
BACKENDS = ('tiny', 'egl', 'gl')
DEFAULT = 'gl'  # the fastest that matches TinyRenderer's pictures (BENCHMARKS.md)
SKY = (255, 255, 255)  # TinyRenderer's clear colour
LIGHT_DIRECTION = (-50.0, 30.0, 100.0)  # TinyRenderer's default for a z-up world
AMBIENT, DIFFUSE, SPECULAR = 0.6, 0.35, 0.05  # TinyRenderer's light coefficients

Frame = Tuple[np.ndarray, np.ndarray]  # rgba (h, w, 4) uint8, depth (h, w) float32


class BackendError(RuntimeError):
    """A backend that cannot run here, or a scene it cannot draw."""


def backend_name(name: Optional[str] = None) -> str:
    """The backend asked for (``name``, else ``$ARM1_RENDERER``, else DEFAULT), checked."""
    chosen = (name if name is not None else os.environ.get(ENV, '')).strip().lower() or DEFAULT
    if chosen not in BACKENDS:
        raise BackendError(
            "%s='%s' is no camera renderer: one of %s" % (ENV, chosen, ', '.join(BACKENDS))
        )
    return chosen


class Backend:
    """One render process's renderer: builds its world, then renders frames of that world."""

    name = 'tiny'
    renderer = p.ER_TINY_RENDERER  # pybullet's renderer flag for getCameraImage
    paints_sky = False  # True where the renderer leaves the background black: painted SKY

    def open_world(self, world_config: Any) -> World:
        return World(world_config, gui=False)

    def render(
        self,
        client: int,
        width: int,
        height: int,
        view: Sequence[float],
        projection: Sequence[float],
    ) -> Frame:
        rgba, depth = _pybullet_image(client, width, height, view, projection, self.renderer)
        if self.paints_sky:
            rgba = np.array(rgba)  # writable
            rgba[depth >= 1.0, :3] = SKY
        return rgba, depth

    def close(self) -> None:
        pass


def _pybullet_image(
    client: int,
    width: int,
    height: int,
    view: Sequence[float],
    projection: Sequence[float],
    renderer: int,
) -> Frame:
    _, _, rgba, depth, _ = p.getCameraImage(
        width,
        height,
        view,
        projection,
        shadow=0,  # TinyRenderer's default (the EGL plugin casts shadows all the same)
        renderer=renderer,
        flags=p.ER_NO_SEGMENTATION_MASK,
        physicsClientId=client,
    )
    return (
        np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4),
        np.asarray(depth, dtype=np.float32).reshape(height, width),
    )


class EglPluginBackend(Backend):
    """pybullet's eglRenderer plugin, loaded into the client before the world's bodies."""

    name = 'egl'
    renderer = p.ER_BULLET_HARDWARE_OPENGL
    paints_sky = True

    def open_world(self, world_config: Any) -> World:
        loader = pkgutil.get_loader('eglRenderer')
        if loader is None:
            raise BackendError("pybullet's eglRenderer plugin is not installed")
        path = loader.get_filename()  # type: ignore[attr-defined]

        def load_plugin(client: int) -> None:
            if p.loadPlugin(path, '_eglRendererPlugin', physicsClientId=client) < 0:
                raise BackendError('pybullet could not load its EGL plugin %s' % path)

        return World(world_config, gui=False, on_connect=load_plugin)


# --------------------------------------------------------------------- our own OpenGL
_VERTEX_SHADER = """
#version 330
uniform mat4 mvp;
uniform mat4 model;
in vec3 in_position;
in vec3 in_normal;
out vec3 v_normal;
void main() {
    v_normal = mat3(model) * in_normal;
    gl_Position = mvp * vec4(in_position, 1.0);
}
"""

_FRAGMENT_SHADER = """
#version 330
uniform vec4 color;
uniform vec3 light;
uniform vec3 coeffs;
in vec3 v_normal;
out vec4 f_color;
void main() {
    vec3 n = normalize(v_normal);
    float diffuse = max(dot(n, light), 0.0);
    vec3 r = normalize(2.0 * dot(n, light) * n - light);
    float specular = pow(max(r.z, 0.0), 2.0);
    float k = coeffs.x + coeffs.y * diffuse + coeffs.z * specular;
    f_color = vec4(min(color.rgb * k, 1.0), color.a);
}
"""


def _box() -> np.ndarray:
    """Triangles of the unit cube (-0.5..0.5) with flat normals: (n, 6) position + normal."""
    out: List[np.ndarray] = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = np.zeros(3)
            n[axis] = sign
            u, v = np.zeros(3), np.zeros(3)
            u[(axis + 1) % 3], v[(axis + 2) % 3] = 1.0, 1.0
            if sign < 0:
                u, v = v, u
            c = n * 0.5
            quad = [c - u / 2 - v / 2, c + u / 2 - v / 2, c + u / 2 + v / 2, c - u / 2 + v / 2]
            for tri in ((0, 1, 2), (0, 2, 3)):
                out.extend(np.concatenate([quad[i], n]) for i in tri)
    return np.array(out)


def _sphere(rings: int = 16, segments: int = 24) -> np.ndarray:
    """Unit-radius sphere, smooth normals."""
    out: List[np.ndarray] = []

    def point(i: int, j: int) -> np.ndarray:
        th, ph = math.pi * i / rings, 2 * math.pi * j / segments
        q = np.array([math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)])
        return np.concatenate([q, q])

    for i in range(rings):
        for j in range(segments):
            a, b, c, d = point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)
            out += [a, b, c, a, c, d]
    return np.array(out)


def _cylinder(segments: int = 24) -> np.ndarray:
    """Radius 1, height 1 (z -0.5..0.5), smooth sides, flat caps."""
    out: List[List[float]] = []
    for j in range(segments):
        a0, a1 = 2 * math.pi * j / segments, 2 * math.pi * (j + 1) / segments
        c0, s0, c1, s1 = math.cos(a0), math.sin(a0), math.cos(a1), math.sin(a1)
        lo0, lo1 = [c0, s0, -0.5, c0, s0, 0], [c1, s1, -0.5, c1, s1, 0]
        hi0, hi1 = [c0, s0, 0.5, c0, s0, 0], [c1, s1, 0.5, c1, s1, 0]
        out += [lo0, lo1, hi1, lo0, hi1, hi0]
        out += [[0, 0, 0.5, 0, 0, 1], [c0, s0, 0.5, 0, 0, 1], [c1, s1, 0.5, 0, 0, 1]]
        out += [[0, 0, -0.5, 0, 0, -1], [c1, s1, -0.5, 0, 0, -1], [c0, s0, -0.5, 0, 0, -1]]
    return np.array(out, dtype=float)


def _capsule(length: float, radius: float) -> np.ndarray:
    """A cylinder of ``length`` along z with a sphere of ``radius`` at each end."""
    side = _cylinder() * np.array([radius, radius, length, 1, 1, 1])
    caps = []
    for end in (-0.5, 0.5):
        ball = _sphere() * np.array([radius, radius, radius, 1, 1, 1])
        ball[:, 2] += end * length
        caps.append(ball)
    return np.concatenate([side] + caps)


def _mesh_triangles(path: str) -> np.ndarray:
    """(n, 6) vertices of a mesh file; STL only (what the project's models use)."""
    from .stl import read_stl

    if not path.lower().endswith('.stl'):
        raise BackendError(
            "the '%s' camera renderer reads STL meshes only, not %s" % (GlBackend.name, path)
        )
    triangles, _ = read_stl(path)
    e1, e2 = triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    n = np.cross(e1, e2)
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
    normals = np.repeat(n[:, None, :], 3, axis=1)
    return np.concatenate([triangles, normals], axis=2).reshape(-1, 6)


def _pose_matrix(position: Sequence[float], orientation: Sequence[float]) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = np.array(p.getMatrixFromQuaternion(orientation)).reshape(3, 3)
    m[:3, 3] = position
    return m


def _link_frame(client: int, body: int, link: int) -> Tuple[Sequence[float], Sequence[float]]:
    """World pose of a link's URDF frame (what pybullet's visual frames are relative to)."""
    if link >= 0:
        s = p.getLinkState(body, link, computeForwardKinematics=True, physicsClientId=client)
        return s[4], s[5]
    com = p.getBasePositionAndOrientation(body, physicsClientId=client)
    inertial = p.getDynamicsInfo(body, -1, physicsClientId=client)[3:5]
    return p.multiplyTransforms(*com, *p.invertTransform(*inertial))


class _Shape:
    """One visual shape of a body, uploaded: its unit geometry, scale and colour."""

    def __init__(
        self, vao: Any, vbo: Any, link: int, local: np.ndarray, color: Tuple[float, ...]
    ) -> None:
        self.vao, self.vbo, self.link, self.local, self.color = vao, vbo, link, local, color


class GlBackend(Backend):
    """moderngl on a headless EGL context: the scene from pybullet's visual shape data."""

    name = 'gl'

    def __init__(self) -> None:
        try:
            import moderngl
        except ImportError as exc:
            raise BackendError('moderngl is not installed (%s)' % exc) from None
        try:
            create: Any = moderngl.create_standalone_context  # its stub types no keywords
            # the runtime libraries, not the -dev packages' unversioned links
            self.ctx: Any = create(backend='egl', libgl='libGL.so.1', libegl='libEGL.so.1')
        except Exception as exc:
            raise BackendError('no headless OpenGL 3.3 context through EGL: %s' % exc) from None
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.program: Any = cast(
            Any, self.ctx.program(vertex_shader=_VERTEX_SHADER, fragment_shader=_FRAGMENT_SHADER)
        )
        light = np.array(LIGHT_DIRECTION)
        self.program['light'].value = tuple(light / np.linalg.norm(light))
        self.program['coeffs'].value = (AMBIENT, DIFFUSE, SPECULAR)
        self._unit: Dict[Any, Any] = {}  # geometry key -> vbo
        self._bodies: Dict[int, Tuple[Any, List[_Shape]]] = {}  # body id -> (key, shapes)
        self._unreadable: Dict[int, Tuple[Any, str]] = {}  # body id -> (key, why)
        self._fbo: Any = None
        self._cannot = ''  # why the last frame went to TinyRenderer (said once per reason)
        self._size = (0, 0)

    # -- scene ---------------------------------------------------------------------
    def _geometry(self, key: Any, make: Callable[[], np.ndarray]) -> Any:
        vbo = self._unit.get(key)
        if vbo is None:
            vbo = self._unit[key] = self.ctx.buffer(make().astype('f4').tobytes())
        return vbo

    def _shape(self, data: Sequence[Any]) -> _Shape:
        _, link, kind, dims, mesh, local_pos, local_orn, rgba = data[:8]
        scale = np.ones(3)
        if kind == p.GEOM_BOX:
            vbo, scale = self._geometry('box', _box), np.array(dims[:3])
        elif kind == p.GEOM_SPHERE:
            vbo, scale = self._geometry('sphere', _sphere), np.full(3, dims[0])
        elif kind == p.GEOM_CAPSULE:  # its own mesh: scaling would flatten the caps
            length, radius = dims[0], dims[1]
            vbo = self._geometry(('capsule', length, radius), lambda: _capsule(length, radius))
        elif kind == p.GEOM_CYLINDER:
            vbo, scale = (
                self._geometry('cylinder', _cylinder),
                np.array([dims[1], dims[1], dims[0]]),
            )
        elif kind == p.GEOM_MESH:
            name = mesh.decode() if isinstance(mesh, bytes) else str(mesh)
            vbo, scale = self._geometry(('mesh', name), lambda: _mesh_triangles(name)), dims[:3]
        else:
            raise BackendError(
                "the '%s' camera renderer cannot draw shape type %d" % (self.name, kind)
            )
        local = _pose_matrix(local_pos, local_orn) @ np.diag([*scale, 1.0])
        vao = self.ctx.vertex_array(self.program, [(vbo, '3f 3f', 'in_position', 'in_normal')])
        return _Shape(vao, vbo, link, local, tuple(rgba))

    def _sync(self, client: int) -> List[Tuple[int, List[_Shape]]]:
        """The bodies of the client, uploaded once each (again if their shapes changed)."""
        bodies = []
        seen = set()
        for n in range(p.getNumBodies(physicsClientId=client)):
            body = p.getBodyUniqueId(n, physicsClientId=client)
            seen.add(body)
            key = p.getVisualShapeData(body, physicsClientId=client)
            known = self._bodies.get(body)
            if known is None or known[0] != key:
                if known is not None:
                    self._release(known[1])
                    del self._bodies[body]
                failed = self._unreadable.get(body)
                if failed is not None and failed[0] == key:
                    raise BackendError(failed[1])  # not read again each frame
                shapes: List[_Shape] = []
                try:
                    shapes.extend(self._shape(d) for d in key)
                except (BackendError, ValueError) as exc:
                    self._release(shapes)
                    self._unreadable[body] = (key, str(exc))
                    raise
                known = self._bodies[body] = (key, shapes)
            bodies.append((body, known[1]))
        for gone in set(self._bodies) - seen:
            self._release(self._bodies.pop(gone)[1])
        for gone in set(self._unreadable) - seen:
            del self._unreadable[gone]
        return bodies

    @staticmethod
    def _release(shapes: List[_Shape]) -> None:
        for s in shapes:
            s.vao.release()

    def _target(self, width: int, height: int) -> Any:
        if self._size != (width, height):
            if self._fbo is not None:
                self._fbo.release()
            self._fbo = self.ctx.framebuffer(
                color_attachments=[self.ctx.renderbuffer((width, height), 4)],
                depth_attachment=self.ctx.depth_renderbuffer((width, height)),
            )
            self._size = (width, height)
        return self._fbo

    # -- frames --------------------------------------------------------------------
    def render(
        self,
        client: int,
        width: int,
        height: int,
        view: Sequence[float],
        projection: Sequence[float],
    ) -> Frame:
        try:
            bodies = self._sync(client)
        except (BackendError, ValueError) as exc:  # a mesh we cannot read: TinyRenderer can
            if str(exc) != self._cannot:
                self._cannot = str(exc)
                sys.stderr.write(
                    'arm1 render process: %s; this frame drawn by TinyRenderer\n' % exc
                )
            return super().render(client, width, height, view, projection)
        fbo = self._target(width, height)
        fbo.use()
        fbo.clear(SKY[0] / 255.0, SKY[1] / 255.0, SKY[2] / 255.0, 1.0, depth=1.0)
        # pybullet's matrices are column-major: transposed, they are numpy's row-major
        vp = np.array(projection).reshape(4, 4).T @ np.array(view).reshape(4, 4).T
        mvp_u, model_u, color_u = self.program['mvp'], self.program['model'], self.program['color']
        for body, shapes in bodies:
            frames: Dict[int, np.ndarray] = {}
            for s in shapes:
                if s.color[3] == 0:
                    continue  # TinyRenderer skips invisible shapes too
                m = frames.get(s.link)
                if m is None:
                    m = frames[s.link] = _pose_matrix(*_link_frame(client, body, s.link))
                model = m @ s.local
                model_u.write(model.T.astype('f4').tobytes())
                mvp_u.write((vp @ model).T.astype('f4').tobytes())
                color_u.value = s.color
                s.vao.render()
        rgba = np.frombuffer(fbo.read(components=4, alignment=1), np.uint8)
        depth = np.frombuffer(fbo.read(components=1, attachment=-1, dtype='f4'), np.float32)
        return (
            rgba.reshape(height, width, 4)[::-1],
            depth.reshape(height, width)[::-1],
        )

    def close(self) -> None:
        for _, shapes in self._bodies.values():
            self._release(shapes)
        self._bodies.clear()
        self.ctx.release()


def open_backend(name: Optional[str] = None) -> Backend:
    """A backend by name (see ``backend_name``); raises BackendError if the one asked for
    cannot run here. The default falls back to TinyRenderer, saying why on stderr."""
    chosen = backend_name(name)
    asked = name is not None or bool(os.environ.get(ENV, '').strip())
    try:
        if chosen == 'egl':
            return EglPluginBackend()
        if chosen == 'gl':
            return GlBackend()
    except BackendError as exc:
        if asked:
            raise
        sys.stderr.write(
            "arm1 render process: camera renderer '%s' unavailable (%s); using 'tiny'\n"
            % (chosen, exc)
        )
    return Backend()


def render(
    backend: Backend,
    client: int,
    sensor: CameraSensor,
    link_position: Sequence[float],
    link_orientation: Sequence[float],
) -> Frame:
    """One frame of ``sensor`` on its link's pose: RGBA and pybullet's depth buffer."""
    return backend.render(
        client,
        sensor.width,
        sensor.height,
        view_matrix(*sensor_pose(sensor, link_position, link_orientation)),
        projection_matrix(sensor),
    )
