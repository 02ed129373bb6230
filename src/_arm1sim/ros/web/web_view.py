"""The world in a browser (gzserver ``--web``): a live 3D view and Gazebo's everyday controls.

viser serves the page and its WebSocket; this module only says what is on it. Its
threads never touch pybullet: they read snapshots the physics thread takes between
two steps (web_snapshot) while a page is open, and nothing at all while none is.
What a button or a slider does goes the way a user's node goes: pause, step and the
resets through the same hand-over calls as the /gazebo services, a joint through its
controller's ``command`` topic, a dragged model through set_model_state's path.
"""

from __future__ import annotations

import collections
import math
import threading
import time
from typing import Any, Callable, Deque, Dict, List, Optional, Tuple

import numpy as np
import rospy
from std_msgs.msg import Float64
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from ...sim import model_state as ms
from ...sim.simulation import Simulation
from ..plugins.camera_plugin import GazeboRosCamera
from ..world.sim_thread import SimThreadCalls
from ..world.world_loop import WorldLoop
from .web_snapshot import (
    TRAJECTORY,
    ModelView,
    Pose,
    Snapshot,
    Visual,
    WorldSnapshots,
    ros_names,
    shown_pose,
)

FRAME_PERIOD = 1 / 32.0  # s of wall time between two scene updates (the view asks >= 30 fps)
PANEL_PERIOD = 0.2  # s: status text, joint readouts, plots and camera images
PLOT_SECONDS = 10.0  # of sim time shown by each joint plot
CAMERA_PERIOD = 0.2  # s of wall time between two camera images rendered for the page
STILL = 1e-5  # m, and quaternion component: a link moved less is not sent again
IDLE_NAP = 0.25  # s: with no page open the view only looks for one this often
TRAJECTORY_SECONDS = 1.0  # time_from_start of a slider's trajectory point
INITIAL_CAMERA = (0.3, -0.3, 0.25)  # m: arm1 (15 cm tall) at the origin, as the pybullet window
INITIAL_LOOK_AT = (0.0, 0.0, 0.05)
INITIAL_FOV = math.radians(60.0)  # vertical
DEFAULT_HOST = '127.0.0.1'
NO_SELECTION = 'Click a model to see its name, pose and links; drag its handles to move it.'
DEFAULT_PORT = 8080


def _place_camera(client: Any) -> None:
    """Each page starts looking at the origin from where gazebo.launch's window does."""
    client.camera.fov = INITIAL_FOV
    client.camera.position = INITIAL_CAMERA
    client.camera.look_at = INITIAL_LOOK_AT


def _no_share(*_: Any, **__: Any) -> None:
    rospy.logwarn('web view: a page asked for a public share link; refused')
    return None


def _wxyz(q: Tuple[float, float, float, float]) -> Tuple[float, float, float, float]:
    return (q[3], q[0], q[1], q[2])


def _xyzw(q: Any) -> Tuple[float, float, float, float]:
    return (float(q[1]), float(q[2]), float(q[3]), float(q[0]))


class MeshCache:
    """Visual geometry as trimesh objects, read once per file and scale."""

    def __init__(self) -> None:
        self._meshes: Dict[Tuple[Any, ...], Any] = {}
        self.failed: Dict[str, str] = {}  # mesh file -> why it is not drawn

    def get(self, v: Visual) -> Any:
        import trimesh

        key = (v.kind, v.size, v.mesh)
        if key in self._meshes:
            return self._meshes[key]
        if v.kind == 'box':
            mesh = trimesh.creation.box(extents=v.size)
        elif v.kind == 'sphere':
            mesh = trimesh.creation.icosphere(subdivisions=2, radius=v.size[0])
        elif v.kind == 'cylinder':
            mesh = trimesh.creation.cylinder(radius=v.size[1], height=v.size[0], sections=24)
        elif v.kind == 'capsule':
            mesh = trimesh.creation.capsule(height=v.size[0], radius=v.size[1])
        else:
            try:
                loaded: Any = trimesh.load(
                    v.mesh, force='scene' if v.mesh.lower().endswith('.dae') else None
                )
                if isinstance(loaded, trimesh.Scene):
                    loaded = (
                        loaded.to_mesh()
                        if hasattr(loaded, 'to_mesh')
                        else loaded.dump(concatenate=True)
                    )
                mesh = loaded.copy()
                mesh.apply_scale(v.size)
            except Exception as exc:  # drawn without it; said once
                self.failed[v.mesh] = '%s: %s' % (type(exc).__name__, exc)
                rospy.logwarn('web view: mesh %s not shown: %s', v.mesh, self.failed[v.mesh])
                mesh = None
        self._meshes[key] = mesh
        return mesh


