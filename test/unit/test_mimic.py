"""URDF <mimic> joints and roboticsgroup's mimic joint plugin: parsed into (follower, leader,
multiplier, offset), and followed in real pybullet physics."""

import os

import pytest
from conftest import REPO_ROOT, WORLD_FILE

from arm1.description.sdf_world import read_world
from arm1.description.urdf_model import UrdfError, parse_urdf
from arm1.sim.simulation import Simulation

GRIPPER = os.path.join(REPO_ROOT, 'test', 'config', 'gripper_bot.urdf')

TWO_ARMS = """<robot name="two">
  <link name="world"/><link name="base"/><link name="a"/><link name="b"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <joint name="lead" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="5" velocity="1"/></joint>
  <joint name="follow" type="revolute"><parent link="base"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="5" velocity="1"/>%s</joint>
  %s
</robot>"""

PLUGIN = """<gazebo><plugin name="m" filename="%s">
    <joint>lead</joint><mimicJoint>follow</mimicJoint><multiplier>0.5</multiplier>
    <offset>0.2</offset><maxEffort>3</maxEffort><sensitiveness>0.01</sensitiveness>
  </plugin></gazebo>"""


def urdf(mimic='', plugin=''):
    return TWO_ARMS.replace('<link name="a"/>', _link('a')).replace(
        '<link name="b"/>', _link('b')
    ) % (mimic, plugin)


def _link(name):
    return (
        '<link name="%s"><inertial><origin xyz="0.1 0 0"/><mass value="0.1"/><inertia ixx="1e-4" '
        'ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>' % name
    )


def test_urdf_mimic_is_read_with_its_multiplier_and_offset():
    model = parse_urdf(urdf('<mimic joint="lead" multiplier="-2" offset="0.3"/>'))
    (m,) = model.mimics
    assert (m.follower, m.leader, m.multiplier, m.offset, m.max_effort) == (
        'follow',
        'lead',
        -2.0,
        0.3,
        None,
    )


def test_mimic_defaults_are_multiplier_one_offset_zero():
    (m,) = parse_urdf(urdf('<mimic joint="lead"/>')).mimics
    assert (m.multiplier, m.offset) == (1.0, 0.0)


@pytest.mark.parametrize(
    'filename',
    [
        'libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so',
        'libroboticsgroup_gazebo_mimic_joint_plugin.so',
    ],
)
def test_roboticsgroup_plugin_is_read_as_a_mimic(filename):
    (m,) = parse_urdf(urdf(plugin=PLUGIN % filename)).mimics
    assert (m.follower, m.leader, m.multiplier, m.offset, m.max_effort, m.sensitiveness) == (
        'follow',
        'lead',
        0.5,
        0.2,
        3.0,
        0.01,
    )


def test_a_mimic_of_an_unknown_joint_names_it():
    with pytest.raises(UrdfError, match="leader 'nope'"):
        parse_urdf(urdf('<mimic joint="nope"/>'))


def test_a_non_numeric_multiplier_names_the_joint():
    with pytest.raises(UrdfError, match="joint 'follow' <mimic>"):
        parse_urdf(urdf('<mimic joint="lead" multiplier="x"/>'))


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def positions(model, names):
    return [pos for pos, _ in model.robot.read(model.robot.indices(names))]


def test_a_mimic_joint_follows_its_leader_times_multiplier_plus_offset(sim):
    model = sim.spawn_urdf('two', urdf('<mimic joint="lead" multiplier="-0.5" offset="0.3"/>'))
    model.robot.set_joint_positions({'lead': 1.0})
    for _ in range(500):
        sim.step()
    lead, follow = positions(model, ['lead', 'follow'])
    assert follow == pytest.approx(lead * -0.5 + 0.3, abs=1e-3)


def test_a_plugin_mimic_follows_a_moving_leader(sim):
    model = sim.spawn_urdf(
        'two', urdf(plugin=PLUGIN % 'libroboticsgroup_gazebo_mimic_joint_plugin.so')
    )
    i = model.robot.indices(['lead'])
    for k in range(1000):  # the leader sweeps at 1 rad/s
        model.robot.set_velocity_motors(i, [1.0], [50.0])
        sim.step()
    lead, follow = positions(model, ['lead', 'follow'])
    assert lead == pytest.approx(1.0, abs=0.05)
    assert follow == pytest.approx(lead * 0.5 + 0.2, abs=0.02)


def test_gripper_mimic_finger_mirrors_the_leader(sim):
    with open(GRIPPER) as f:
        model = sim.spawn_urdf('gripper', f.read())
    model.robot.set_joint_positions({'left_finger_joint': 0.03})
    for _ in range(300):
        sim.step()
    left, right = positions(model, ['left_finger_joint', 'right_finger_joint'])
    assert right == pytest.approx(-left, abs=1e-3)
    assert left > 0.02  # the leader was not dragged back by the follower's motor
