"""Camera sensors: Gazebo's ``<sensor type="camera">`` + gazebo_ros_camera, rendered by pybullet.

ROS-free. A 640 x 480 frame costs 10 to 55 ms of CPU in pybullet's software
renderer (ER_TINY_RENDERER: no GPU, no display needed), more than a 30 Hz frame
period, so frames are rendered in other processes: DIRECT pybullet clients that
mirror the world (same scenery and URDFs; every robot's base pose and joint
positions are sent with each request), two on a two-core machine, so that frame
k+1 renders while frame k does. The physics loop hands a frame over at each
sensor update instant and steps on. When as many frames as there are render
processes are still out, it waits for the oldest (lockstep, as Gazebo's
``--lockstep``): frames are taken at exact sim-time instants, none is skipped,
and rendering slower than real time lowers the real-time factor instead.
Nothing is rendered (and no process started) while nobody wants images.
"""
import collections
import logging
import math
import os
import signal
import socket
import subprocess
import sys
from dataclasses import dataclass
from multiprocessing.connection import Connection

import numpy as np
import pybullet as p

from .urdf_model import UrdfError
from .world import World

log = logging.getLogger('arm1.physics')

CAMERA_PLUGIN = 'libgazebo_ros_camera.so'
# SDF <image><format> -> (sensor_msgs encoding, bytes per pixel)
ENCODINGS = {'R8G8B8': ('rgb8', 3), 'B8G8R8': ('bgr8', 3), 'L8': ('mono8', 1)}
RENDER_TIMEOUT = 30.0  # s of wall time one frame may take before the renderer counts as hung


@dataclass
class CameraSensor:
    """One camera as the description declares it; defaults are SDF's and gazebo_ros_camera's."""
    name: str
    link: str
    update_rate: float = 0.0  # Hz in sim time; 0: as fast as the renderer goes
    horizontal_fov: float = 1.047
    width: int = 320
    height: int = 240
    format: str = 'R8G8B8'
    near: float = 0.1
    far: float = 100.0
    pose: tuple = (0.0,) * 6  # of the sensor in its link's frame
    camera_name: str = ''
    image_topic_name: str = 'image_raw'
    camera_info_topic_name: str = 'camera_info'
    frame_name: str = 'world'
    robot_namespace: str = ''

    @property
    def encoding(self):
        return ENCODINGS[self.format][0]

    @property
    def step(self):
        """Bytes per image row."""
        return self.width * ENCODINGS[self.format][1]

    def topic(self, name):
        """``/<robotNamespace>/<cameraName>/<name>``, as gazebo_ros_camera advertises it."""
        if name.startswith('/'):
            return name
        parts = [s.strip('/') for s in (self.robot_namespace, self.camera_name, name)]
        return '/' + '/'.join(s for s in parts if s)

    @property
    def image_topic(self):
        return self.topic(self.image_topic_name)

    @property
    def camera_info_topic(self):
        return self.topic(self.camera_info_topic_name)


def _number(element, path, default, what, kind=float):
    text = element.findtext(path)
    if text is None or not text.strip():
        return default
    try:
        return kind(text.strip())
    except ValueError:
        raise UrdfError('%s <%s>: %r is not a number' % (what, path, text))


