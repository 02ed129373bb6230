"""gazebo_ros_laser / gazebo_ros_gpu_laser: <ray> parsing and defaults, Gazebo's ray directions
and interpolation, scans of a known wall in real pybullet (exact geometry without noise), REP 117
infinities, noise statistics with a seed, the sensor's own link not shadowing it, the limit, and
measuring only while wanted."""

import io
import logging
import math

import numpy as np
import pybullet as p
import pytest
from conftest import WORLD_FILE, box_link

from _arm1sim.description.gazebo_plugins import sensor_specs
from _arm1sim.description.limits import LimitError, Limits
from _arm1sim.description.ray_sensor import RaySpec, laser_plugin, ray_spec
from _arm1sim.description.sdf_world import read_world
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.physics.laser import Laser, interpolate, ray_directions
from _arm1sim.sim.simulation import Simulation, SpawnError

HEIGHT = 1.0  # sensor height above the ground: horizontal rays never meet it
WALL_X = 2.0  # the wall's centre; its front face is 0.1 nearer


def ray_block(samples=5, lo=-0.4, hi=0.4, rmin=0.1, rmax=10.0, noise='', extra=''):
    return """<ray><scan><horizontal><samples>%d</samples><resolution>1</resolution>
      <min_angle>%s</min_angle><max_angle>%s</max_angle></horizontal>%s</scan>
      <range><min>%s</min><max>%s</max><resolution>0.01</resolution></range>%s</ray>""" % (
        samples,
        lo,
        hi,
        extra,
        rmin,
        rmax,
        noise,
    )


def mast_urdf(
    ray=None,
    kind='gpu_ray',
    plugin='libgazebo_ros_gpu_laser.so',
    params='',
    rate='40',
    head='0.1 0.1 0.1',
    pose='0 0 0 0 0 0',
    ref='hokuyo_link',
):
    """A mast bolted to the world with a hokuyo-like head at HEIGHT (rrbot's sensor block)."""
    return """<robot name="mast"><link name="world"/>%s%s
  <joint name="fix" type="fixed"><parent link="world"/><child link="mast"/></joint>
  <joint name="head_joint" type="fixed"><parent link="mast"/><child link="hokuyo_link"/>
    <origin xyz="0 0 %g"/></joint>
  <gazebo reference="%s">
    <sensor type="%s" name="head_hokuyo_sensor">
      <pose>%s</pose><update_rate>%s</update_rate>%s
      <plugin name="laser" filename="%s">%s</plugin>
    </sensor>
  </gazebo>
</robot>""" % (
        box_link('mast', '0.05 0.05 0.5', xyz='0 0 0.25'),
        box_link('hokuyo_link', head),
        HEIGHT,
        ref,
        kind,
        pose,
        rate,
        ray if ray is not None else ray_block(),
        plugin,
        params,
    )


WALL = """<robot name="wall"><link name="world"/>%s
  <joint name="fix" type="fixed"><parent link="world"/><child link="wall"/>
    <origin xyz="%g 0 1"/></joint>
</robot>""" % (box_link('wall', '0.2 20 2', mass=10.0), WALL_X)

FACE = WALL_X - 0.1


def spec_of(urdf, limits=None):
    (sensor,) = sensor_specs(parse_urdf(urdf))
    return ray_spec(sensor, limits), sensor


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


sim2 = sim  # a second world in the same test


def laser_of(sim, urdf, ns='', wall=True):
    if wall:
        sim.spawn_urdf('wall', WALL)
    model = sim.spawn_urdf('mast', urdf, robot_namespace=ns)
    (laser,) = model.sensors
    assert isinstance(laser, Laser)
    return laser


