"""Cameras: sensors from the URDF (description.camera_sensor), their geometry, scheduling and
rendering."""

import io
import math
import os
import signal
import struct
import time
import zlib

import numpy as np
import pybullet as p
import pytest
from conftest import WORLD_FILE, box_link
from PIL import Image

from _arm1sim.description.camera_sensor import CameraSensor, camera_sensors
from _arm1sim.description.limits import LimitError, Limits
from _arm1sim.description.sdf_world import WorldConfig, read_world
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.goal.image import is_uniform, png
from _arm1sim.physics import sensor_manager
from _arm1sim.physics.camera_geometry import intrinsics, view_matrix
from _arm1sim.physics.render_process import RenderError, encode, render
from _arm1sim.physics.sensor_manager import Camera, SensorManager
from _arm1sim.sim.pacer import Pacer
from _arm1sim.sim.simulation import Simulation, SpawnError

STEP_NS = 1000000  # 1 ms physics step


def robot_with(sensor_xml, link='b'):
    return (
        '<robot name="r">'
        + box_link('a')
        + box_link('b')
        + """
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
  <gazebo reference="%s">%s</gazebo></robot>"""
        % (link, sensor_xml)
    )


def sensors_of(xml):
    return camera_sensors(parse_urdf(xml))


# ------------------------------------------------------------------------- parsing
def test_arm1_camera_as_the_reference_gives_it(arm1_urdf):
    model = parse_urdf(arm1_urdf)
    cam_joint = model.joints['camera_joint']
    assert (cam_joint.type, cam_joint.parent, cam_joint.child) == ('fixed', 'link4', 'camera_link')
    [s] = camera_sensors(model)
    assert (s.name, s.link) == ('rgb_camera', 'camera_link')
    assert (s.update_rate, s.horizontal_fov) == (30, 1.4)
    assert (s.width, s.height, s.format, s.near, s.far) == (640, 480, 'R8G8B8', 0.02, 300)
    assert (s.encoding, s.step) == ('rgb8', 1920)
    assert s.image_topic == '/rgb_camera/image_raw'
    assert s.camera_info_topic == '/rgb_camera/camera_info'
    assert s.frame_name == 'camera_link'


def test_defaults_namespace_and_plugin_rate():
    [s] = sensors_of(
        robot_with("""
      <sensor type="camera" name="eye"><update_rate>60</update_rate><camera/>
        <plugin name="c" filename="libgazebo_ros_camera.so">
          <robotNamespace>/bot</robotNamespace><cameraName>front</cameraName>
          <updateRate>10</updateRate><cameraInfoTopicName>/info</cameraInfoTopicName>
        </plugin></sensor>""")
    )
    # SDF's and gazebo_ros_camera's defaults; the plugin's updateRate throttles the sensor
    assert (s.width, s.height, s.format, s.horizontal_fov) == (320, 240, 'R8G8B8', 1.047)
    assert (s.near, s.far, s.frame_name, s.update_rate) == (0.1, 100.0, 'world', 10.0)
    assert s.image_topic == '/bot/front/image_raw'
    assert s.camera_info_topic == '/info'  # absolute names stay as they are


def test_only_cameras_with_the_ros_plugin_are_rendered():
    xml = robot_with("""
      <sensor type="ray" name="laser"><plugin name="l" filename="libgazebo_ros_laser.so"/></sensor>
      <sensor type="camera" name="bare"><camera/></sensor>""")
    assert sensors_of(xml) == []


def test_other_formats_and_bad_values():
    fmt = (
        '<sensor type="camera" name="c"><camera><image><format>%s</format></image></camera>'
        '<plugin filename="libgazebo_ros_camera.so"/></sensor>'
    )
    assert sensors_of(robot_with(fmt % 'L8'))[0].encoding == 'mono8'
    assert sensors_of(robot_with(fmt % 'B8G8R8'))[0].step == 320 * 3
    assert sensors_of(robot_with(fmt % 'FLOAT32'))[0].encoding == 'rgb8'  # with a warning
    bad = robot_with(
        '<sensor type="camera" name="c"><camera><image><width>wide</width></image>'
        '</camera><plugin filename="libgazebo_ros_camera.so"/></sensor>'
    )
    with pytest.raises(UrdfError, match="sensor 'c' on link 'b'.*wide"):
        sensors_of(bad)
    nowhere = robot_with(
        '<sensor type="camera" name="c"><camera/>'
        '<plugin filename="libgazebo_ros_camera.so"/></sensor>',
        link='ghost',
    )
    # Gazebo's URDF->SDF puts an extension into its link only: on no link, no camera (the
    # warning at spawn is test_unplaced_sensor's)
    assert sensors_of(nowhere) == []