def camera_sensors(description):
    """The camera sensors with the gazebo_ros_camera plugin in a urdf_model.RobotModel."""
    out = []
    for link, sensor in description.sensors:
        plugin = next((pl for pl in sensor.findall('plugin')
                       if pl.get('filename') == CAMERA_PLUGIN), None)
        if sensor.get('type') != 'camera' or plugin is None:
            continue
        name = sensor.get('name', 'camera')
        what = "sensor '%s' on link '%s'" % (name, link)
        if link not in description.links:
            raise UrdfError('%s: the link is not in the URDF' % what)
        cam = sensor.find('camera')
        if cam is None:
            raise UrdfError('%s has no <camera>' % what)
        pose_text = (sensor.findtext('pose') or '').split()
        if pose_text and len(pose_text) != 6:
            raise UrdfError('%s <pose>: %r is not 6 numbers' % (what, sensor.findtext('pose')))
        d = CameraSensor(name, link)
        s = CameraSensor(
            name, link,
            update_rate=_number(sensor, 'update_rate', d.update_rate, what),
            horizontal_fov=_number(cam, 'horizontal_fov', d.horizontal_fov, what),
            width=_number(cam, 'image/width', d.width, what, int),
            height=_number(cam, 'image/height', d.height, what, int),
            format=(cam.findtext('image/format') or d.format).strip(),
            near=_number(cam, 'clip/near', d.near, what),
            far=_number(cam, 'clip/far', d.far, what),
            pose=tuple(float(v) for v in pose_text) if pose_text else d.pose,
            camera_name=(plugin.findtext('cameraName') or '').strip(),
            image_topic_name=(plugin.findtext('imageTopicName') or d.image_topic_name).strip(),
            camera_info_topic_name=(plugin.findtext('cameraInfoTopicName')
                                    or d.camera_info_topic_name).strip(),
            frame_name=(plugin.findtext('frameName') or d.frame_name).strip(),
            robot_namespace=(plugin.findtext('robotNamespace') or '').strip())
        # The plugin's own <updateRate> throttles what the sensor produces.
        throttle = _number(plugin, 'updateRate', 0.0, what)
        if throttle > 0:
            s.update_rate = min(s.update_rate, throttle) if s.update_rate > 0 else throttle
        if s.width <= 0 or s.height <= 0 or not 0 < s.horizontal_fov < math.pi:
            raise UrdfError('%s: image %dx%d with horizontal_fov %g cannot be rendered'
                            % (what, s.width, s.height, s.horizontal_fov))
        if s.format not in ENCODINGS:
            log.warning('%s: image format %s is not supported, rendering R8G8B8 (rgb8)',
                        what, s.format)
            s.format = 'R8G8B8'
        out.append(s)
    return out


# ------------------------------------------------------------------------ geometry
def intrinsics(width, height, horizontal_fov):
    """CameraInfo's K (3x3) and P (3x4), row-major, of an ideal pinhole with square pixels.

    The principal point is the image centre in ROS's pixel convention (pixel
    centres at integers), i.e. (w - 1) / 2; gazebo_ros_camera puts it at
    (w + 1) / 2, one pixel off the image it renders.
    """
    f = width / (2.0 * math.tan(horizontal_fov / 2.0))
    cx, cy = (width - 1) / 2.0, (height - 1) / 2.0
    return [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0], \
        [f, 0.0, cx, 0.0, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0]


def sensor_pose(sensor, link_position, link_orientation):
    """World pose of the sensor: its link's pose composed with the sensor's <pose>."""
    return p.multiplyTransforms(link_position, link_orientation, sensor.pose[:3],
                                p.getQuaternionFromEuler(sensor.pose[3:]))


def view_matrix(position, orientation):
    """Gazebo's camera looks along its frame's +x with +z up."""
    r = p.getMatrixFromQuaternion(orientation)  # row-major 3x3
    forward, up = (r[0], r[3], r[6]), (r[2], r[5], r[8])
    target = [a + b for a, b in zip(position, forward)]
    return p.computeViewMatrix(position, target, up)


def projection_matrix(sensor):
    aspect = sensor.width / float(sensor.height)
    vertical_fov = 2.0 * math.atan(math.tan(sensor.horizontal_fov / 2.0) / aspect)
    return p.computeProjectionMatrixFOV(math.degrees(vertical_fov), aspect, sensor.near,
                                        sensor.far)


def encode(rgba, fmt):
    """Image bytes in the sensor's format from pybullet's RGBA (height x width x 4) pixels."""
    if fmt == 'B8G8R8':
        return np.ascontiguousarray(rgba[:, :, 2::-1]).tobytes()
    if fmt == 'L8':  # luma, ITU-R BT.601
        return np.rint(rgba[:, :, :3] @ np.array([0.299, 0.587, 0.114])).astype(np.uint8).tobytes()
    return np.ascontiguousarray(rgba[:, :, :3]).tobytes()


def render(client, sensor, link_position, link_orientation):
    """One frame of ``sensor`` from a pybullet client, as image bytes (``sensor.step`` per row)."""
    w, h = sensor.width, sensor.height
    _, _, rgba, _, _ = p.getCameraImage(
        w, h, view_matrix(*sensor_pose(sensor, link_position, link_orientation)),
        projection_matrix(sensor), renderer=p.ER_TINY_RENDERER,
        flags=p.ER_NO_SEGMENTATION_MASK, physicsClientId=client)
    return encode(np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4), sensor.format)


