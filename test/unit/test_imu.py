"""gazebo_ros_imu_sensor and gazebo_ros_imu on real pybullet: gravity as an accelerometer reads
it, orientation, frames, rates, noise, and plugins that would not load in Gazebo."""

import logging
import math
import statistics

import pytest
from helpers import G, box, listen, robot, steps, world

from _arm1sim.physics.imu import ImuModelPlugin, ImuSensor

BOLTED = (
    '<link name="world"/><joint name="bolt" type="fixed"><parent link="world"/>'
    '<child link="base"/><origin xyz="0 0 1" rpy="%s"/></joint>'
)


def imu_sensor(params='<frameName>imu_link</frameName>', pose='0 0 0 0 0 0', rate='0', sdf=''):
    return """<gazebo reference="base"><sensor type="imu" name="imu">
      <pose>%s</pose><update_rate>%s</update_rate>%s
      <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">%s</plugin>
    </sensor></gazebo>""" % (pose, rate, sdf, params)


@pytest.fixture
def sim():
    s = world(ground=False)
    yield s
    s.close()


def spawn(sim, gazebo, rpy='0 0 0', bolted=True, **kwargs):
    body = (BOLTED % rpy if bolted else '') + box('base')
    return sim.spawn_urdf('r', robot(body, gazebo), **kwargs)


