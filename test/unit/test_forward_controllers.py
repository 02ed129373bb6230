"""The forward command controllers (control/forward_command_controller.py) and
effort_controllers/JointVelocityController (control/joint_velocity_controller.py): each
controller's update rule, start value, topics and error messages, against ros_controllers."""

import logging
import math

import pytest
from conftest import FakeRobot, FakeRos, box_link, control_plugin, transmission

from _arm1sim.control.controller import ControllerError
from _arm1sim.control.registry import CONTROLLER_TYPES
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim

NS = '/iface'
DT_NS = 1000000
POS = 'hardware_interface/PositionJointInterface'
VEL = 'hardware_interface/VelocityJointInterface'
EFF = 'hardware_interface/EffortJointInterface'


def joint(name, kind='revolute', limit='lower="-1" upper="1" effort="5" velocity="2"'):
    return """
  <joint name="%s" type="%s">
    <parent link="base"/><child link="%s_link"/><axis xyz="0 0 1"/><limit %s/>
  </joint>""" % (name, kind, name, limit)


# One joint per interface, and a second of each for the group controllers.
URDF = (
    '<robot name="iface"><link name="world"/>'
    + box_link('base')
    + ''.join(box_link(n + '_link') for n in ('p1', 'p2', 'v1', 'v2', 'e1', 'e2'))
    + '<joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>'
    + joint('p1')
    + joint('p2')
    + joint('v1', 'continuous', 'effort="3" velocity="4"')
    + joint('v2')
    + joint('e1')
    + joint('e2')
    + transmission('p1', POS)
    + transmission('p2', 'PositionJointInterface')
    + transmission('v1', VEL)
    + transmission('v2', VEL)
    + transmission('e1', EFF)
    + transmission('e2', EFF)
    + control_plugin(NS)
    + '</robot>'
)


class Rig:
    """One controller of ``type_name`` with ``params`` on a fake robot."""

    def __init__(self, type_name, **params):
        model = parse_urdf(URDF)
        self.robot = FakeRobot(list(model.joints))
        self.hw = DefaultRobotHWSim(model, self.robot)
        self.ros = FakeRos({'iface': {'c': dict(params, type=type_name)}})
        self.c = CONTROLLER_TYPES[type_name]()
        self.c.name = 'c'
        self.c.init_request(self.hw, self.ros.node_handle(NS), self.ros.node_handle(NS + '/c'))
        self.t = 0

    def at(self, name, position, velocity=0.0):
        self.robot.set(name, position, velocity)
        self.hw.read()

    def start(self):
        self.c.start_request(self.t)

    def command(self, value):
        return self.ros.publish(NS + '/c/command', value)

    def update(self, n=1):
        for _ in range(n):
            self.t += DT_NS
            self.c.update(self.t, DT_NS)

    def cmd(self, name):
        return self.hw.handles[name].command


# ----------------------------------------------------------------------------- registry
@pytest.mark.parametrize(
    'type_name, interface',
    [
        ('position_controllers/JointPositionController', POS),
        ('velocity_controllers/JointVelocityController', VEL),
        ('effort_controllers/JointEffortController', EFF),
        ('position_controllers/JointGroupPositionController', POS),
        ('velocity_controllers/JointGroupVelocityController', VEL),
        ('effort_controllers/JointGroupEffortController', EFF),
        ('effort_controllers/JointVelocityController', EFF),
    ],
)
def test_each_type_is_registered_with_its_interface(type_name, interface):
    assert CONTROLLER_TYPES[type_name].interface == interface


# ----------------------------------------------------------------------------- single joint
def test_position_controller_starts_at_the_current_position_and_forwards_commands():
    rig = Rig('position_controllers/JointPositionController', joint='p1')
    rig.at('p1', 0.3)
    rig.command(0.9)  # before start: overwritten by the start value
    rig.start()
    rig.update()
    assert rig.cmd('p1') == 0.3
    assert rig.command(-0.7) == 1
    rig.update()
    assert rig.cmd('p1') == -0.7
    assert rig.c.claimed_resources() == [(POS, ['p1'])]


