"""gazebo_ros_ft_sensor on real pybullet: the wrench a joint puts on its child, in the child's
frame, torque about the joint."""

import logging
import statistics

import pytest
from helpers import G, inertial, listen, robot, steps, world

from _arm1sim.physics.force_torque import ForceTorque


def hanging(joint='fixed', child_com='0 0 -0.1', rpy='0 0 0', axis='1 0 0'):
    """A base bolted 1 m up; under it, on ``joint``, a 3 kg link, and 1 kg more below that."""
    limit = (
        ''
        if joint == 'fixed'
        else '<axis xyz="%s"/><limit lower="-1" upper="1" effort="10" velocity="1"/>' % axis
    )
    return (
        '<link name="world"/><joint name="bolt" type="fixed"><parent link="world"/>'
        '<child link="base"/><origin xyz="0 0 1"/></joint><link name="base">%s</link>'
        '<joint name="wrist" type="%s"><parent link="base"/><child link="hand"/>'
        '<origin xyz="0 0 -0.2" rpy="%s"/>%s</joint><link name="hand">%s</link>'
        '<joint name="grip" type="fixed"><parent link="hand"/><child link="load"/>'
        '<origin xyz="0 0 -0.3"/></joint><link name="load">%s</link>'
        % (inertial(1.0), joint, rpy, limit, inertial(3.0, child_com), inertial(1.0))
        # as in Gazebo, a fixed joint is lumped (and its ft sensor lost) unless preserved
        + '<gazebo reference="wrist"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
    )


def ft(params='<jointName>wrist</jointName><topicName>ft</topicName>'):
    plugin = '<plugin name="ft_plugin" filename="libgazebo_ros_ft_sensor.so">%s</plugin>'
    return '<gazebo>%s</gazebo>' % (plugin % params)


@pytest.fixture
def sim():
    s = world(ground=False)
    yield s
    s.close()


def close(a, b, tol):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def test_a_hanging_mass_reads_its_weight_in_the_child_frame(sim):
    model = sim.spawn_urdf('r', robot(hanging(), ft()))
    (sensor,) = model.sensors
    assert isinstance(sensor, ForceTorque)
    assert (sensor.topic, sensor.frame_id) == ('/ft', 'hand')
    got = listen(model)
    steps(sim, 200)
    assert len(got['ft_plugin']) == 199  # from the step after pybullet was asked
    _, r = got['ft_plugin'][-1]
    assert close(r.force, (0, 0, 4.0 * G), 1e-6)  # the hand and the load below it
    assert close(r.torque, (0, 0, 0), 1e-6)


def test_an_offset_mass_loads_the_joint_with_a_torque_about_it(sim):
    # the hand's centre of mass 0.1 m out along x: 3 kg x g x 0.1 m about -y
    model = sim.spawn_urdf('r', robot(hanging(child_com='0.1 0 0'), ft()))
    got = listen(model)
    steps(sim, 10)
    _, r = got['ft_plugin'][-1]
    assert close(r.force, (0, 0, 4.0 * G), 1e-6)
    assert close(r.torque, (0, -3.0 * G * 0.1, 0), 1e-6)


def test_a_tilted_child_frame_turns_the_force(sim):
    import math

    model = sim.spawn_urdf('r', robot(hanging(joint='revolute', rpy='0 0.5 0'), ft()))
    got = listen(model)
    steps(sim, 2)
    _, r = got['ft_plugin'][-1]
    w = 4.0 * G
    assert close(r.force, (-w * math.sin(0.5), 0, w * math.cos(0.5)), 1e-3)


def test_the_axis_component_of_a_revolute_joint_is_dropped(sim):
    # an offset mass on a joint about y would read its torque about y: that is the joint's
    # own (the actuator's, or its motion), not the structure's
    model = sim.spawn_urdf(
        'r', robot(hanging(joint='revolute', child_com='0.1 0 0', axis='0 1 0'), ft())
    )
    got = listen(model)
    steps(sim, 2)
    _, r = got['ft_plugin'][-1]
    assert abs(r.torque[1]) < 1e-9


def test_the_rate_noise_and_only_when_wanted(sim):
    params = (
        '<jointName>wrist</jointName><topicName>ft</topicName><updateRate>100</updateRate>'
        '<gaussianNoise>0.2</gaussianNoise>'
    )
    model = sim.spawn_urdf('r', robot(hanging(), ft(params)))
    (sensor,) = model.sensors
    steps(sim, 100)
    assert not sensor._enabled  # pybullet computes no joint reactions for nobody
    got = listen(model)
    steps(sim, 2000)
    assert sensor._enabled and len(got['ft_plugin']) in (200, 201)
    assert 0.15 < statistics.pstdev([r.force[2] for _, r in got['ft_plugin']]) < 0.25


@pytest.mark.parametrize(
    'params, named',
    [
        ('<topicName>ft</topicName>', 'jointName'),
        ('<jointName>wrist</jointName>', 'topicName'),
        ('<jointName>elbow</jointName><topicName>ft</topicName>', "'elbow'"),
    ],
)
def test_a_plugin_gazebo_would_not_load_is_named(sim, caplog, params, named):
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        model = sim.spawn_urdf('r', robot(hanging(), ft(params)))
    assert model.sensors == []
    assert any(
        "plugin 'ft_plugin'" in r.getMessage() and named in r.getMessage() for r in caplog.records
    )


def test_pybullet_stops_computing_it_when_nobody_listens(sim):
    model = sim.spawn_urdf('r', robot(hanging(), ft()))
    (sensor,) = model.sensors
    listen(model)
    steps(sim, 5)
    assert sensor._enabled
    sensor.wanted = lambda: False
    steps(sim, 1)
    assert not sensor._enabled
