"""DefaultRobotHWSim's position and velocity interfaces (sim/robot_hw_sim.py), as
gazebo_ros_control's writeSim has them: with a fake robot for the exact writes, and
with real pybullet for what the joints do."""

import logging
import math

import pytest
from conftest import WORLD_FILE, FakeRobot, FakeRos, box_link, control_plugin, transmission

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.sdf_world import read_world
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.sim.robot_hw_sim import UNLIMITED_MOTOR_FORCE, DefaultRobotHWSim
from _arm1sim.sim.simulation import Simulation

POS = 'hardware_interface/PositionJointInterface'
VEL = 'hardware_interface/VelocityJointInterface'
DT = 0.001


def joint(name, kind, limit, axis='0 0 1', xyz='0 0 0.1'):
    return """
  <joint name="%s" type="%s">
    <parent link="base"/><child link="%s_link"/><origin xyz="%s"/><axis xyz="%s"/>%s
  </joint>""" % (name, kind, name, xyz, axis, limit and '<limit %s/>' % limit)


# A horizontal arm on a vertical-axis position joint, one on a horizontal-axis position joint
# (gravity pulls it), a wheel on a velocity joint and a continuous position joint.
URDF = (
    '<robot name="iface"><link name="world"/>'
    + box_link('base', '0.2 0.2 0.05', 2.0)
    + box_link('pos_link', '0.2 0.02 0.02', 0.2, xyz='0.1 0 0')
    + box_link('grav_link', '0.2 0.02 0.02', 0.2, xyz='0.1 0 0')
    + box_link('vel_link', '0.1 0.1 0.02', 0.3)
    + box_link('turn_link', '0.1 0.02 0.02', 0.1)
    + '<joint name="fix" type="fixed"><parent link="world"/><child link="base"/>'
    '<origin xyz="0 0 0.5"/></joint>'
    + joint('pos', 'revolute', 'lower="-1" upper="1.5" effort="5" velocity="2"')
    + joint(
        'grav', 'revolute', 'lower="-2" upper="2" effort="10" velocity="3"', '0 1 0', '0 0.3 0.1'
    )
    + joint('vel', 'continuous', 'effort="2" velocity="6"', xyz='0 -0.3 0.1')
    + joint('turn', 'continuous', '', xyz='0.3 0 0.1')
    + transmission('pos', POS)
    + transmission('grav', 'PositionJointInterface')
    + transmission('vel', VEL)
    + transmission('turn', POS)
    + control_plugin('/iface')
    + '</robot>'
)
NAMES = ['grav', 'pos', 'turn', 'vel']


@pytest.fixture
def fake():
    model = parse_urdf(URDF)
    robot = FakeRobot(list(model.joints))
    return DefaultRobotHWSim(model, robot, DT), robot


def by_name(robot, indices, values):
    names = {i: n for n, i in robot.joint_index.items()}
    return {names[i]: v for i, v in zip(indices, values)}


# ----------------------------------------------------------------------------- exact writes
def test_every_interface_gets_a_handle_named_by_its_transmission(fake):
    hw, _ = fake
    assert hw.joint_names() == NAMES
    assert {n: hw.handles[n].interface for n in NAMES} == {
        'grav': POS,
        'pos': POS,
        'turn': POS,
        'vel': VEL,
    }


def test_set_joints_get_a_motor_capped_at_their_effort_limit_at_start(fake):
    # Gazebo sets fmax = the effort limit on joints it sets directly
    hw, robot = fake
    indices, velocities, forces = robot.motors[-1]
    assert velocities == [0.0] * 4
    assert by_name(robot, indices, forces) == {
        'grav': 10.0,
        'pos': 5.0,
        'turn': UNLIMITED_MOTOR_FORCE,
        'vel': 2.0,
    }


def test_position_command_is_set_within_limits_and_one_velocity_step_from_the_last(fake):
    hw, robot = fake
    robot.set('pos', 0.5)
    hw.read()
    hw.handles['pos'].command = 1.0
    hw.write()
    placed = by_name(robot, *robot.placed[-1])
    # 2 rad/s over 1 ms from the measured 0.5
    assert placed['pos'] == pytest.approx(0.502)
    for _ in range(1000):
        hw.handles['pos'].command = 3.0  # beyond the upper limit 1.5
        hw.write()
    assert by_name(robot, *robot.placed[-1])['pos'] == pytest.approx(1.5)
    # without a velocity limit (no <limit>) the continuous joint jumps to the command
    assert by_name(robot, *robot.placed[-1])['turn'] == 0.0
    hw.handles['turn'].command = 10.0
    hw.write()
    assert by_name(robot, *robot.placed[-1])['turn'] == 10.0