def test_forward_controllers_do_not_clamp_the_command():
    # 5.0 is beyond p1's upper limit 1.0: the hardware saturates it, not the controller
    rig = Rig('position_controllers/JointPositionController', joint='p1')
    rig.start()
    rig.command(5.0)
    rig.update()
    assert rig.cmd('p1') == 5.0


@pytest.mark.parametrize(
    'type_name, name',
    [
        ('velocity_controllers/JointVelocityController', 'v1'),
        ('effort_controllers/JointEffortController', 'e1'),
    ],
)
def test_velocity_and_effort_controllers_start_at_zero_and_forward(type_name, name):
    rig = Rig(type_name, joint=name)
    rig.at(name, 0.4, 1.5)
    rig.command(2.5)
    rig.start()
    rig.update()
    assert rig.cmd(name) == 0.0
    rig.command(-1.25)
    rig.update()
    assert rig.cmd(name) == -1.25


def test_effort_forward_controller_leaves_no_effort_when_stopped():
    rig = Rig('effort_controllers/JointEffortController', joint='e1')
    rig.start()
    rig.command(2.0)
    rig.update()
    rig.c.stop_request(rig.t)
    assert rig.cmd('e1') == 0.0


def test_non_finite_command_is_refused_and_the_last_one_held(caplog):
    rig = Rig('velocity_controllers/JointVelocityController', joint='v1')
    rig.start()
    rig.command(1.0)
    with caplog.at_level(logging.WARNING, logger='_arm1sim.control'):
        assert rig.c.set_command(math.nan) is False
    rig.update()
    assert rig.cmd('v1') == 1.0
    assert 'non-finite' in caplog.text


def test_single_joint_controller_without_joint_names_its_namespace():
    with pytest.raises(ControllerError, match=r'No joint given \(namespace: /iface/c\)'):
        Rig('position_controllers/JointPositionController')


@pytest.mark.parametrize(
    'type_name, name, interface',
    [
        ('position_controllers/JointPositionController', 'e1', 'PositionJointInterface'),
        ('velocity_controllers/JointVelocityController', 'p1', 'VelocityJointInterface'),
        ('effort_controllers/JointEffortController', 'v1', 'EffortJointInterface'),
    ],
)
def test_a_joint_of_another_interface_fails_the_load(type_name, name, interface):
    with pytest.raises(ControllerError) as exc:
        Rig(type_name, joint=name)
    assert "Could not find resource '%s' in 'hardware_interface::%s'" % (name, interface) in str(
        exc.value
    )
    assert '/iface/c' in str(exc.value)


# ----------------------------------------------------------------------------- groups
def test_group_position_controller_starts_at_positions_and_maps_data_to_joints_in_order():
    rig = Rig('position_controllers/JointGroupPositionController', joints=['p2', 'p1'])
    rig.at('p1', 0.1)
    rig.at('p2', -0.2)
    rig.start()
    rig.update()
    assert (rig.cmd('p2'), rig.cmd('p1')) == (-0.2, 0.1)
    assert rig.command([0.5, -0.5]) == 1
    rig.update()
    assert (rig.cmd('p2'), rig.cmd('p1')) == (0.5, -0.5)
    assert rig.c.claimed_resources() == [(POS, ['p2', 'p1'])]


@pytest.mark.parametrize(
    'type_name, names',
    [
        ('velocity_controllers/JointGroupVelocityController', ['v1', 'v2']),
        ('effort_controllers/JointGroupEffortController', ['e1', 'e2']),
    ],
)
def test_group_velocity_and_effort_controllers_start_at_zeros(type_name, names):
    rig = Rig(type_name, joints=names)
    rig.at(names[0], 0.3, 2.0)
    rig.command([1.0, 1.0])
    rig.start()
    rig.update()
    assert [rig.cmd(n) for n in names] == [0.0, 0.0]
    rig.command([1.5, -2.5])
    rig.update()
    assert [rig.cmd(n) for n in names] == [1.5, -2.5]