# ------------------------------------------------------------------------ geometry
def test_camera_info_k_and_p_from_the_field_of_view_and_size():
    k, proj = intrinsics(640, 480, 1.4)
    f = 320 / math.tan(0.7)
    assert f == pytest.approx(379.9, abs=0.1)
    assert k == pytest.approx([f, 0, 319.5, 0, f, 239.5, 0, 0, 1])
    assert proj == pytest.approx([f, 0, 319.5, 0, 0, f, 239.5, 0, 0, 0, 1, 0])


def test_optical_axis_is_the_frame_x_axis():
    # a camera frame turned 90 deg about z looks along world +y
    q = p.getQuaternionFromEuler((0, 0, math.pi / 2))
    view = np.array(view_matrix((1, 2, 3), q)).reshape(4, 4).T  # OpenGL: column-major
    looking = -view[2, :3]  # the view's -z row is the viewing direction
    assert looking == pytest.approx([0, 1, 0], abs=1e-6)
    assert view[1, :3] == pytest.approx([0, 0, 1], abs=1e-6)  # image up = frame +z


def test_pixels_in_each_format():
    rgba = np.array([[[200, 100, 50, 255], [0, 0, 255, 255]]], np.uint8)
    assert encode(rgba, 'R8G8B8') == bytes([200, 100, 50, 0, 0, 255])
    assert encode(rgba, 'B8G8R8') == bytes([50, 100, 200, 255, 0, 0])
    assert encode(rgba, 'L8') == bytes([124, 29])  # 0.299 R + 0.587 G + 0.114 B


# ---------------------------------------------------------------------- scheduling
def test_updates_at_30_hz_in_sim_time():
    cam = Camera('m', CameraSensor('c', 'l', update_rate=30))
    ticks = [t for t in range(STEP_NS, 3 * 10**9, STEP_NS) if cam.due(t)]
    assert len(ticks) == 90
    assert set(np.diff(ticks)) <= {33 * STEP_NS, 34 * STEP_NS}
    # reset_simulation: time back to zero, updates start again at once
    assert cam.due(STEP_NS) and not cam.due(2 * STEP_NS)


class FakeClock:
    """Sim time as the fake render processes see it (a frame takes ``render_ns`` of it)."""

    now = 0


class FakeRenderer:
    """A render process that finishes a frame ``render_ns`` after it was asked (None: never on
    its own). receive() before a frame is ready counts as a wait of the world."""

    def __init__(self, config, robots, clock=None, render_ns=None):
        self.robots = dict(robots)
        self.requests = []  # (camera name, states)
        self.done_at = []  # per request out: clock time it is ready
        self.replies = 0
        self.waited = 0
        self.in_flight = 0
        self.clock, self.render_ns = clock, render_ns
        self.dead = self.closed = False

    def send(self, message):
        if self.dead:
            raise RenderError('fake render process is gone')
        if message[0] == 'add':
            self.robots[message[1]] = message[2]
        elif message[0] == 'remove':
            del self.robots[message[1]]
        else:
            self.requests.append((message[2].name, message[3]))
            self.done_at.append(None if self.render_ns is None else self.clock.now + self.render_ns)

    def ready(self):
        return self.dead or (
            bool(self.done_at) and self.done_at[0] is not None and self.done_at[0] <= self.clock.now
        )

    def receive(self, timeout=None):
        if self.dead:
            raise RenderError('fake render process is gone')
        if not self.ready():
            self.waited += 1  # a real one would block here
        self.done_at.pop(0)
        self.replies += 1
        return 'frame', b'frame %d' % self.replies

    def close(self, kill=False):
        self.closed = True


def manager_with_fakes(processes, lockstep=False, render_ns=None, limits=None, **kwargs):
    made, clock = [], FakeClock()

    def factory(config, robots):
        made.append(FakeRenderer(config, robots, clock, render_ns))
        return made[-1]

    config = WorldConfig(lockstep=lockstep, limits=limits or Limits())
    return SensorManager(config, processes, factory, **kwargs), made, clock