def test_defaults_are_sdf_and_upstream_ones():
    spec, sensor = spec_of(mast_urdf(ray='<ray><range><max>5</max></range></ray>'))
    assert (spec.samples, spec.resolution, spec.min_angle, spec.max_angle) == (640, 1, 0, 0)
    assert (spec.vertical_samples, spec.vertical_range_count) == (1, 1)
    assert (spec.range_min, spec.range_max, spec.noise) == (0, 5, None)
    assert spec.angle_increment == 0  # (0 - 0) / 639
    one = RaySpec(samples=1, min_angle=0.1, max_angle=0.2, range_max=1)
    assert math.isinf(one.angle_increment)  # Gazebo divides by range count - 1 = 0
    assert sensor.update_rate == 40
    plugin = laser_plugin(sensor.plugins[0], '/spawn_ns')
    assert (plugin.topic_name, plugin.frame_name, plugin.namespace) == (
        '/world',
        '/world',
        '/spawn_ns',
    )


def test_rrbot_parameters_are_read():
    noise = '<noise><type>gaussian</type><mean>0.0</mean><stddev>0.01</stddev></noise>'
    spec, sensor = spec_of(
        mast_urdf(
            ray_block(720, -1.570796, 1.570796, 0.1, 30.0, noise),
            params='<topicName>/rrbot/laser/scan</topicName><frameName>hokuyo_link</frameName>',
        )
    )
    assert (spec.samples, spec.range_count, spec.range_min, spec.range_max) == (720, 720, 0.1, 30)
    assert spec.angle_increment == pytest.approx(2 * 1.570796 / 719)
    assert (spec.noise.mean, spec.noise.stddev) == (0.0, 0.01)
    plugin = laser_plugin(sensor.plugins[0], '/')
    assert (plugin.topic_name, plugin.frame_name) == ('/rrbot/laser/scan', 'hokuyo_link')


@pytest.mark.parametrize(
    'ray, culprit',
    [
        ('<ray><range><min>0.1</min></range></ray>', r'<range><max> is required'),
        (ray_block(rmin=2, rmax=1), r'0 <= min < max'),
        (ray_block(samples=0), r'samples>: 0'),
        (ray_block(noise='<noise type="uniform"/>'), r"type 'uniform'"),
        ('<camera/>', r'has no <ray>'),
    ],
)
def test_bad_rays_name_the_sensor(ray, culprit):
    with pytest.raises(UrdfError, match="sensor 'head_hokuyo_sensor' on link 'hokuyo_link'.*"):
        spec_of(mast_urdf(ray))
    with pytest.raises(UrdfError, match=culprit):
        spec_of(mast_urdf(ray))


def test_a_laser_over_the_ray_limit_is_refused_naming_it(sim):
    urdf = mast_urdf(ray_block(2000, extra='<vertical><samples>600</samples></vertical>'))
    with pytest.raises(LimitError, match='rays per laser is 1200000, over the limit of 1000000'):
        spec_of(urdf, Limits())
    with pytest.raises(SpawnError, match='rays_per_laser'):
        sim.spawn_urdf('mast', urdf)
    assert 'mast' not in sim.models


def test_ray_directions_follow_multirayshape():
    spec = RaySpec(
        samples=3,
        min_angle=-0.5,
        max_angle=0.5,
        vertical_samples=2,
        vertical_min_angle=-0.2,
        vertical_max_angle=0.2,
        range_max=1,
    )
    dirs = ray_directions(spec)
    assert dirs.shape == (6, 3)
    np.testing.assert_allclose(np.linalg.norm(dirs, axis=1), 1)
    # layer 0 points down (pitch -0.2), its first ray to the right (yaw -0.5)
    np.testing.assert_allclose(
        dirs[0], [math.cos(0.2) * math.cos(0.5), -math.cos(0.2) * math.sin(0.5), -math.sin(0.2)]
    )
    np.testing.assert_allclose(dirs[4], [math.cos(0.2), 0, math.sin(0.2)], atol=1e-12)
    one = ray_directions(RaySpec(samples=1, min_angle=0.3, max_angle=0.3, range_max=1))
    np.testing.assert_allclose(one, [[1, 0, 0]])  # one sample looks straight ahead in Gazebo


def test_resolution_interpolates_between_rays():
    spec = RaySpec(samples=3, resolution=2, range_max=10)  # 6 ranges over 3 rays
    out = interpolate(np.array([1.0, 2.0, 4.0]), spec)
    np.testing.assert_allclose(out, [1.0, 1.4, 1.8, 2.4, 3.2, 4.0])
    assert spec.angle_increment == 0  # min = max = 0 here
    same = RaySpec(samples=3, range_max=10)
    assert interpolate(np.array([1.0, 2.0, 4.0]), same).tolist() == [1, 2, 4]