# ------------------------------------------------------------------ render process
class RenderError(RuntimeError):
    """A render process died or hung."""


def _serve(conn):
    """The render process: a headless mirror of the world that answers render requests."""
    world = None
    try:
        world_config, robots = conn.recv()
        world = World(world_config, gui=False)
        mirror = {name: world.load_robot(*args) for name, args in robots.items()}
        while True:
            request = conn.recv()
            kind = request[0]
            if kind == 'add':
                mirror[request[1]] = world.load_robot(*request[2])
            elif kind == 'remove':
                robot = mirror.pop(request[1], None)
                if robot is not None:
                    world.remove_robot(robot)
            elif kind == 'render':
                _, model, sensor, states = request
                try:
                    for name, state in states.items():
                        mirror[name].set_state(state)
                    reply = ('frame', render(world.client, sensor,
                                             *mirror[model].link_pose(sensor.link)))
                except Exception as exc:  # reported to the world, which logs it
                    reply = ('error', '%s: %s' % (type(exc).__name__, exc))
                conn.send(reply)
    except (EOFError, OSError):  # the world has gone
        pass
    finally:
        if world is not None:
            world.close()


def render_process_main(fd):
    """Entry point of the render process; ``fd`` is its end of a socket pair."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C of the launch is the world's to handle
    _serve(Connection(fd))


class RenderProcess:
    """One render process, seen from the world: requests go in, replies come back in order.

    A plain child interpreter (not multiprocessing's 'spawn', which re-runs the
    parent's main script) on a socket pair; it exits when the world's end closes.
    """

    def __init__(self, world_config, robots):
        """``robots``: {model name: World.load_robot arguments} to mirror from the start."""
        ours, theirs = socket.socketpair()
        for end in (ours, theirs):
            end.setblocking(True)  # rospy sets a default socket timeout, which means non-blocking
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
        self.process = subprocess.Popen(
            [sys.executable, '-c', 'import sys; from arm1.physics.camera import '
             'render_process_main; render_process_main(int(sys.argv[1]))', str(theirs.fileno())],
            pass_fds=[theirs.fileno()], env=env, stdout=subprocess.DEVNULL)
        theirs.close()
        self._conn = Connection(ours.detach())
        self.in_flight = 0  # render requests not answered yet
        self.send((world_config, dict(robots)))

    def send(self, message):
        try:
            self._conn.send(message)
        except (OSError, ValueError) as exc:
            raise RenderError('a render process is gone (%s)' % exc)

    def ready(self):
        """Is a reply waiting?"""
        return self._conn.poll()

    def receive(self):
        """The next reply, ``('frame', data)`` or ``('error', text)``; waits for it."""
        try:
            if not self._conn.poll(RENDER_TIMEOUT):
                raise RenderError('no frame from a render process in %g s' % RENDER_TIMEOUT)
            return self._conn.recv()
        except (EOFError, OSError) as exc:
            raise RenderError('a render process is gone (%s)' % (exc or 'it exited'))

    def close(self):
        self._conn.close()  # the process sees EOF and exits
        try:
            self.process.wait(2.0)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()


# ------------------------------------------------------------------ sensor updates
def _nobody():
    return False


class Camera:
    """A camera of a spawned model, as the world updates it.

    Whoever publishes its output sets ``wants_image`` / ``wants_info`` (is
    anyone listening?) and ``on_image(stamp_ns, data)`` / ``on_info(stamp_ns)``.
    """

    def __init__(self, model, sensor):
        self.model, self.sensor = model, sensor
        self.period_ns = int(round(1e9 / sensor.update_rate)) if sensor.update_rate > 0 else 0
        self.next_ns = 0
        self.last_ns = -1
        self.in_flight = 0  # frames asked for and not handed over yet
        self.frames = 0  # rendered and handed over
        self.wants_image = self.wants_info = _nobody
        self.on_image = self.on_info = None

    def due(self, now_ns):
        """True at the sensor's update instants (always, if its rate is 0)."""
        if not self.period_ns:
            return True
        if now_ns < self.last_ns:  # time went back (reset_simulation)
            self.next_ns = now_ns
        self.last_ns = now_ns
        if now_ns < self.next_ns:
            return False
        self.next_ns += self.period_ns
        if self.next_ns <= now_ns:  # e.g. the first update
            self.next_ns = now_ns + self.period_ns
        return True

    def deliver(self, stamp_ns, data):
        self.frames += 1
        if self.on_image is not None:
            self.on_image(stamp_ns, data)


def default_render_processes():
    """Two where there are two cores: frame k+1 renders while frame k does."""
    return max(1, min(2, os.cpu_count() or 1))


class SensorManager:
    """Updates the cameras after each physics step (Gazebo's sensor manager, in lockstep).

    With N render processes a camera may have N frames in flight; at an update
    instant with N in flight the world waits for the oldest. Frames are handed
    over in the order they were asked for.
    """

    def __init__(self, world_config, render_processes=None, renderer_factory=RenderProcess):
        self.world_config = world_config
        self.render_processes = render_processes or default_render_processes()
        self.cameras = []
        self._robots = {}  # model name -> World.load_robot arguments, to mirror
        self._renderer_factory = renderer_factory
        self.renderers = []  # started at the first frame anyone wants
        self._in_flight = collections.deque()  # (camera, stamp_ns, renderer), oldest first
        self.failed = False

    def add_robot(self, name, load_args, sensors=()):
        """Mirror a spawned robot; returns Camera objects for its ``camera_sensors``."""
        cameras = [Camera(name, s) for s in sensors]
        self._robots[name] = load_args
        self._to_renderers(('add', name, load_args))
        self.cameras.extend(cameras)
        return cameras

    def remove_robot(self, name):
        self._robots.pop(name, None)
        self.cameras = [c for c in self.cameras if c.model != name]
        self._to_renderers(('remove', name))

    def _to_renderers(self, message):
        try:
            for r in self.renderers:
                r.send(message)
        except RenderError as exc:
            self._fail(exc)

    def update(self, now_ns, states):
        """After a physics step at ``now_ns``; ``states()`` gives every robot's state."""
        try:
            while self._in_flight and self._in_flight[0][2].ready():
                self._hand_over()
            for cam in self.cameras:
                if not cam.due(now_ns):
                    continue
                if cam.wants_image() and not self.failed:
                    self._start()
                    depth = len(self.renderers)
                    if not cam.period_ns and cam.in_flight >= depth:
                        continue  # rate 0: as fast as the renderers go
                    while cam.in_flight >= depth:
                        self._hand_over()  # lockstep: the world waits for the renderers
                    self._request(cam, now_ns, states())
                elif cam.period_ns and cam.wants_info() and cam.on_info is not None:
                    cam.on_info(now_ns)
        except RenderError as exc:
            self._fail(exc)

    def _start(self):
        if not self.renderers:
            self.renderers = [self._renderer_factory(self.world_config, self._robots)
                              for _ in range(self.render_processes)]
            log.info('cameras: %d render process(es) started (pid %s)', len(self.renderers),
                     ', '.join(str(getattr(getattr(r, 'process', None), 'pid', '?'))
                               for r in self.renderers))

    def _request(self, cam, now_ns, states):
        renderer = min(self.renderers, key=lambda r: r.in_flight)
        renderer.send(('render', cam.model, cam.sensor, states))
        renderer.in_flight += 1
        cam.in_flight += 1
        self._in_flight.append((cam, now_ns, renderer))

    def _hand_over(self):
        """Wait for the oldest frame in flight and hand it to its camera."""
        cam, stamp_ns, renderer = self._in_flight[0]
        kind, payload = renderer.receive()
        self._in_flight.popleft()
        renderer.in_flight -= 1
        cam.in_flight -= 1
        if kind == 'frame':
            cam.deliver(stamp_ns, payload)
        else:
            log.error("camera '%s': render failed: %s", cam.sensor.name, payload)

    def _fail(self, exc):
        log.error('cameras: %s; no more images from %s', exc,
                  ', '.join(c.sensor.name for c in self.cameras) or 'any camera')
        self.failed = True
        self.close()

    def close(self):
        for r in self.renderers:
            r.close()
        self.renderers = []
        self._in_flight.clear()
        for cam in self.cameras:
            cam.in_flight = 0