def watched(cam):
    """Subscribe to a camera: returns the list of (stamp, data) it will hand over."""
    frames = []
    cam.wants_image, cam.on_image = (lambda: True), (lambda t, d: frames.append((t, d)))
    return frames


def run(manager, clock, start_ns, end_ns, states=None):
    for t in range(start_ns, end_ns, STEP_NS):
        clock.now = t
        manager.update(t, states or (lambda: {'m': t}))


@pytest.mark.parametrize('lockstep', [False, True])
def test_nothing_is_rendered_without_a_subscriber(lockstep):
    manager, made, clock = manager_with_fakes(2, lockstep)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    infos = []
    cam.on_info = infos.append
    run(manager, clock, STEP_NS, 10**9)
    assert made == [] and infos == []  # no render process was even started
    cam.wants_info = lambda: True  # camera_info alone: published without rendering
    run(manager, clock, 10**9, 2 * 10**9)
    assert made == [] and len(infos) == 30


@pytest.mark.parametrize('processes', [1, 2])
def test_lockstep_every_update_instant_gets_its_frame_in_order(processes):
    manager, made, clock = manager_with_fakes(processes, lockstep=True)
    manager.add_robot('other', ('other.urdf',))
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    frames = watched(cam)
    run(manager, clock, STEP_NS, 10**9)  # the robots' state at each step is its time
    assert len(made) == processes
    assert all(set(r.robots) == {'other', 'm'} for r in made)  # each mirrors every robot
    asked = sorted(states['m'] for r in made for _, states in r.requests)
    assert len(asked) == 30
    assert set(np.diff(asked)) <= {33 * STEP_NS, 34 * STEP_NS}
    # the renderers never finished on their own: the world waited, so that no more than one
    # frame per render process was ever out; frames came in order, each with its instant
    assert [t for t, _ in frames] == asked[: 30 - processes]
    assert sum(r.waited for r in made) == 30 - processes
    if processes == 2:  # the requests alternate between the two
        assert [len(r.requests) for r in made] == [15, 15]
    manager.remove_robot('m')
    assert manager.cameras == [] and all(set(r.robots) == {'other'} for r in made)


def test_default_timing_never_waits_and_the_image_rate_drops():
    # one render process, 100 ms of rendering per frame, a 30 Hz camera
    manager, made, clock = manager_with_fakes(1, render_ns=100 * STEP_NS)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    frames = watched(cam)
    run(manager, clock, STEP_NS, 3 * 10**9)
    [r] = made
    assert r.waited == 0, 'the physics waited for a render process'
    # 10 frames a second instead of 30; the instants in between were skipped
    assert 28 <= len(frames) <= 30, len(frames)
    assert cam.skipped >= 40 and cam.frames == len(frames)


def test_a_late_frame_shows_the_newest_state_stamped_with_its_time():
    # 50 ms per frame: the renderer frees up between two 30 Hz instants
    manager, made, clock = manager_with_fakes(1, render_ns=50 * STEP_NS)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    frames = watched(cam)
    run(manager, clock, STEP_NS, 10**9)
    stamps = [t for t, _ in frames]
    # asked for as soon as the renderer was free, with the state of that step, stamped so
    assert stamps[:5] == [STEP_NS + k * 50 * STEP_NS for k in range(5)]
    assert [states['m'] for _, states in made[0].requests][:5] == stamps[:5]
    assert stamps[1] % (10**9 // 30) not in (0, STEP_NS)  # not an update instant: late
    assert made[0].waited == 0


def test_two_render_processes_keep_every_instant_without_waiting():
    manager, made, clock = manager_with_fakes(2, render_ns=50 * STEP_NS)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    frames = watched(cam)
    run(manager, clock, STEP_NS, 2 * 10**9)
    stamps = [t for t, _ in frames]
    assert set(np.diff(stamps)) <= {33 * STEP_NS, 34 * STEP_NS}  # every instant, in order
    assert len(stamps) >= 58 and cam.skipped == 0
    assert sum(r.waited for r in made) == 0


@pytest.mark.parametrize('lockstep', [False, True])
def test_rate_zero_renders_as_fast_as_the_render_processes_go(lockstep):
    manager, made, clock = manager_with_fakes(2, lockstep)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=0)])
    watched(cam)
    run(manager, clock, STEP_NS, 100 * STEP_NS)
    # both busy from the first steps on, and the world never waited for them
    assert [len(r.requests) for r in made] == [1, 1]
    assert sum(r.replies for r in made) == 0
    # and with 20 ms frames, each keeps going
    for r in made:
        r.render_ns, r.done_at = 20 * STEP_NS, [clock.now]
    run(manager, clock, 100 * STEP_NS, 300 * STEP_NS)
    assert sum(r.waited for r in made) == 0
    assert cam.frames >= 15