def test_a_scan_of_a_wall_gives_the_known_ranges(sim):
    laser = laser_of(sim, mast_urdf())
    sim.step()
    reading = laser.measure(sim.time_ns)
    angles = np.linspace(-0.4, 0.4, 5)
    np.testing.assert_allclose(reading.ranges, FACE / np.cos(angles), atol=1e-4)
    assert reading.intensities.tolist() == [0.0] * 5
    assert laser.spec.angle_increment == pytest.approx(0.2)


def test_nothing_beyond_max_range_reads_plus_infinity(sim, sim2):
    laser = laser_of(sim, mast_urdf(ray_block(rmax=1.5)))  # the wall is 1.9 away
    assert np.isposinf(laser.measure(0).ranges).all()
    alone = laser_of(sim2, mast_urdf(), wall=False)
    assert np.isposinf(alone.measure(0).ranges).all()  # nothing in front at all


def test_the_sensor_is_not_shadowed_by_its_own_link(sim):
    # a 0.6 m head around a sensor whose rays start at 0: Gazebo's rays ignore the own link
    laser = laser_of(sim, mast_urdf(ray_block(rmin=0.0), head='0.6 0.6 0.6'))
    np.testing.assert_allclose(laser.measure(0).ranges[2], FACE, atol=1e-4)


def test_rays_pass_through_the_own_link_from_outside(sim):
    # a sensor on the mast, 0.5 behind it, looking through it: pybullet's ray stops at the mast
    laser = laser_of(sim, mast_urdf(ray_block(rmin=0.0), pose='-0.5 0 0.25 0 0 0', ref='mast'))
    position, _ = laser.world_pose()
    hit = p.rayTest(position, (5, 0, position[2]), physicsClientId=laser.robot.client)[0]
    assert (hit[0], hit[1]) == laser._own  # what the laser must look past
    np.testing.assert_allclose(laser.measure(0).ranges[2], FACE + 0.5, atol=1e-4)


def test_the_sensor_pose_offsets_the_rays(sim):
    laser = laser_of(sim, mast_urdf(pose='0.5 0 0 0 0 0.2'))
    ranges = laser.measure(0).ranges
    angles = np.linspace(-0.4, 0.4, 5) + 0.2
    np.testing.assert_allclose(ranges, (FACE - 0.5) / np.cos(angles), atol=1e-4)


def test_gaussian_noise_has_its_statistics_and_stays_in_range(sim, sim2):
    noise = '<noise type="gaussian"><mean>0.02</mean><stddev>0.05</stddev></noise>'
    laser = laser_of(sim, mast_urdf(ray_block(720, -0.3, 0.3, 0.1, 10.0, noise)))
    laser._rng = np.random.default_rng(7)
    truth = FACE / np.cos(np.linspace(-0.3, 0.3, 720))
    errors = np.concatenate([laser.measure(0).ranges - truth for _ in range(20)])
    assert errors.mean() == pytest.approx(0.02, abs=0.005)
    assert errors.std() == pytest.approx(0.05, abs=0.005)
    wide = laser_of(
        sim2,
        mast_urdf(ray_block(720, -0.3, 0.3, 1.8, 1.95, noise.replace('0.05', '1.0'))),
    )
    ranges = wide.measure(0).ranges
    assert ((ranges >= 1.8) & (ranges <= 1.95) | np.isinf(ranges)).all()
    assert (ranges == 1.8).any() and (ranges == 1.95).any()  # clamped, not dropped


def test_rep117_minus_infinity_below_min_range(sim):
    sim.spawn_urdf('wall', WALL)
    laser = laser_of(sim, mast_urdf(ray_block(rmin=FACE, rmax=5)), wall=False)
    assert np.isneginf(laser.measure(0).ranges[2])  # the wall is exactly at min


