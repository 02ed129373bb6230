"""gazebo_ros_bumper's contact sensor on real pybullet: a box resting on the ground."""

import logging

import pytest
from helpers import G, box, listen, robot, steps, world

from _arm1sim.physics.contact import ContactSensor


def bumper(collision='<contact><collision>base_collision</collision></contact>', params=''):
    return """<gazebo reference="base"><sensor type="contact" name="bumper">
      <update_rate>50</update_rate>%s
      <plugin name="bumper_plugin" filename="libgazebo_ros_bumper.so">%s</plugin>
    </sensor></gazebo>""" % (collision, params)


@pytest.fixture
def sim():
    s = world(ground=True)
    yield s
    s.close()


def test_a_box_resting_on_the_ground_feels_its_weight(sim):
    mass = 2.0
    model = sim.spawn_urdf('crate', robot(box('base', mass), bumper()), position=(0, 0, 0.1))
    (sensor,) = model.sensors
    assert isinstance(sensor, ContactSensor)
    assert (sensor.topic, sensor.frame_id) == ('/bumper_states', 'world')
    got = listen(model)
    steps(sim, 1000)
    assert len(got['bumper']) in (50, 51)  # on the 20 ms marks, and at the first step
    _, pairs = got['bumper'][-1]
    (pair,) = pairs
    assert pair.collision1 == 'crate::base::base_collision'
    assert pair.collision2 == 'ground_plane::link::collision'
    assert len(pair.wrenches) == len(pair.positions) == len(pair.normals) == len(pair.depths) >= 1
    total = [sum(w[0][i] for w in pair.wrenches) for i in range(3)]
    assert abs(total[2] - mass * G) < 0.02 * mass * G
    assert abs(total[0]) < 1e-3 and abs(total[1]) < 1e-3
    assert all(abs(n[2] - 1) < 1e-9 for n in pair.normals)
    assert all(abs(pos[2]) < 2e-3 for pos in pair.positions)
    assert all(d >= 0 for d in pair.depths)


def test_the_wrench_is_in_the_link_frame(sim):
    # the box spawned upside down: the ground pushes along its own -z
    model = sim.spawn_urdf(
        'crate', robot(box('base', 1.0), bumper()), position=(0, 0, 0.1), orientation=(1, 0, 0, 0)
    )
    got = listen(model)
    steps(sim, 500)
    (pair,) = got['bumper'][-1][1]
    total_z = sum(w[0][2] for w in pair.wrenches)
    assert abs(total_z + G) < 0.02 * G
    assert all(abs(n[2] - 1) < 1e-9 for n in pair.normals)  # normals stay in world axes


def test_in_the_air_it_reports_no_states(sim):
    model = sim.spawn_urdf('crate', robot(box('base'), bumper()), position=(0, 0, 5))
    got = listen(model)
    steps(sim, 100)
    assert got['bumper'] and all(pairs == [] for _, pairs in got['bumper'])


def test_without_a_collision_named_it_reports_nothing_and_says_so(sim, caplog):
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        model = sim.spawn_urdf(
            'crate',
            robot(
                box('base'),
                bumper(
                    collision='',
                    params='<bumperTopicName>hits</bumperTopicName><frameName>/base</frameName>',
                ),
            ),
            position=(0, 0, 0.1),
        )
    (sensor,) = model.sensors
    assert (sensor.topic, sensor.frame_id) == ('/hits', '/base')
    assert any(
        "sensor 'bumper'" in r.getMessage() and '<collision>' in r.getMessage()
        for r in caplog.records
    )
    got = listen(model)
    steps(sim, 200)
    assert all(pairs == [] for _, pairs in got['bumper'])