def test_a_deleted_models_camera_gets_no_late_frame_and_its_name_can_come_back():
    manager, made, clock = manager_with_fakes(2, render_ns=50 * STEP_NS)
    [old] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    old_frames = watched(old)
    run(manager, clock, STEP_NS, 40 * STEP_NS)
    assert old.in_flight == 2 and old_frames == []  # two frames out
    manager.remove_robot('m')
    assert all('m' not in r.robots for r in made)  # gone from the render mirrors
    [new] = manager.add_robot('m', ('m2.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    new_frames = watched(new)
    run(manager, clock, 40 * STEP_NS, 10**9)
    assert old_frames == [] and old.frames == 0
    assert len(new_frames) >= 25 and all(r.robots['m'] == ('m2.urdf',) for r in made)


# ---------------------------------------------------------------------------- limits
BIG = (
    '<sensor type="camera" name="big"><update_rate>%s</update_rate><camera><image>'
    '<width>%d</width><height>%d</height></image></camera>'
    '<plugin filename="libgazebo_ros_camera.so"/></sensor>'
)


def test_a_camera_over_the_pixel_limit_is_refused_naming_limit_value_and_parameter():
    description = parse_urdf(robot_with(BIG % (30, 6000, 6000)))
    with pytest.raises(LimitError) as err:
        camera_sensors(description, Limits())
    msg = str(err.value)
    assert "sensor 'big' on link 'b' (6000x6000)" in msg
    assert 'camera pixels is 36000000, over the limit of 16777216' in msg
    assert '~limits/camera_pixels' in msg
    [s] = camera_sensors(description, Limits(camera_pixels=36_000_000))  # raised: fine
    assert (s.width, s.height, s.update_rate) == (6000, 6000, 30)


def test_a_camera_over_the_rate_limit_is_refused():
    description = parse_urdf(robot_with(BIG % (5000, 64, 48)))
    with pytest.raises(
        LimitError,
        match=r"sensor 'big'.*sensor update rate is 5000, over the "
        r"limit of 1000 .*~limits/sensor_update_rate",
    ):
        camera_sensors(description, Limits())
    assert camera_sensors(description, Limits(sensor_update_rate=5000))[0].update_rate == 5000


@pytest.mark.parametrize('rate', ['nan', 'inf', '-1'])
def test_a_rate_that_is_no_rate_is_refused(rate):
    with pytest.raises(UrdfError, match="sensor 'big'.*update_rate"):
        sensors_of(robot_with(BIG % (rate, 64, 48)))


def test_the_worlds_render_budget_is_checked_before_anything_changes():
    limits = Limits(render_pixels_per_second=150e6)
    manager, made, clock = manager_with_fakes(1, limits=limits)
    [arm_cam] = manager.add_robot(
        'arm', ('arm.urdf',), [CameraSensor('eye', 'l', 30, width=640, height=480)]
    )
    watched(arm_cam)
    run(manager, clock, STEP_NS, 3 * STEP_NS)  # a render process runs and mirrors the arm
    # 2000 x 2000 at 30 Hz = 120 Mpx/s; with the arm's 9.2 Mpx/s, under 150
    manager.add_robot('m1', ('m1.urdf',), [CameraSensor('c1', 'l', 30, width=2000, height=2000)])
    before = (list(manager.cameras), dict(made[0].robots))
    with pytest.raises(LimitError) as err:  # rate 0 counts as 60 Hz: 1 Mpx x 60 = 60 Mpx/s more
        manager.add_robot('m2', ('m2.urdf',), [CameraSensor('c2', 'l', 0, width=1000, height=1000)])
    msg = str(err.value)
    assert "camera 'c2' (1000x1000 at as fast as possible) with the world's 2 other" in msg
    assert 'render pixels per second is 189216000, over the limit of 150000000' in msg
    assert '~limits/render_pixels_per_second' in msg
    assert (list(manager.cameras), dict(made[0].robots)) == before  # nothing changed
    manager.remove_robot('m1')  # frees its share
    manager.add_robot('m2', ('m2.urdf',), [CameraSensor('c2', 'l', 0, width=1000, height=1000)])


def test_spawning_a_6000x6000_camera_is_refused_and_leaves_nothing_behind(world_sim):
    sim = world_sim()
    with pytest.raises(
        SpawnError,
        match=r"cannot spawn 'big'.*camera pixels is 36000000.*"
        r"~limits/camera_pixels",
    ):
        sim.spawn_urdf('big', camera_on_a_box(6000, 6000, 30))
    # raised, the world's render budget (1.08 Gpx/s) still says no, and names its own limit
    sim.limits.camera_pixels = 36_000_000
    with pytest.raises(
        SpawnError, match='render pixels per second is 1080000000.*~limits/render_pixels_per_second'
    ):
        sim.spawn_urdf('big', camera_on_a_box(6000, 6000, 30))
    assert not sim.models and not sim.world.robots and not sim.sensors.cameras
    sim.limits.render_pixels_per_second = 1.1e9
    model = sim.spawn_urdf('big', camera_on_a_box(6000, 6000, 30))
    assert model.cameras[0].sensor.pixels == 36_000_000


# --------------------------------------------------------------- failing render processes
@pytest.mark.parametrize('lockstep', [False, True])
def test_a_dead_render_process_is_replaced_and_the_world_goes_on(caplog, lockstep):
    manager, made, clock = manager_with_fakes(
        2, lockstep, render_ns=20 * STEP_NS, restart_delay=0.0
    )
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('eye', 'l', update_rate=30)])
    watched(cam)
    run(manager, clock, STEP_NS, 200 * STEP_NS)
    before = cam.frames
    made[0].dead = True
    run(manager, clock, 200 * STEP_NS, 10**9)
    assert made[0].closed and made[0] not in manager.renderers
    assert len(made) == 3 and len(manager.renderers) == 2 and manager.restarts == 1
    assert cam.frames - before >= 20 and not manager.failed
    assert any(
        "'eye'" in r.message and 'gone' in r.message
        for r in caplog.records
        if r.levelname == 'ERROR'
    )