def test_measured_only_while_wanted_and_at_its_rate(sim):
    laser = laser_of(sim, mast_urdf(rate='40'))
    got = []
    laser.deliver = lambda stamp, reading: got.append(stamp)
    for _ in range(300):
        sim.step()
    assert laser.readings == 0 and got == []
    laser.wanted = lambda: True
    for _ in range(1000):
        sim.step()
    assert len(got) == 40 and laser.readings == 40
    assert all(b - a == 25_000_000 for a, b in zip(got, got[1:]))


def test_topic_and_a_plugin_in_the_wrong_sensor_type(sim, caplog):
    laser = laser_of(sim, mast_urdf(params='<topicName>laser/scan</topicName>'), ns='/ns')
    assert laser.topic == '/ns/laser/scan' and laser.plugin.namespace == '/ns'
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        model = sim.spawn_urdf('other', mast_urdf(kind='ray').replace('"mast"', '"other"', 1))
    assert model.sensors == []
    assert any(
        "needs a sensor of type 'gpu_ray', not 'ray'" in r.getMessage() for r in caplog.records
    )


def test_vertical_layers_are_concatenated_with_a_warning(sim, caplog):
    extra = (
        '<vertical><samples>3</samples><min_angle>-0.1</min_angle>'
        '<max_angle>0.1</max_angle></vertical>'
    )
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        laser = laser_of(
            sim, mast_urdf(ray_block(extra=extra), kind='ray', plugin='libgazebo_ros_laser.so')
        )
    assert any('3 vertical layers' in r.getMessage() for r in caplog.records)
    ranges = laser.measure(0).ranges
    assert len(ranges) == 15
    pitches = np.repeat([-0.1, 0.0, 0.1], 5)
    yaws = np.tile(np.linspace(-0.4, 0.4, 5), 3)
    np.testing.assert_allclose(ranges, FACE / (np.cos(pitches) * np.cos(yaws)), atol=1e-4)


def test_laser_scan_message_as_upstream_fills_it(sim):
    from _arm1sim.ros.plugins.laser_plugin import laser_message

    laser = laser_of(sim, mast_urdf(ray_block(rmax=1.5)))
    reading = laser.reading(np.array([1.0, 1.5, 0.1, 0.7, 2.0]))
    msg = laser_message(12_345_000_678, 'hokuyo_link', laser, reading)
    assert (msg.header.stamp.secs, msg.header.stamp.nsecs) == (12, 345_000_678)
    assert msg.header.frame_id == 'hokuyo_link'
    assert (msg.angle_min, msg.angle_max) == (-0.4, 0.4)
    assert msg.angle_increment == pytest.approx(0.2)
    assert (msg.time_increment, msg.scan_time) == (0.0, 0.0)
    assert (msg.range_min, msg.range_max) == (0.1, 1.5)
    assert msg.ranges == [1.0, math.inf, -math.inf, 0.7, math.inf]
    assert msg.intensities == [0.0] * 5
    buffer = io.BytesIO()
    msg.serialize(buffer)  # float32[] with infinities serialises


@pytest.mark.parametrize(
    'namespace, param, frame, expected',
    [
        ('/', None, 'hokuyo_link', 'hokuyo_link'),  # rrbot: spawn_model's '/'
        ('/ns', None, 'hokuyo_link', 'ns/hokuyo_link'),  # the namespace is the tf_prefix
        ('/ns/', None, '/hokuyo_link', 'hokuyo_link'),  # an absolute frame loses its '/'
        ('/ns', None, '/world', 'world'),  # the default frameName
        ('/ns/sub', ('/ns/tf_prefix', 'robot1'), 'laser', 'robot1/laser'),  # found upward
        ('', None, 'laser', 'laser'),
    ],
)
def test_frame_id_is_tf_resolved_as_upstream(monkeypatch, namespace, param, frame, expected):
    from _arm1sim.ros.plugins import frames

    params = dict([param]) if param else {}
    monkeypatch.setattr(frames.rospy, 'has_param', lambda key: key in params)
    monkeypatch.setattr(frames.rospy, 'get_param', lambda key: params[key])
    prefix = frames.tf_prefix(namespace, namespace)
    assert frames.tf_resolve(prefix, frame) == expected