def test_position_joints_go_to_command_zero_until_a_controller_writes(fake):
    hw, robot = fake
    robot.set('grav', 1.0)
    hw.read()
    hw.write()
    assert by_name(robot, *robot.placed[-1])['grav'] == pytest.approx(1.0 - 3 * DT)


def test_a_non_finite_position_command_holds_the_last(fake):
    hw, robot = fake
    robot.set('turn', 0.25)
    hw.read()
    hw.handles['turn'].command = math.nan
    hw.write()
    assert by_name(robot, *robot.placed[-1])['turn'] == 0.25


def test_velocity_command_drives_a_motor_clamped_to_the_velocity_limit(fake):
    hw, robot = fake
    hw.handles['vel'].command = 4.0
    hw.write()
    indices, velocities, forces = robot.motors[-1]
    assert by_name(robot, indices, velocities) == {'vel': 4.0}
    assert forces == [2.0]
    hw.handles['vel'].command = -50.0
    hw.write()
    assert robot.motors[-1][1] == [-6.0]
    hw.handles['vel'].command = math.inf
    hw.write()
    assert robot.motors[-1][1] == [0.0]


def test_with_pid_gains_position_and_velocity_joints_are_driven_by_clamped_effort(fake):
    hw, robot = fake
    hw.set_pid_gains({'pos': {'p': 100.0}, 'vel': {'p': 3.0}})
    # their motors are switched off so that effort acts; the others keep theirs
    indices, _, forces = robot.motors[-1]
    assert by_name(robot, indices, forces) == {
        'grav': 10.0,
        'pos': 0.0,
        'turn': UNLIMITED_MOTOR_FORCE,
        'vel': 0.0,
    }
    robot.set('pos', 0.2)
    robot.set('vel', 0.0, 1.0)
    hw.read()
    hw.handles['pos'].command = 0.2005  # within one velocity step
    hw.handles['vel'].command = 1.5
    hw.write()
    efforts = by_name(robot, *robot.applied[-1])
    assert efforts == {'pos': pytest.approx(100.0 * 0.0005), 'vel': pytest.approx(1.5)}
    assert hw.handles['pos'].effort == pytest.approx(0.05)
    hw.handles['pos'].command = -0.8  # saturated to one step: 0.2 - 0.002, error -0.0015
    hw.handles['vel'].command = 5.0  # effort 3 * 4 = 12, clamped to the effort limit 2
    hw.write()
    efforts = by_name(robot, *robot.applied[-1])
    assert efforts == {'pos': pytest.approx(100.0 * (0.2005 - 0.002 - 0.2)), 'vel': 2.0}
    assert set(by_name(robot, *robot.placed[-1])) == {'grav', 'turn'}


def test_gains_without_p_name_the_joint_and_leave_it_set_directly(fake, caplog):
    hw, robot = fake
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        hw.set_pid_gains({'grav': {'d': 1.0}})
    assert "joint 'grav'" in caplog.text and 'No p gain specified' in caplog.text
    hw.write()
    assert 'grav' in by_name(robot, *robot.placed[-1])


def test_an_unsimulated_interface_leaves_the_joint_passive_with_upstreams_message(caplog):
    xml = URDF.replace(VEL, 'hardware_interface/PosVelJointInterface')
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        hw = DefaultRobotHWSim(parse_urdf(xml), FakeRobot(list(parse_urdf(xml).joints)))
    assert 'vel' not in hw.handles
    assert (
        "No matching hardware interface found for 'hardware_interface/PosVelJointInterface'"
        " while loading interfaces for vel" in caplog.text
    )