def test_a_hung_render_process_is_replaced(monkeypatch):
    monkeypatch.setattr(sensor_manager, 'render_timeout', lambda sensor: 0.05)
    manager, made, clock = manager_with_fakes(1, render_ns=None, restart_delay=0.0)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('eye', 'l', update_rate=30)])
    watched(cam)
    run(manager, clock, STEP_NS, 10 * STEP_NS)
    time.sleep(0.1)
    run(manager, clock, 10 * STEP_NS, 20 * STEP_NS)
    assert made[0].closed and len(made) == 2 and cam.lost == 1
    assert made[1].requests, 'the replacement got no request'


def test_cameras_give_up_after_repeated_failures_and_say_so(caplog):
    started = []

    def broken(config, robots):
        started.append(1)
        raise OSError('no such interpreter')

    manager = SensorManager(WorldConfig(), 1, broken, restart_delay=0.0, max_restarts=3)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('eye', 'l', update_rate=30)])
    watched(cam)
    for t in range(STEP_NS, 100 * STEP_NS, STEP_NS):
        manager.update(t, lambda: {})  # returns: the world goes on
    assert manager.failed and len(started) == 4  # the first and three replacements
    assert any('no more images' in r.message and "'eye'" in r.message for r in caplog.records)


# ------------------------------------------------------------------------ rendering
@pytest.fixture
def arm1_sim(arm1_urdf, find_package):
    sim = Simulation(read_world(WORLD_FILE))
    model = sim.spawn_urdf('arm1', arm1_urdf, find_package=find_package)
    yield sim, model
    sim.close()


def pixels(sensor, data):
    return np.frombuffer(data, np.uint8).reshape(sensor.height, sensor.width, 3)


def test_blank_sky_is_uniform_and_the_arm_over_the_ground_is_not(arm1_sim):
    sim, model = arm1_sim
    sensor = model.cameras[0].sensor
    client = sim.world.client
    up = p.getQuaternionFromEuler((0, -math.pi / 2, 0))  # frame +x to world +z
    sky = render(client, sensor, (0, 0, 1), up)
    assert len(sky) == sensor.step * sensor.height
    assert is_uniform(sky, sensor.width, sensor.height, sensor.step)
    # from 0.3 m away, looking back and down at the arm
    yaw, pitch = math.atan2(-0.3, -0.3), math.atan2(0.15, 0.3 * math.sqrt(2))
    arm = render(client, sensor, (0.3, 0.3, 0.2), p.getQuaternionFromEuler((0, pitch, yaw)))
    assert not is_uniform(arm, sensor.width, sensor.height, sensor.step)
    img = pixels(sensor, arm)
    orange = (img[:, :, 0] > 200) & (img[:, :, 1] > 80) & (img[:, :, 1] < 170) & (img[:, :, 2] < 60)
    assert orange.sum() > 200, 'the orange links are not in the picture'