def close(a, b, tol=1e-6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def test_an_imu_at_rest_reads_plus_g_on_z_and_identity(sim):
    model = spawn(
        sim, imu_sensor('<frameName>imu_link</frameName><updateRateHZ>100</updateRateHZ>')
    )
    (sensor,) = model.sensors
    assert isinstance(sensor, ImuSensor) and sensor.frame_id == 'imu_link'
    got = listen(model)
    steps(sim, 100)
    _, r = got['imu'][-1]
    assert close(r.linear_acceleration, (0, 0, G))
    assert close(r.orientation, (0, 0, 0, 1))
    assert close(r.angular_velocity, (0, 0, 0))


def test_a_rolled_sensor_reads_gravity_in_its_own_axes(sim):
    # rolled +90 degrees about x: the sensor's y axis points up
    model = spawn(sim, imu_sensor(pose='0 0 0 %r 0 0' % (math.pi / 2)))
    got = listen(model)
    steps(sim, 1000)
    _, r = got['imu'][-1]
    assert close(r.linear_acceleration, (0, G, 0))
    s = math.sin(math.pi / 4)
    assert close(r.orientation, (s, 0, 0, s))


def test_a_free_falling_imu_reads_no_acceleration(sim):
    model = spawn(sim, imu_sensor(), bolted=False)
    got = listen(model)
    steps(sim, 1000)
    assert len(got['imu']) == 1  # updateRateHZ defaults to 1 Hz
    _, r = got['imu'][-1]
    assert close(r.linear_acceleration, (0, 0, 0), 1e-6)


def test_publication_follows_update_rate_hz_over_the_sensor_rate(sim):
    model = spawn(
        sim, imu_sensor('<frameName>f</frameName><updateRateHZ>50</updateRateHZ>', rate='200')
    )
    got = listen(model)
    steps(sim, 1000)
    stamps = [t for t, _ in got['imu']]
    assert len(stamps) == 50
    assert all(b - a == 20_000_000 for a, b in zip(stamps, stamps[1:]))


def test_nothing_is_measured_while_nobody_listens(sim):
    model = spawn(sim, imu_sensor())
    (sensor,) = model.sensors
    got = []
    sensor.deliver = lambda t, r: got.append(t)
    steps(sim, 2000)
    assert got == [] and sensor.readings == 0


def test_gaussian_noise_spreads_every_component(sim):
    params = (
        '<frameName>f</frameName><updateRateHZ>0</updateRateHZ><gaussianNoise>0.1</gaussianNoise>'
    )
    model = spawn(sim, imu_sensor(params))
    got = listen(model)
    steps(sim, 2000)
    readings = [r for _, r in got['imu']]
    assert len(readings) == 2000 and readings[0].noise == 0.1
    for values in (
        [r.linear_acceleration[2] for r in readings],
        [r.angular_velocity[0] for r in readings],
        [r.orientation[3] for r in readings],
    ):
        assert abs(statistics.mean(values) - values[0]) < 0.5
        assert 0.08 < statistics.pstdev(values) < 0.12


def test_sdf_noise_and_bias_on_one_axis(sim):
    sdf = """<imu><linear_acceleration><z><noise type="gaussian"><mean>0.5</mean>
      <stddev>0</stddev></noise></z></linear_acceleration>
      <angular_velocity><x><noise type="gaussian_quantized"><mean>0.26</mean>
      <precision>0.1</precision></noise></x></angular_velocity></imu>"""
    model = spawn(
        sim, imu_sensor(sdf=sdf, params='<frameName>f</frameName><updateRateHZ>0</updateRateHZ>')
    )
    got = listen(model)
    steps(sim, 10)
    _, r = got['imu'][-1]
    assert close(r.linear_acceleration, (0, 0, G + 0.5))
    assert close(r.angular_velocity, (0.3, 0, 0))


def test_rpy_offset_turns_the_orientation_only(sim):
    params = (
        '<frameName>f</frameName><updateRateHZ>0</updateRateHZ><rpyOffset>0 0 %r</rpyOffset>'
        % (math.pi / 2)
    )
    model = spawn(sim, imu_sensor(params))
    got = listen(model)
    steps(sim, 10)
    _, r = got['imu'][-1]
    s = math.sin(math.pi / 4)
    assert close(r.orientation, (0, 0, s, s))
    assert close(r.linear_acceleration, (0, 0, G))


def test_initial_orientation_as_reference(sim):
    rpy = '0 0 0.7'
    every = '<frameName>f</frameName><updateRateHZ>0</updateRateHZ>'
    plain = spawn(sim, imu_sensor(every), rpy=rpy)
    got = listen(plain)
    steps(sim, 10)
    assert close(got['imu'][-1][1].orientation, (0, 0, math.sin(0.35), math.cos(0.35)))
    sim.delete_model('r')
    params = every + '<initialOrientationAsReference>true</initialOrientationAsReference>'
    relative = spawn(sim, imu_sensor(params), rpy=rpy)
    got = listen(relative)
    steps(sim, 10)
    assert close(got['imu'][-1][1].orientation, (0, 0, 0, 1))


def test_without_frame_name_the_plugin_is_not_loaded_and_named(sim, caplog):
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        model = spawn(sim, imu_sensor('<topicName>imu</topicName>'))
    assert model.sensors == []
    assert any(
        "plugin 'imu_plugin'" in r.getMessage() and 'frameName' in r.getMessage()
        for r in caplog.records
    )


def test_topic_defaults_under_the_namespace(sim):
    model = spawn(sim, imu_sensor(), robot_namespace='/bot')
    assert model.sensors[0].topic == '/bot/imu_data'


def model_imu(params):
    return (
        '<gazebo><plugin name="old_imu" filename="libgazebo_ros_imu.so">%s</plugin></gazebo>'
        % params
    )


def test_gazebo_ros_imu_reads_no_gravity_at_rest_and_g_falling(sim):
    model = spawn(sim, model_imu('<bodyName>base</bodyName>'))
    (sensor,) = model.sensors
    assert isinstance(sensor, ImuModelPlugin)
    assert (sensor.topic, sensor.service, sensor.frame_id) == (
        '/default_imu',
        '/default_imu',
        'base',
    )
    got = listen(model)
    steps(sim, 10)
    assert close(got['old_imu'][-1][1].linear_acceleration, (0, 0, 0))
    sim.delete_model('r')
    falling = spawn(
        sim, model_imu('<bodyName>base</bodyName><topicName>imu</topicName>'), bolted=False
    )
    got = listen(falling)
    steps(sim, 10)
    assert falling.sensors[0].topic == '/imu'
    assert close(got['old_imu'][-1][1].linear_acceleration, (0, 0, -G), 1e-6)


def test_gazebo_ros_imu_turns_by_r_not_r_transposed(sim):
    # yawed 90 degrees and falling: R (0 0 -g) is still (0 0 -g); spinning about world x
    # reads R (w 0 0) = (0 w 0), where a real IMU would read (0 -w 0)
    model = spawn(
        sim,
        model_imu('<bodyName>base</bodyName>'),
        bolted=False,
        orientation=(0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4)),
    )
    import pybullet as p

    p.resetBaseVelocity(
        model.robot.body, [0, 0, 0], [1.0, 0, 0], physicsClientId=model.robot.client
    )
    got = listen(model)
    steps(sim, 1)
    r = got['old_imu'][-1][1]
    assert close(r.angular_velocity, (0, 1.0, 0), 1e-3)


def test_gazebo_ros_imu_without_body_is_not_loaded(sim, caplog):
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        model = spawn(sim, model_imu('<bodyName>nowhere</bodyName>'))
    assert model.sensors == []
    assert any("'nowhere'" in r.getMessage() for r in caplog.records)


def test_a_rate_over_the_limit_fails_the_spawn_naming_the_plugin(sim):
    from _arm1sim.sim.simulation import SpawnError

    params = '<frameName>f</frameName><updateRateHZ>5000</updateRateHZ>'
    with pytest.raises(SpawnError, match="plugin 'imu_plugin'.*sensor update rate is 5000"):
        spawn(sim, imu_sensor(params))
    assert 'r' not in sim.models