def test_joint_limits_parameters_override_the_urdfs_per_kind(fake):
    hw, robot = fake
    hw.set_joint_limits(
        {
            # position: range narrowed, velocity limit raised, effort cap lowered
            'pos': {
                'has_position_limits': True,
                'min_position': -0.5,
                'max_position': 0.5,
                'has_velocity_limits': True,
                'max_velocity': 10.0,
                'has_effort_limits': True,
                'max_effort': 1.0,
            },
            # velocity: no velocity limit any more, and an acceleration limit
            'vel': {
                'has_velocity_limits': False,
                'has_acceleration_limits': True,
                'max_acceleration': 100.0,
            },
            # has_* true without its values: the URDF's stay
            'grav': {'has_velocity_limits': True},
        }
    )
    brakes = robot.motors[-1]
    robot.set('pos', 0.0)
    robot.set('grav', 0.0)
    hw.read()
    hw.handles['pos'].command = 0.3
    hw.handles['grav'].command = 1.0
    hw.handles['vel'].command = 50.0
    hw.write()
    placed = by_name(robot, *robot.placed[-1])
    assert placed['pos'] == pytest.approx(10.0 * DT)  # the raised velocity limit
    assert placed['grav'] == pytest.approx(3.0 * DT)  # the URDF's 3 rad/s
    assert robot.motors[-1][1] == [pytest.approx(100.0 * DT)]  # one acceleration step
    for _ in range(1000):
        hw.handles['pos'].command = 0.9
        hw.handles['vel'].command = 50.0
        hw.write()
    assert by_name(robot, *robot.placed[-1])['pos'] == pytest.approx(0.5)
    assert robot.motors[-1][1] == [pytest.approx(50.0)]  # beyond the URDF's 6: none now
    # the motor that holds the set joint between teleports is capped at the new effort limit
    assert by_name(robot, brakes[0], brakes[2])['pos'] == 1.0


def test_bad_joint_limits_parameters_name_the_joint_and_keep_the_urdfs(fake, caplog):
    hw, robot = fake
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        hw.set_joint_limits({'pos': {'has_velocity_limits': True, 'max_velocity': 'fast'}})
    assert 'joint_limits/pos' in caplog.text
    robot.set('pos', 0.0)
    hw.read()
    hw.handles['pos'].command = 1.0
    hw.write()
    assert by_name(robot, *robot.placed[-1])['pos'] == pytest.approx(2.0 * DT)


# Soft limits: one joint per interface, each with a <safety_controller> inside [-1, 1].
SAFETY = (
    '<safety_controller soft_lower_limit="-0.5" soft_upper_limit="0.5" k_position="10"'
    ' k_velocity="2"/>'
)
SOFT_URDF = (
    '<robot name="soft"><link name="world"/>'
    + box_link('base')
    + ''.join(box_link(n + '_link') for n in ('se', 'sp', 'sv'))
    + '<joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>'
    + ''.join(
        '<joint name="%s" type="revolute"><parent link="base"/><child link="%s_link"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="3" velocity="4"/>%s</joint>'
        % (n, n, SAFETY)
        for n in ('se', 'sp', 'sv')
    )
    + transmission('se')
    + transmission('sp', POS)
    + transmission('sv', VEL)
    + control_plugin('/soft')
    + '</robot>'
)


@pytest.fixture
def soft():
    model = parse_urdf(SOFT_URDF)
    robot = FakeRobot(list(model.joints))
    return DefaultRobotHWSim(model, robot, DT), robot


def test_safety_controller_is_read_into_soft_limits():
    limits = parse_urdf(SOFT_URDF).joints['sp'].limits
    assert (limits.soft.lower, limits.soft.upper) == (-0.5, 0.5)
    assert (limits.soft.k_position, limits.soft.k_velocity) == (10.0, 2.0)


def test_soft_limits_bound_an_effort_joints_effort_by_velocity(soft):
    hw, robot = soft
    # inside the soft range at rest: velocity bounds -k_p * (pos - soft limit) = (-5, 5),
    # within +-4: (-4, 4); effort bounds -k_v * (vel - bound) = (-8, 8) -> (-3, 3): it passes
    robot.set('se', 0.0, 0.0)
    hw.read()
    hw.handles['se'].command = 2.5
    hw.write()
    assert by_name(robot, *robot.applied[-1])['se'] == 2.5
    # beyond the soft upper limit (0.7): velocity bounds (-4, -2); moving up at 1 rad/s the
    # effort may be at most -2 * (1 - (-2)) = -6 -> -3: pushed back whatever the command
    robot.set('se', 0.7, 1.0)
    hw.read()
    hw.handles['se'].command = 2.5
    hw.write()
    assert by_name(robot, *robot.applied[-1])['se'] == -3.0
    # moving down already at -2.5 rad/s: the upper bound -2 * (-2.5 + 2) = 1.0
    robot.set('se', 0.7, -2.5)
    hw.read()
    hw.write()
    assert by_name(robot, *robot.applied[-1])['se'] == pytest.approx(1.0)