def test_render_processes_mirror_the_arm(arm1_sim):
    sim, model = arm1_sim
    cam = model.cameras[0]
    frames = []
    cam.wants_image, cam.on_image = (lambda: True), (lambda t, d: frames.append((t, d)))
    # arm up: the camera at its tip sees only the sky; then flat: the horizon
    for joint2, at in ((1.57, 0), (0.01, 40 * STEP_NS)):
        model.robot.set_joint_positions({'joint2': joint2})
        sim.sensors.update(at, sim._robot_states)
    sim.sensors.drain()
    s = cam.sensor
    (t0, up), (t1, flat) = frames
    assert (t0, t1) == (0, 40 * STEP_NS)
    assert is_uniform(up, s.width, s.height, s.step)
    assert not is_uniform(flat, s.width, s.height, s.step)
    assert cam.frames == 2
    procs = [r.process for r in sim.sensors.renderers]
    assert len(procs) == sim.sensors.render_processes
    sim.close()
    assert all(proc.poll() is not None for proc in procs)  # they end with the simulation


def camera_on_a_box(width=64, height=48, rate=30):
    """A one-link model (no joints at all) with a camera looking down at the ground."""
    return (
        '<robot name="box">%s<gazebo reference="body"><sensor type="camera" name="eye">'
        '<update_rate>%g</update_rate><pose>0 0 0.5 0 1.2 0</pose><camera><image>'
        '<width>%d</width><height>%d</height></image></camera>'
        '<plugin filename="libgazebo_ros_camera.so"><cameraName>eye</cameraName></plugin>'
        '</sensor></gazebo></robot>' % (box_link('body'), rate, width, height)
    )


@pytest.fixture
def world_sim():
    sims = []

    def make(lockstep=False):
        config = read_world(WORLD_FILE)
        config.lockstep = lockstep
        sims.append(Simulation(config))
        return sims[-1]

    yield make
    for sim in sims:
        sim.close()


def step_until(sim, predicate, timeout, pacer=None):
    """Step (at real time) until ``predicate()``."""
    pacer = pacer or Pacer(sim.period)
    deadline = time.monotonic() + timeout
    while not predicate():
        assert time.monotonic() < deadline, 'timed out'
        sim.step()
        pacer.wait()


def run_queue_seconds():
    """Seconds the calling thread has waited for a CPU so far: the second field of the
    kernel's schedstat, complete whenever the thread is running."""
    with open('/proc/thread-self/schedstat') as f:
        return int(f.read().split()[1]) * 1e-9


def time_blocked_in(obj, names, monkeypatch):
    """Wrap methods ``names`` of ``obj``: the returned list gets, per call, the seconds the
    calling thread slept in it (on a pipe, a process, a thread or a lock). That is its wall time
    less the CPU time it ran and the time it waited for a CPU, which is what a busy machine
    adds; so load does not fake a wait."""
    slept = []

    def timed(method):
        def call(*args, **kwargs):
            wall, cpu, queued = time.perf_counter(), time.thread_time(), run_queue_seconds()
            try:
                return method(*args, **kwargs)
            finally:  # read in reverse: a wait for a CPU between the reads counts as sleep
                queued, cpu = run_queue_seconds() - queued, time.thread_time() - cpu
                slept.append(time.perf_counter() - wall - cpu - queued)

        return call

    for name in names:
        monkeypatch.setattr(obj, name, timed(getattr(obj, name)))
    return slept