class SceneModel:
    """A model's nodes in the viser scene: a frame per link, its visuals beneath."""

    def __init__(self, view: 'WebView', model: ModelView, visuals: List[Visual]) -> None:
        scene = view.server.scene
        self.name, self.token = model.name, model.token
        self.visuals = visuals  # for the MoveIt layer's ghosts
        self.root = '/world/%s' % model.name
        self.frames = [
            scene.add_frame('%s/%d' % (self.root, i), show_axes=False)
            for i in range(len(model.links))
        ]
        self._shown: List[Optional[Pose]] = [None] * len(self.frames)
        for k, v in enumerate(visuals):
            mesh = view.meshes.get(v)
            if mesh is None or not (0 <= v.link + 1 < len(self.frames)):
                continue
            node = '%s/%d/v%d' % (self.root, v.link + 1, k)
            pos, wxyz = v.pose[0], _wxyz(v.pose[1])
            custom = v.kind == 'mesh' and v.rgba[:3] == (1.0, 1.0, 1.0) and _has_colours(mesh)
            handle: Any
            if custom:  # the file's own colours (Collada, OBJ materials)
                handle = scene.add_mesh_trimesh(node, mesh, position=pos, wxyz=wxyz)
            else:
                handle = scene.add_mesh_simple(
                    node,
                    np.asarray(mesh.vertices, dtype=np.float32),
                    np.asarray(mesh.faces, dtype=np.uint32),
                    color=(v.rgba[0], v.rgba[1], v.rgba[2]),
                    opacity=v.rgba[3] if v.rgba[3] < 1.0 else None,
                    position=pos,
                    wxyz=wxyz,
                    flat_shading=v.kind in ('box', 'mesh'),
                )
            if not model.static:
                handle.on_click(_selector(view, model.name))
        self.move(model.poses)

    def move(self, poses: Tuple[Pose, ...]) -> None:
        # only links that moved: each assignment is a message to every page
        for i, (frame, pose) in enumerate(zip(self.frames, poses)):
            if _moved(self._shown[i], pose):
                self._shown[i] = pose
                frame.position = pose[0]
                frame.wxyz = _wxyz(pose[1])

    def remove(self) -> None:
        # a frame's removal takes its visuals with it; each is forgotten only once gone, so
        # that a removal cut short (WebView._run) is finished by the next frame's call
        while self.frames:
            self.frames[-1].remove()
            self.frames.pop()


def _moved(shown: Optional[Pose], pose: Pose) -> bool:
    """Whether ``pose`` is drawn apart from ``shown``: a controller at rest jitters far below."""
    if shown is None:
        return True
    return any(abs(a - b) > STILL for a, b in zip(shown[0] + shown[1], pose[0] + pose[1]))


def _selector(view: 'WebView', name: str) -> Callable[[Any], None]:
    return lambda _: view.select(name)


def _has_colours(mesh: Any) -> bool:
    kind = getattr(getattr(mesh, 'visual', None), 'kind', None)
    return kind in ('vertex', 'face', 'texture')