def test_soft_limits_slow_a_position_joint_near_its_soft_limit(soft):
    hw, robot = soft
    robot.set('sp', 0.45)
    hw.read()
    hw.handles['sp'].command = 1.0
    hw.write()
    # upper velocity bound -10 * (0.45 - 0.5) = 0.5 rad/s, not the URDF's 4
    assert by_name(robot, *robot.placed[-1])['sp'] == pytest.approx(0.45 + 0.5 * DT)
    for _ in range(5000):
        hw.handles['sp'].command = 1.0  # a controller writes it every update
        hw.write()
    # it approaches the soft limit and never passes it
    assert by_name(robot, *robot.placed[-1])['sp'] == pytest.approx(0.5, abs=1e-6)


def test_soft_limits_bound_a_velocity_joints_velocity_by_position(soft):
    hw, robot = soft
    robot.set('sv', 0.4)
    hw.read()
    hw.handles['sv'].command = 3.0
    hw.write()
    assert robot.motors[-1][1] == [pytest.approx(-10.0 * (0.4 - 0.5))]  # 1.0
    robot.set('sv', 0.6)
    hw.read()
    hw.write()
    assert robot.motors[-1][1] == [pytest.approx(-1.0)]  # beyond: driven back
    hw.handles['sv'].command = -3.0
    hw.write()
    assert robot.motors[-1][1] == [pytest.approx(-3.0)]  # towards the range: allowed


def test_a_safety_controller_without_k_velocity_is_refused_naming_the_joint():
    with pytest.raises(UrdfError, match="joint 'se' <safety_controller> has no k_velocity"):
        parse_urdf(SOFT_URDF.replace(' k_velocity="2"', '', 1))


# ----------------------------------------------------------------------------- real pybullet
@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def spawn(sim, params, gains=None):
    ros = FakeRos({'iface': params})
    model = sim.spawn_urdf(
        'iface',
        URDF,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    if gains:
        model.hw.set_pid_gains(gains)
    names = sorted(params)
    for n in names:
        model.controller_manager.load_controller(n)
    ok, _ = switch_while_updating(model.controller_manager, names, [], sim.step, 2, poll=0.0005)
    assert ok
    return model, ros


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.period))):
        sim.step()


def state(model, name):
    return model.robot.read(model.robot.indices([name]))[0]


CONTROLLERS = {
    'pos_controller': {'type': 'position_controllers/JointPositionController', 'joint': 'pos'},
    'grav_controller': {'type': 'position_controllers/JointPositionController', 'joint': 'grav'},
    'vel_controller': {'type': 'velocity_controllers/JointVelocityController', 'joint': 'vel'},
}


def test_position_joints_reach_their_commands_at_the_velocity_limit_and_velocity_is_held(sim):
    model, ros = spawn(sim, CONTROLLERS)
    ros.publish('/iface/pos_controller/command', 1.2)
    ros.publish('/iface/grav_controller/command', -0.9)  # gravity pulls on this one
    ros.publish('/iface/vel_controller/command', 3.0)
    run(sim, 0.3)
    # 2 rad/s: 0.6 rad after 0.3 s, not yet there
    assert state(model, 'pos')[0] == pytest.approx(0.6, abs=0.01)
    run(sim, 0.7)
    assert state(model, 'pos')[0] == pytest.approx(1.2, abs=1e-3)
    assert state(model, 'grav')[0] == pytest.approx(-0.9, abs=1e-3)
    assert state(model, 'vel')[1] == pytest.approx(3.0, abs=0.05)
    ros.publish('/iface/vel_controller/command', -2.0)
    run(sim, 0.5)
    assert state(model, 'vel')[1] == pytest.approx(-2.0, abs=0.05)


def test_a_velocity_command_beyond_the_limit_turns_at_the_limit(sim):
    model, ros = spawn(sim, CONTROLLERS)
    ros.publish('/iface/vel_controller/command', 50.0)
    run(sim, 1.0)
    assert state(model, 'vel')[1] == pytest.approx(6.0, abs=0.05)


def test_hardware_pids_drive_position_and_velocity_joints_through_effort(sim):
    model, ros = spawn(sim, CONTROLLERS, gains={'pos': {'p': 20.0, 'd': 0.5}, 'vel': {'p': 0.5}})
    ros.publish('/iface/pos_controller/command', 0.8)
    ros.publish('/iface/vel_controller/command', 2.0)
    run(sim, 2.0)
    assert state(model, 'pos')[0] == pytest.approx(0.8, abs=0.01)
    assert state(model, 'vel')[1] == pytest.approx(2.0, abs=0.05)