def test_a_model_without_joints_renders_and_its_name_comes_back_after_delete(world_sim):
    sim = world_sim()
    model = sim.spawn_urdf('cam', camera_on_a_box(), position=(0, 0, 0.05))
    assert model.robot.state()[2] == []  # no joint positions at all
    frames = watched(model.cameras[0])
    step_until(sim, lambda: len(frames) >= 3, 30)
    assert all(len(d) == 64 * 48 * 3 for _, d in frames)
    assert not is_uniform(frames[-1][1], 64, 48, 64 * 3)  # the ground and the sky
    old = model.cameras[0]
    step_until(sim, lambda: old.in_flight > 0, 5)
    count = len(frames)
    sim.delete_model('cam')  # with a frame out
    sim.sensors.drain()
    assert len(frames) == count and sim.sensors.cameras == []
    again = sim.spawn_urdf('cam', camera_on_a_box(), position=(0, 0, 0.05))
    new_frames = watched(again.cameras[0])
    step_until(sim, lambda: len(new_frames) >= 2, 30)
    assert len(frames) == count  # the old camera got nothing late


def test_a_killed_render_process_is_replaced_and_the_world_steps_on(world_sim, caplog, monkeypatch):
    sim = world_sim()
    model = sim.spawn_urdf('cam', camera_on_a_box(), position=(0, 0, 0.05))
    frames = watched(model.cameras[0])
    step_until(sim, lambda: len(frames) >= 2, 30)
    victim = sim.sensors.renderers[0]
    slept = time_blocked_in(victim, ('send', 'ready', 'receive', 'close'), monkeypatch)
    os.kill(victim.pid, signal.SIGKILL)
    count, t0 = len(frames), sim.time_ns
    pids = lambda: {r.pid for r in sim.sensors.renderers}  # noqa: E731
    step_until(
        sim, lambda: len(frames) >= count + 10 and len(pids()) == 2 and victim.pid not in pids(), 30
    )
    # The world did not stop for it: the physics thread's calls on the dead process slept
    # (not ran or queued for a CPU) under 0.1 s in all. The waits that could hold it there are
    # a frame's render timeout (30 s), reaping the process and joining its reader (up to 2 s
    # each), and a write finding the pipe broken, which waits at most 0.05 s for the exit.
    assert slept and sum(slept) < 0.1, 'the physics slept %.3f s on the dead process' % sum(slept)
    assert victim.process.poll() == -signal.SIGKILL  # reaped, not a zombie
    assert frames[-1][0] > t0 and sim.sensors.restarts == 1 and not sim.sensors.failed
    assert any(
        r.levelname == 'ERROR' and "'eye'" in r.message and 'killed by signal 9' in r.message
        for r in caplog.records
    )


def test_a_killed_render_process_is_named_by_its_signal_whichever_end_notices(world_sim):
    """The reader may see the end first, or a request may find the pipe broken first (CI
    saw "Broken pipe" alone): either way the message says what happened to the process."""
    sim = world_sim()
    model = sim.spawn_urdf('cam', camera_on_a_box(), position=(0, 0, 0.05))
    frames = watched(model.cameras[0])
    step_until(sim, lambda: len(frames) >= 1, 30)
    victim = sim.sensors.renderers[0]
    os.kill(victim.pid, signal.SIGKILL)
    victim.process.wait(10)
    victim._reader.join(10)
    victim._gone = None  # as if the reader had not seen the end yet: the write finds out
    message = None
    for _ in range(50):  # a write may still go into the socket's buffer: the next one fails
        try:
            victim.send(('ping',))
        except RenderError as exc:
            message = str(exc)
            break
        time.sleep(0.01)
    assert message == 'render process %d is gone: it was killed by signal 9' % victim.pid