def test_group_command_of_the_wrong_size_is_dropped_with_upstreams_error(caplog):
    rig = Rig('velocity_controllers/JointGroupVelocityController', joints=['v1', 'v2'])
    rig.start()
    rig.command([1.0, 2.0])
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        rig.command([3.0, 4.0, 5.0])
    rig.update()
    assert [rig.cmd('v1'), rig.cmd('v2')] == [1.0, 2.0]
    assert (
        'Dimension of command (3) does not match number of joints (2)! Not executing!'
        in caplog.text
    )


@pytest.mark.parametrize(
    'joints, message',
    [
        (None, "Failed to getParam 'joints' (namespace: /iface/c)."),
        ('p1', "Failed to getParam 'joints' (namespace: /iface/c)."),
        ([], 'List of joint names is empty.'),
    ],
)
def test_group_controller_joints_parameter_errors(joints, message):
    params = {} if joints is None else {'joints': joints}
    with pytest.raises(ControllerError) as exc:
        Rig('position_controllers/JointGroupPositionController', **params)
    assert message in str(exc.value)


def test_group_controller_with_one_joint_of_another_interface_fails_naming_it():
    with pytest.raises(ControllerError, match="'v1' in 'hardware_interface::Effort"):
        Rig('effort_controllers/JointGroupEffortController', joints=['e1', 'v1'])


# ----------------------------------------------------------------------------- velocity PID
VPID = 'effort_controllers/JointVelocityController'


def test_effort_velocity_controller_is_a_pid_on_velocity_error():
    rig = Rig(VPID, joint='e1', pid={'p': 2.0, 'd': 0.001})
    rig.at('e1', 0.5, 0.25)
    rig.start()
    rig.update()
    # command 0 at start: error = -0.25, D on the first error's change from 0
    assert rig.cmd('e1') == pytest.approx(2.0 * -0.25 + 0.001 * (-0.25 / 0.001))
    rig.command(1.0)
    rig.update()
    assert rig.cmd('e1') == pytest.approx(2.0 * 0.75 + 0.001 * (1.0 / 0.001))
    rig.update()
    assert rig.cmd('e1') == pytest.approx(2.0 * 0.75)  # no change in error: no D
    # the effort is not clamped by the controller (the hardware saturates it to 5)
    rig.command(100.0)
    rig.update(2)
    assert rig.cmd('e1') == pytest.approx(2.0 * 99.75)


def test_effort_velocity_controller_state_every_tenth_update():
    rig = Rig(VPID, joint='e1', pid={'p': 1.0, 'i': 0.5, 'i_clamp': 0.3})
    rig.at('e1', 0.0, 0.2)
    rig.start()
    rig.command(1.0)
    rig.update(21)
    states = rig.ros.messages(NS + '/c/state')
    assert len(states) == 3
    s = states[-1]
    assert s['set_point'] == 1.0 and s['process_value'] == 0.2
    assert s['process_value_dot'] == 0.0
    assert s['error'] == pytest.approx(0.8)
    assert s['time_step'] == pytest.approx(0.001)
    assert (s['p'], s['i'], s['i_clamp']) == (1.0, 0.5, 0.3)
    assert s['stamp'] == 21 * DT_NS


def test_effort_velocity_controller_needs_a_p_gain():
    with pytest.raises(ControllerError) as exc:
        Rig(VPID, joint='e1', pid={'d': 1.0})
    assert 'No p gain specified for pid.  Namespace: /iface/c/pid' in str(exc.value)


def test_effort_velocity_controller_refuses_velocity_joints():
    with pytest.raises(ControllerError, match="'v1' in 'hardware_interface::EffortJointInterface'"):
        Rig(VPID, joint='v1', pid={'p': 1.0})


def test_effort_velocity_controller_zeroes_its_effort_on_stop():
    rig = Rig(VPID, joint='e1', pid={'p': 1.0})
    rig.start()
    rig.command(1.0)
    rig.update()
    assert rig.cmd('e1') != 0.0
    rig.c.stop_request(rig.t)
    assert rig.cmd('e1') == 0.0