class ControllerPanel:
    """One controller manager's folder: controllers and states, a slider per commanded joint,
    position beside command, and a plot of both over the last seconds."""

    def __init__(self, view: 'WebView', model: ModelView) -> None:
        gui = view.server.gui
        self.view, self.key = view, _panel_key(model)
        self.folder: Any = gui.add_folder('Controllers: %s' % model.namespace)
        self.publishers: List[rospy.Publisher] = []
        self.readout: Any = None
        self.plot: Any = None
        self.series: List[str] = []
        self.history: Deque[Tuple[float, List[float]]] = collections.deque()
        with self.folder:
            lines = ['| controller | type | state |', '|---|---|---|']
            lines += [
                '| %s | %s | %s |' % (c.name, c.type.split('/')[-1], c.state)
                for c in model.controllers
            ]
            gui.add_markdown('\n'.join(lines))
            for c in model.controllers:
                if c.joints:
                    self._sliders(model.namespace, c)
            if self.series:
                series: Any = ({'label': 'sim time (s)'},) + tuple(
                    {'label': s, 'stroke': _colour(i), 'width': 1.5, 'dash': _dash(s)}
                    for i, s in enumerate(self.series)
                )
                self.readout = gui.add_markdown('')
                self.plot = gui.add_uplot(
                    data=tuple(np.zeros(1) for _ in range(len(self.series) + 1)),
                    series=series,
                    title='joint position and command (rad)',
                    height=180,
                )

    def _sliders(self, namespace: str, c: Any) -> None:
        gui = self.view.server.gui
        topic = ros_names(namespace, c.name)
        trajectory = c.type.endswith(TRAJECTORY)
        pub = rospy.Publisher(
            topic, JointTrajectory if trajectory else Float64, queue_size=1, latch=False
        )
        self.publishers.append(pub)
        sliders: List[Any] = []

        def send(_: Any) -> None:
            if trajectory:
                point = JointTrajectoryPoint(
                    positions=[s.value for s in sliders],
                    time_from_start=rospy.Duration(TRAJECTORY_SECONDS),
                )
                pub.publish(JointTrajectory(joint_names=[j.name for j in c.joints], points=[point]))
            else:
                pub.publish(Float64(sliders[0].value))

        for j in c.joints:
            value = j.command if j.command is not None else j.position
            slider = gui.add_slider(
                j.name,
                min=j.lower,
                max=j.upper,
                step=0.01,
                initial_value=min(j.upper, max(j.lower, round(value, 2))),
            )
            slider.on_update(send)
            sliders.append(slider)
            self.series += ['%s position' % j.name, '%s command' % j.name]

    def update(self, snap: Snapshot, model: ModelView) -> None:
        values: List[float] = []
        rows = []
        for c in model.controllers:
            for j in c.joints:
                command = j.command if j.command is not None else math.nan
                values += [j.position, command]
                rows.append('%s: **%.3f** (command %.3f)' % (j.name, j.position, command))
        if self.readout is None or len(values) != len(self.series):
            return
        self.readout.content = '  \n'.join(rows)
        now = snap.time_ns * 1e-9
        if self.history and now < self.history[-1][0]:
            self.history.clear()  # reset_simulation
        self.history.append((now, values))
        while self.history and self.history[0][0] < now - PLOT_SECONDS:
            self.history.popleft()

    def draw(self) -> None:
        if self.plot is None or len(self.history) < 2:
            return
        times = np.array([t for t, _ in self.history])
        cols = np.array([v for _, v in self.history]).T
        self.plot.data = (times,) + tuple(cols)

    def remove(self) -> None:
        while self.publishers:
            self.publishers.pop().unregister()
        if self.folder is not None:  # once: a removal cut short is finished by the next call
            self.folder.remove()
            self.folder = None


def _panel_key(model: ModelView) -> Tuple[Any, ...]:
    return (model.token, tuple((c.name, c.type, c.state, len(c.joints)) for c in model.controllers))