@pytest.mark.parametrize('lockstep', [False, True], ids=['default', 'lockstep'])
def test_a_heavy_camera_lowers_its_image_rate_not_the_real_time_factor(
    world_sim, lockstep, monkeypatch
):
    monkeypatch.setenv('ARM1_RENDERER', 'tiny')  # slow enough for 1500 x 1500 to fall behind
    sim = world_sim(lockstep)
    model = sim.spawn_urdf('cam', camera_on_a_box(1500, 1500, 30), position=(0, 0, 0.05))
    frames = watched(model.cameras[0])
    pacer = Pacer(sim.period)
    step_until(sim, lambda: frames, 60, pacer)  # the render processes are up
    seconds = 2.0 if lockstep else 4.0
    wall0, sim0, count = time.perf_counter(), sim.time_ns, len(frames)
    queued0 = run_queue_seconds()
    step_until(
        sim,  # and six frames in lockstep (at a few hundredths of real time, 2 s hold ~3),
        # two in default timing (the renderers run at nice 10: a busy machine can starve
        # them of a whole 4 s window, which then shows no image rate at all)
        lambda: (
            time.perf_counter() - wall0 >= seconds and len(frames) - count >= (6 if lockstep else 2)
        ),
        60,
        pacer,
    )
    wall = time.perf_counter() - wall0
    queued = run_queue_seconds() - queued0  # what a busy machine kept the thread waiting
    rtf = (sim.time_ns - sim0) * 1e-9 / wall
    rate = (len(frames) - count) / ((sim.time_ns - sim0) * 1e-9)
    print(
        '%s: real-time factor %.3f, %.1f images per sim second, %.3f s waiting for a CPU'
        % ('lockstep' if lockstep else 'default', rtf, rate, queued)
    )
    if lockstep:  # every 30 Hz instant gets its frame, and the world slows down for them
        # Judged by the frames' stamps, not by a count over a short window whose last frame
        # may still be in flight: no 30 Hz instant was skipped.
        stamps = [t for t, _ in frames[count:]]
        gaps = [(b - a) * 1e-9 for a, b in zip(stamps, stamps[1:])]
        assert len(stamps) >= 5 and max(gaps) <= 1 / 30 + 2 * sim.period, gaps
        assert rtf < 0.8
    else:  # sim time lost no more than the machine's load kept the thread from a CPU
        assert (1 - rtf) * wall <= 0.01 * wall + queued, (rtf, queued)
        assert 0 < rate < 25


def decode_png(data):
    """(width, height, colour type, rows of pixel bytes) of a PNG made by png(): chunks and
    header read here, the (filtered, compressed) pixels decoded by Pillow."""
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    chunks, pos = {}, 8
    while pos < len(data):
        (n,), tag = struct.unpack('>I', data[pos : pos + 4]), data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + n]
        assert struct.unpack('>I', data[pos + 8 + n : pos + 12 + n])[0] == zlib.crc32(tag + body)
        chunks[tag] = body
        pos += 12 + n
    w, h, depth, kind = struct.unpack('>IIBB', chunks[b'IHDR'][:10])
    assert depth == 8
    with Image.open(io.BytesIO(data)) as image:
        pixels = np.asarray(image)
    assert pixels.shape[:2] == (h, w)
    return w, h, kind, [pixels[r].tobytes() for r in range(h)]


def test_snapshot_png_of_a_frame():
    px = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    rows = np.zeros((2, 12), np.uint8)  # padded rows: step 12 for 9 bytes of pixels
    rows[:, :9] = px.reshape(2, 9)
    w, h, kind, out = decode_png(png(rows.tobytes(), 3, 2, 12, 'rgb8'))
    assert (w, h, kind) == (3, 2, 2)
    assert out == [px[0].tobytes(), px[1].tobytes()]
    _, _, _, swapped = decode_png(png(px.tobytes(), 3, 2, 9, 'bgr8'))
    assert swapped[0] == px[0][:, ::-1].tobytes()
    assert decode_png(png(b'\x01\x02', 2, 1, 2, 'mono8'))[2:] == (0, [b'\x01\x02'])


# ------------------------------------------------------------------------ frame ids
@pytest.mark.parametrize(
    'namespace, camera_name, params, frame, expected',
    [
        ('/', 'rgb_camera', {}, 'camera_link', 'camera_link'),  # arm1: spawn_model's '/'
        ('/bot', 'cam', {}, 'camera_link', 'bot/camera_link'),  # the namespace as tf_prefix
        ('/bot', 'cam', {'/bot/cam/tf_prefix': 'p'}, 'camera_link', 'p/camera_link'),
        ('/bot', 'cam', {'/tf_prefix': 'top'}, 'camera_link', 'top/camera_link'),  # upward
        ('/bot', 'cam', {}, '/camera_link', 'camera_link'),  # absolute: no prefix
    ],
)
def test_camera_frame_id_as_gazebo_ros_camera_utils(
    monkeypatch, namespace, camera_name, params, frame, expected
):
    from _arm1sim.ros.plugins import camera_plugin, frames

    monkeypatch.setattr(frames.rospy, 'has_param', lambda key: key in params)
    monkeypatch.setattr(frames.rospy, 'get_param', lambda key: params[key])
    sensor = CameraSensor(
        'c', 'b', camera_name=camera_name, frame_name=frame, robot_namespace=namespace
    )
    assert camera_plugin.camera_frame(sensor) == expected
    assert camera_plugin.camera_info(sensor, expected).header.frame_id == expected
