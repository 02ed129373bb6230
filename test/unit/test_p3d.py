"""gazebo_ros_p3d on real pybullet: ground truth of a falling and of a pushed, spinning body,
relative to a link, with offsets and noise, and plugins that would not load in Gazebo."""

import logging
import math
import statistics

import pybullet as p
import pytest
from helpers import G, box, inertial, listen, robot, steps, world

from _arm1sim.physics.p3d import P3d


def p3d(params):
    return (
        '<gazebo><plugin name="truth" filename="libgazebo_ros_p3d.so">%s</plugin></gazebo>' % params
    )


def two_links():
    """base and, 0.5 m above it on a revolute joint about z, a light arm link."""
    return box('base') + (
        '<joint name="spin" type="continuous"><parent link="base"/><child link="arm"/>'
        '<origin xyz="0 0 0.5"/><axis xyz="0 0 1"/></joint>'
        '<link name="arm">%s</link>' % inertial(0.1)
    )


@pytest.fixture
def sim():
    s = world(ground=False)
    yield s
    s.close()


@pytest.fixture
def weightless():
    s = world(ground=False, gravity=(0.0, 0.0, 0.0))
    yield s
    s.close()


def close(a, b, tol=1e-6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def test_a_falling_body_reports_where_free_fall_puts_it(sim):
    model = sim.spawn_urdf(
        'r',
        robot(box('base'), p3d('<bodyName>base</bodyName><topicName>odom</topicName>')),
        position=(1, 2, 10),
    )
    (sensor,) = model.sensors
    assert isinstance(sensor, P3d)
    assert (sensor.topic, sensor.frame_id, sensor.child_frame_id) == ('/odom', 'world', 'base')
    got = listen(model)
    steps(sim, 1000)
    assert len(got['truth']) == 1000  # updateRate 0: every step
    t, r = got['truth'][-1]
    assert t == 1_000_000_000
    # pybullet's semi-implicit Euler: v_n = -g n h, z_n = z0 - g h² n(n+1)/2
    h, n = 0.001, 1000
    assert close(r.linear, (0, 0, -G * n * h), 1e-9)
    assert close(r.position, (1, 2, 10 - G * h * h * n * (n + 1) / 2), 1e-4)
    assert close(r.orientation, (0, 0, 0, 1))


def test_a_pushed_spinning_body_reports_its_world_twist(weightless):
    sim = weightless
    model = sim.spawn_urdf(
        'r',
        robot(
            box('base'),
            p3d('<bodyName>base</bodyName><topicName>odom</topicName><updateRate>100</updateRate>'),
        ),
    )
    p.resetBaseVelocity(
        model.robot.body, [0.5, 0, 0], [0, 0, 2.0], physicsClientId=model.robot.client
    )
    got = listen(model)
    steps(sim, 1000)
    assert len(got['truth']) in (100, 101)  # on the 10 ms marks, and at the first step
    t, r = got['truth'][-1]
    assert close(r.linear, (0.5, 0, 0), 1e-9) and close(r.angular, (0, 0, 2.0), 1e-9)
    assert close(r.position, (0.5, 0, 0), 1e-3)
    assert close(r.orientation, (0, 0, math.sin(1.0), math.cos(1.0)), 1e-3)


def test_the_twist_is_of_the_link_origin_in_world_axes(weightless):
    # the arm link spins with the base about z; its origin is on the axis, 0.5 m up
    sim = weightless
    model = sim.spawn_urdf(
        'r', robot(two_links(), p3d('<bodyName>arm</bodyName><topicName>odom</topicName>'))
    )
    p.resetBaseVelocity(
        model.robot.body, [0, 0, 0], [1.0, 0, 0], physicsClientId=model.robot.client
    )
    got = listen(model)
    steps(sim, 1)
    _, r = got['truth'][-1]
    # spinning about x at 1 rad/s: the point 0.5 m up moves along -y at 0.5 m/s
    assert close(r.linear, (0, -0.5, 0), 2e-3)
    assert close(r.angular, (1.0, 0, 0), 1e-6)


def test_relative_to_a_link_and_offsets(weightless):
    sim = weightless
    params = (
        '<bodyName>arm</bodyName><topicName>odom</topicName><frameName>base</frameName>'
        '<xyzOffset>1 0 0</xyzOffset><rpyOffset>0 0 %r</rpyOffset>' % (math.pi / 2)
    )
    model = sim.spawn_urdf(
        'r',
        robot(two_links(), p3d(params)),
        position=(3, 4, 5),
        orientation=(0, 0, math.sin(0.3), math.cos(0.3)),
    )
    assert model.sensors[0].frame_id == 'base'
    got = listen(model)
    steps(sim, 1)
    _, r = got['truth'][-1]
    assert close(r.position, (1, 0, 0.5), 1e-6)
    s = math.sin(math.pi / 4)
    assert close(r.orientation, (0, 0, s, s), 1e-6)
    assert close(r.linear, (0, 0, 0), 1e-9)


def test_plural_offsets_are_ignored_as_upstream(weightless):
    params = '<bodyName>base</bodyName><topicName>odom</topicName><xyzOffsets>1 2 3</xyzOffsets>'
    model = weightless.spawn_urdf('r', robot(box('base'), p3d(params)))
    got = listen(model)
    steps(weightless, 1)
    assert close(got['truth'][-1][1].position, (0, 0, 0))


def test_noise_goes_on_the_twist_only(weightless):
    params = (
        '<bodyName>base</bodyName><topicName>odom</topicName><gaussianNoise>0.05</gaussianNoise>'
    )
    model = weightless.spawn_urdf('r', robot(box('base'), p3d(params)))
    got = listen(model)
    steps(weightless, 2000)
    readings = [r for _, r in got['truth']]
    assert all(r.position == readings[0].position for r in readings)
    assert 0.04 < statistics.pstdev([r.linear[0] for r in readings]) < 0.06
    assert 0.04 < statistics.pstdev([r.angular[2] for r in readings]) < 0.06


@pytest.mark.parametrize(
    'params, named',
    [
        ('<topicName>odom</topicName>', 'bodyName'),
        ('<bodyName>base</bodyName>', 'topicName'),
        ('<bodyName>elsewhere</bodyName><topicName>odom</topicName>', "'elsewhere'"),
        (
            '<bodyName>base</bodyName><topicName>odom</topicName><frameName>nowhere</frameName>',
            "'nowhere'",
        ),
    ],
)
def test_a_plugin_gazebo_would_not_load_is_named(sim, caplog, params, named):
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        model = sim.spawn_urdf('r', robot(box('base'), p3d(params)))
    assert model.sensors == []
    text = [r.getMessage() for r in caplog.records]
    assert any("plugin 'truth'" in t and named in t for t in text)