def _colour(i: int) -> str:
    palette = ('#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2')
    return palette[(i // 2) % len(palette)]


def _dash(series: str) -> List[int]:
    return [4, 4] if series.endswith('command') else []


class CameraPanel:
    """A camera sensor's latest image, as the plugin publishes it, a few times a second."""

    def __init__(self, view: 'WebView', plugin: GazeboRosCamera) -> None:
        s = plugin.sensor
        self.plugin, self.sensor = plugin, s
        self._latest: Optional[Tuple[int, Any]] = None
        self._received_at = -CAMERA_PERIOD
        self.handle = view.server.gui.add_image(
            np.zeros((s.height, s.width, 3), np.uint8),
            label='camera %s (%s)' % (s.name, s.image_topic),
            format='jpeg',
        )
        plugin.viewers.append(self)

    # -- the plugin's threads: a frame is rendered for the page only a few times a second
    def due(self) -> bool:
        return time.monotonic() - self._received_at >= CAMERA_PERIOD

    def show(self, stamp_ns: int, data: Any) -> None:
        self._latest, self._received_at = (stamp_ns, data), time.monotonic()

    def draw(self) -> None:
        latest = self._latest
        if latest is None:
            return
        self._latest = None
        s = self.sensor
        pixels = np.frombuffer(latest[1], np.uint8, count=s.height * s.step)
        rows = pixels.reshape(s.height, s.step)
        if s.format == 'L8':
            image = np.repeat(rows[:, : s.width, None], 3, axis=2)
        else:
            image = rows[:, : s.width * 3].reshape(s.height, s.width, 3)
            if s.format == 'B8G8R8':
                image = image[:, :, ::-1]
        self.handle.image = image

    def remove(self) -> None:
        if self in self.plugin.viewers:
            self.plugin.viewers.remove(self)
        self.handle.remove()


def _moveit_view(view: 'WebView') -> Any:
    """The MoveIt layer (planning scene, planned paths), when moveit_msgs is built."""
    try:
        from .moveit_view import MoveItView
    except ImportError:  # a workspace without moveit_msgs: the world alone
        return None
    return MoveItView(view)


class WebView:
    """The browser view of one world; ``url`` is the address to open."""

    def __init__(
        self,
        sim: Simulation,
        calls: SimThreadCalls,
        loop: WorldLoop,
        host: str = DEFAULT_HOST,
        port: int = DEFAULT_PORT,
        set_paused: Optional[Callable[[bool], None]] = None,
    ) -> None:
        import viser

        self.sim, self.calls, self.loop = sim, calls, loop
        self._set_paused = set_paused or (lambda paused: setattr(loop, 'paused', paused))
        self.snapshots = WorldSnapshots(sim, calls, loop)
        self.server = viser.ViserServer(host=host, port=port, label='arm1 world', verbose=False)
        self.url = 'http://%s:%d' % (
            '[%s]' % host if ':' in host else host,
            self.server.get_port(),
        )
        self.meshes = MeshCache()
        self.models: Dict[str, SceneModel] = {}
        self.panels: Dict[str, ControllerPanel] = {}
        self.cameras: Dict[int, CameraPanel] = {}
        self.selected: Optional[str] = None
        self._dragging = False
        self._drag_handle: Any = None
        self._last: Optional[Snapshot] = None
        self.frames = 0  # scene updates sent (the test's and the bench's frame counter)
        self._running = True
        self._build_gui()
        self.moveit = _moveit_view(self)
        self._thread = threading.Thread(target=self._run, name='web-view', daemon=True)
        self._thread.start()

    # -- GUI -------------------------------------------------------------------------
    def _build_gui(self) -> None:
        server = self.server
        # viser lets any page ask the server to open a tunnel to a public share service:
        # never from the world (docs/web-view.md, Security).
        server.request_share_url = _no_share  # type: ignore[method-assign]
        server.scene.set_up_direction('+z')
        server.initial_camera.position = INITIAL_CAMERA
        server.initial_camera.look_at = INITIAL_LOOK_AT
        server.initial_camera.fov = INITIAL_FOV
        server.on_client_connect(_place_camera)
        server.scene.add_grid('/grid', width=10, height=10, cell_size=0.5, plane='xy')
        gui = server.gui
        gui.configure_theme(control_width='large', show_share_button=False, show_logo=False)
        with gui.add_folder('World'):
            self.status = gui.add_markdown('starting')
            self.pause_button = gui.add_button('Pause')
            self.step_button = gui.add_button('Step')
            self.reset_world_button = gui.add_button('Reset world')
            self.reset_sim_button = gui.add_button('Reset simulation')
        self.pause_button.on_click(lambda _: self._toggle_pause())
        self.step_button.on_click(lambda _: self._call(self._step))
        self.reset_world_button.on_click(lambda _: self._call(self.sim.reset_world))
        self.reset_sim_button.on_click(lambda _: self._call(self.sim.reset_simulation))
        with gui.add_folder('Selected model'):
            self.info = gui.add_markdown(NO_SELECTION)

    def _call(self, fn: Callable[..., Any], *args: Any) -> Any:
        try:
            return self.calls.call(fn, *args)
        except Exception as exc:  # shown, never raised into viser's thread pool
            rospy.logwarn('web view: %s', exc)
            return None

    def _toggle_pause(self) -> None:
        self._call(self._set_paused, not self.loop.paused)

    def _step(self) -> None:
        """One physics step while paused (Gazebo's step button). Physics thread."""
        if self.loop.paused:
            self.sim.step()
            self.loop.clock.after_step(self.sim.time_ns)

    def select(self, name: str) -> None:
        self.selected = name
        if self._drag_handle is not None:
            self._drag_handle.remove()
            self._drag_handle = None
        view = self._last.models.get(name) if self._last else None
        if view is None:
            return
        pos, orn = view.poses[0]
        handle = self.server.scene.add_transform_controls(
            '/drag', scale=0.3, position=pos, wxyz=_wxyz(orn), depth_test=False
        )

        @handle.on_drag_start
        def _(_: Any) -> None:
            self._dragging = True

        @handle.on_update
        def _(_: Any) -> None:
            self._move(name, handle)

        @handle.on_drag_end
        def _(_: Any) -> None:
            self._move(name, handle)
            self._dragging = False

        self._drag_handle = handle
        self._show_info(view)

    def _move(self, name: str, handle: Any) -> None:
        target = ms.State(tuple(float(v) for v in handle.position), _xyzw(handle.wxyz))  # type: ignore[arg-type]
        try:
            self.calls.call(ms.set_model_state, self.sim, name, target, 'world')
        except Exception as exc:
            rospy.logwarn('web view: %s', exc)

    def _show_info(self, view: ModelView) -> None:
        x, y, z, r, p, yw = shown_pose(view.poses[0])
        self.info.content = (
            '**%s**  \nposition %.3f %.3f %.3f m  \nroll pitch yaw %.3f %.3f %.3f rad  \n'
            'links: %s' % (view.name, x, y, z, r, p, yw, ', '.join(view.links))
        )

    # -- the view's thread -----------------------------------------------------------
    def _run(self) -> None:
        last_panel = 0.0
        while self._running and not rospy.is_shutdown():
            if not self.server.get_clients():
                for cam in self.cameras.values():  # nobody watches: nothing rendered for them
                    cam.remove()
                self.cameras.clear()
                time.sleep(IDLE_NAP)
                continue
            started = time.monotonic()
            snap = self.snapshots.take()
            if snap is None:
                break
            try:
                self._show(snap)
                if self.moveit is not None:
                    self.moveit.update(snap.models)
                if started - last_panel >= PANEL_PERIOD:
                    last_panel = started
                    self._panels(snap)
            except Exception as exc:  # a page's trouble never ends the world
                # viser 1.1.1 sets an asyncio.Event from this thread with each message: rarely
                # "deque mutated during iteration" as its loop adds a waiter. The message is
                # queued; the rest of the frame is redone (or finished) by the next one.
                rospy.logerr('web view: %s: %s', type(exc).__name__, exc)
            self.frames += 1
            rest = FRAME_PERIOD - (time.monotonic() - started)
            if rest > 0:
                time.sleep(rest)

    def _show(self, snap: Snapshot) -> None:
        self._last = snap
        with self.server.atomic():
            for name in [n for n in self.models if n not in snap.models]:
                self.models[name].remove()
                del self.models[name]  # only once gone: a cut-short removal is retried
                if name == self.selected:
                    self.select_none()
            self.snapshots.known = frozenset(m.token for m in self.models.values())
            for name, view in snap.models.items():
                scene = self.models.get(name)
                if scene is not None and scene.token != view.token:
                    scene.remove()
                    scene = None
                    self.models.pop(name)
                if scene is None:
                    visuals = snap.visuals.get(view.token)
                    if visuals is None:
                        continue  # its visuals come with the next snapshot
                    scene = self.models[name] = SceneModel(self, view, visuals)
                elif not view.static:
                    scene.move(view.poses)
            self.snapshots.known = frozenset(m.token for m in self.models.values())
            if (
                self.selected in snap.models
                and self._drag_handle is not None
                and not self._dragging
            ):
                pos, orn = snap.models[self.selected].poses[0]
                self._drag_handle.position = pos
                self._drag_handle.wxyz = _wxyz(orn)

    def select_none(self) -> None:
        self.selected = None
        self.info.content = NO_SELECTION  # the model is gone: nothing of it stays on the page
        if self._drag_handle is not None:
            self._drag_handle.remove()
            self._drag_handle = None

    def _panels(self, snap: Snapshot) -> None:
        state = 'paused' if snap.paused else 'running'
        rtf = '%.2f' % snap.rtf if snap.rtf is not None else '-'
        self.status.content = 'sim time **%.3f s**  \nreal-time factor **%s**  \n**%s**' % (
            snap.time_ns * 1e-9,
            rtf,
            state,
        )
        self.pause_button.label = 'Play' if snap.paused else 'Pause'
        for name in [n for n in self.panels if n not in snap.models]:
            self.panels[name].remove()
            del self.panels[name]
        for name, view in snap.models.items():
            if not view.namespace:
                continue
            panel = self.panels.get(name)
            if panel is not None and panel.key != _panel_key(view):
                panel.remove()
                panel = None
            if panel is None:
                panel = self.panels[name] = ControllerPanel(self, view)
            panel.update(snap, view)
            panel.draw()
        if self.selected in snap.models:
            self._show_info(snap.models[self.selected])
        self._sync_cameras()
        for cam in self.cameras.values():
            cam.draw()

    def _sync_cameras(self) -> None:
        plugins = {
            id(p): p
            for m in list(self.sim.models.values())
            for p in list(m.plugins)
            if isinstance(p, GazeboRosCamera)
        }
        for key in [k for k in self.cameras if k not in plugins]:
            self.cameras.pop(key).remove()
        for key, plugin in plugins.items():
            if key not in self.cameras:
                self.cameras[key] = CameraPanel(self, plugin)

    def close(self) -> None:
        self._running = False
        self.snapshots.close()
        for cam in self.cameras.values():
            cam.remove()
        self.server.stop()
