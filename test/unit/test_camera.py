"""physics/camera.py: camera sensors from the URDF, their geometry, scheduling and rendering."""
import math
import struct
import zlib

import numpy as np
import pybullet as p
import pytest

from arm1.image import is_uniform, png
from arm1.physics.camera import (Camera, CameraSensor, SensorManager, camera_sensors, encode,
                                 intrinsics, render, view_matrix)
from arm1.physics.sdf_world import read_world
from arm1.physics.urdf_model import UrdfError, parse_urdf
from arm1.simulation import Simulation
from conftest import WORLD_FILE, box_link

STEP_NS = 1000000  # 1 ms physics step


def robot_with(sensor_xml, link='b'):
    return ('<robot name="r">' + box_link('a') + box_link('b') + """
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
  <gazebo reference="%s">%s</gazebo></robot>""" % (link, sensor_xml))


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
    [s] = sensors_of(robot_with("""
      <sensor type="camera" name="eye"><update_rate>60</update_rate><camera/>
        <plugin name="c" filename="libgazebo_ros_camera.so">
          <robotNamespace>/bot</robotNamespace><cameraName>front</cameraName>
          <updateRate>10</updateRate><cameraInfoTopicName>/info</cameraInfoTopicName>
        </plugin></sensor>"""))
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
    fmt = '<sensor type="camera" name="c"><camera><image><format>%s</format></image></camera>' \
          '<plugin filename="libgazebo_ros_camera.so"/></sensor>'
    assert sensors_of(robot_with(fmt % 'L8'))[0].encoding == 'mono8'
    assert sensors_of(robot_with(fmt % 'B8G8R8'))[0].step == 320 * 3
    assert sensors_of(robot_with(fmt % 'FLOAT32'))[0].encoding == 'rgb8'  # with a warning
    bad = robot_with('<sensor type="camera" name="c"><camera><image><width>wide</width></image>'
                     '</camera><plugin filename="libgazebo_ros_camera.so"/></sensor>')
    with pytest.raises(UrdfError, match="sensor 'c' on link 'b'.*wide"):
        sensors_of(bad)
    nowhere = robot_with('<sensor type="camera" name="c"><camera/>'
                         '<plugin filename="libgazebo_ros_camera.so"/></sensor>', link='ghost')
    with pytest.raises(UrdfError, match="link 'ghost'"):
        sensors_of(nowhere)


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
    ticks = [t for t in range(STEP_NS, 3 * 10 ** 9, STEP_NS) if cam.due(t)]
    assert len(ticks) == 90
    assert set(np.diff(ticks)) <= {33 * STEP_NS, 34 * STEP_NS}
    # reset_simulation: time back to zero, updates start again at once
    assert cam.due(STEP_NS) and not cam.due(2 * STEP_NS)


class FakeRenderer:
    """Renders nothing until asked for a reply; then the oldest request's frame."""

    def __init__(self, config, robots):
        self.robots = dict(robots)
        self.requests = []  # (camera name, states)
        self.replies = 0
        self.in_flight = 0

    def send(self, message):
        if message[0] == 'add':
            self.robots[message[1]] = message[2]
        elif message[0] == 'remove':
            del self.robots[message[1]]
        else:
            self.requests.append((message[2].name, message[3]))

    def ready(self):
        return False

    def receive(self):
        self.replies += 1
        return 'frame', b'frame %d' % self.replies

    def close(self):
        pass


def manager_with_fakes(processes):
    made = []

    def factory(config, robots):
        made.append(FakeRenderer(config, robots))
        return made[-1]
    return SensorManager(None, processes, factory), made


def test_nothing_is_rendered_without_a_subscriber():
    manager, made = manager_with_fakes(2)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    infos = []
    cam.on_info = infos.append
    for t in range(STEP_NS, 10 ** 9, STEP_NS):
        manager.update(t, lambda: {})
    assert made == [] and infos == []  # no render process was even started
    cam.wants_info = lambda: True  # camera_info alone: published without rendering
    for t in range(10 ** 9, 2 * 10 ** 9, STEP_NS):
        manager.update(t, lambda: {})
    assert made == [] and len(infos) == 30


@pytest.mark.parametrize('processes', [1, 2])
def test_lockstep_every_update_instant_gets_its_frame_in_order(processes):
    manager, made = manager_with_fakes(processes)
    manager.add_robot('other', ('other.urdf',))
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=30)])
    frames = []
    cam.wants_image, cam.on_image = (lambda: True), (lambda t, d: frames.append(t))
    for t in range(STEP_NS, 10 ** 9, STEP_NS):
        manager.update(t, lambda: {'m': t})  # the robots' state at the update instant
    assert len(made) == processes
    assert all(set(r.robots) == {'other', 'm'} for r in made)  # each mirrors every robot
    asked = sorted(states['m'] for r in made for _, states in r.requests)
    assert len(asked) == 30
    assert set(np.diff(asked)) <= {33 * STEP_NS, 34 * STEP_NS}
    # the renderers never finished on their own: the world waited, so that no more than one
    # frame per render process was ever out; frames came in order, each with its instant
    assert frames == asked[:30 - processes]
    if processes == 2:  # the requests alternate between the two
        assert [len(r.requests) for r in made] == [15, 15]
    manager.remove_robot('m')
    assert manager.cameras == [] and all(set(r.robots) == {'other'} for r in made)


def test_rate_zero_renders_as_fast_as_the_render_processes_go():
    manager, made = manager_with_fakes(2)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('c', 'l', update_rate=0)])
    cam.wants_image = lambda: True
    for t in range(STEP_NS, 100 * STEP_NS, STEP_NS):
        manager.update(t, lambda: {})
    # both busy from the first steps on, and the world never waited for them
    assert [len(r.requests) for r in made] == [1, 1]
    assert sum(r.replies for r in made) == 0


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
    while cam.in_flight:
        sim.sensors._hand_over()
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


def decode_png(data):
    """(width, height, colour type, rows of pixel bytes) of a PNG made by png()."""
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    chunks, pos = {}, 8
    while pos < len(data):
        (n,), tag = struct.unpack('>I', data[pos:pos + 4]), data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + n]
        assert struct.unpack('>I', data[pos + 8 + n:pos + 12 + n])[0] == zlib.crc32(tag + body)
        chunks[tag] = body
        pos += 12 + n
    w, h, depth, kind = struct.unpack('>IIBB', chunks[b'IHDR'][:10])
    raw = zlib.decompress(chunks[b'IDAT'])
    stride = len(raw) // h
    assert depth == 8 and all(raw[r * stride] == 0 for r in range(h))  # filter: none
    return w, h, kind, [raw[r * stride + 1:(r + 1) * stride] for r in range(h)]


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
