"""effort_controllers/JointPositionController (control/joint_position_controller.py)."""

import math

import pytest
from conftest import JPC, MIXED_URDF, FakeRobot, FakeRos
from helpers import PositionControllerRig as Rig

from _arm1sim.control.controller import ControllerError
from _arm1sim.control.joint_position_controller import JointPositionController
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim

NS = '/mixed_ns'
DT = 0.001
DT_NS = 1000000
STATE_FIELDS = {
    'stamp',
    'set_point',
    'process_value',
    'process_value_dot',
    'error',
    'time_step',
    'command',
    'p',
    'i',
    'd',
    'i_clamp',
    'antiwindup',
}


def test_init_requires_joint_parameter():
    ros = FakeRos({'ns': {'c': {'type': JPC, 'pid': {'p': 1}}}})
    hw = DefaultRobotHWSim(parse_urdf(MIXED_URDF), FakeRobot(list(parse_urdf(MIXED_URDF).joints)))
    with pytest.raises(ControllerError, match="'joint'"):
        JointPositionController().init(hw, ros.node_handle('/ns'), ros.node_handle('/ns/c'))


def test_init_without_p_fails_with_no_p_gain_message():
    ros = FakeRos({'ns': {'c': {'type': JPC, 'joint': 'flap_joint', 'pid': {'i': 1}}}})
    hw = DefaultRobotHWSim(parse_urdf(MIXED_URDF), FakeRobot(list(parse_urdf(MIXED_URDF).joints)))
    with pytest.raises(ControllerError, match=r'No p gain specified for pid\..*/ns/c/pid'):
        JointPositionController().init(hw, ros.node_handle('/ns'), ros.node_handle('/ns/c'))


def test_subscribes_command_and_advertises_state_under_the_controller_namespace():
    rig = Rig('flap_joint', {'p': 1})
    assert list(rig.ros.subscribers) == [NS + '/c/command']
    assert list(rig.ros.publishers) == [NS + '/c/state']
    assert rig.c.claimed_resources() == [
        ('hardware_interface/EffortJointInterface', ['flap_joint'])
    ]


def test_starting_holds_the_current_position_and_drops_earlier_commands():
    rig = Rig('flap_joint', {'p': 2.0})
    rig.at(0.7)
    rig.command(-2.0)  # before start: dropped
    rig.start()
    assert rig.c.target == pytest.approx(0.7)
    assert rig.update() == pytest.approx(0.0)
    assert rig.states()[-1]['set_point'] == pytest.approx(0.7)


def test_restarting_drops_the_old_target():
    rig = Rig('flap_joint', {'p': 2.0})
    rig.start()
    rig.command(1.0)
    rig.update()
    rig.stop()
    rig.command(2.0)  # while stopped: dropped
    rig.at(0.4)
    rig.start()
    assert rig.c.target == pytest.approx(0.4)
    assert rig.update() == pytest.approx(0.0)


def test_stopping_leaves_no_effort_on_the_joint():
    rig = Rig('flap_joint', {'p': 2.0})
    rig.start()
    rig.command(1.0)
    assert rig.update() == pytest.approx(2.0)
    rig.stop()
    assert rig.c.state == 'stopped'
    assert rig.hw.handles['flap_joint'].command == 0.0


def test_starting_resets_the_pid():
    rig = Rig('flap_joint', {'p': 0.0, 'd': 1.0})
    rig.start()
    rig.command(1.0)
    rig.update()  # previous error becomes 1.0
    rig.at(0.0)
    rig.stop()
    rig.start()
    rig.command(0.5)
    # after the reset the derivative uses a previous error of 0: (0.5 - 0) / dt
    assert rig.update() == pytest.approx(0.5 / DT)


def test_effort_is_pid_of_position_error():
    rig = Rig('flap_joint', {'p': 3.0})
    rig.at(0.2)
    rig.start()
    rig.command(0.5)
    assert rig.update() == pytest.approx(3.0 * 0.3)


@pytest.mark.parametrize(
    'joint, cmd, clamped',
    [
        ('flap_joint', 10.0, 3.0),
        ('flap_joint', -10.0, -3.0),
        ('slider_joint', 1.0, 0.2),
        ('slider_joint', -1.0, -0.1),
    ],
)
def test_command_is_clamped_to_urdf_limits(joint, cmd, clamped):
    rig = Rig(joint, {'p': 1.0})
    rig.at(0.0)
    rig.start()
    rig.command(cmd)
    effort = rig.update()
    state = rig.states()[-1]
    assert state['set_point'] == pytest.approx(clamped)
    assert state['error'] == pytest.approx(clamped)
    assert effort == pytest.approx(clamped)  # p = 1, from 0


def test_continuous_joint_is_not_clamped_and_wraps_the_error():
    rig = Rig('wheel_joint', {'p': 1.0})
    rig.at(3.0)
    rig.start()
    rig.command(-3.0)
    rig.update()
    state = rig.states()[-1]
    assert state['set_point'] == pytest.approx(-3.0)
    assert state['error'] == pytest.approx(2 * math.pi - 6.0)  # +0.283: across +-pi
    # a target many turns away is the same direction
    rig.command(3.0 + 10 * math.pi + 0.1)
    rig.update(10)
    assert rig.states()[-1]['error'] == pytest.approx(0.1, abs=1e-9)


def test_prismatic_error_is_the_plain_difference():
    rig = Rig('slider_joint', {'p': 1.0})
    rig.at(-0.05)
    rig.start()
    rig.command(0.15)
    rig.update()
    assert rig.states()[-1]['error'] == pytest.approx(0.2)


def test_revolute_error_respects_the_limits_going_the_long_way_round():
    """flap_joint is limited to [-3, 3]: from 2.9 to -2.9 the short way crosses the gap."""
    rig = Rig('flap_joint', {'p': 1.0})
    rig.at(2.9)
    rig.start()
    rig.command(-2.9)
    rig.update()
    assert rig.states()[-1]['error'] == pytest.approx(-5.8)


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_commands_are_ignored_and_the_last_target_held(bad):
    rig = Rig('flap_joint', {'p': 1.0})
    rig.at(0.0)
    rig.start()
    rig.command(0.5)
    rig.command(bad)
    assert rig.c.target == pytest.approx(0.5)
    effort = rig.update()
    assert effort == pytest.approx(0.5)
    assert rig.states()[-1]['set_point'] == pytest.approx(0.5)


def test_state_is_published_every_tenth_update_with_the_listed_fields():
    rig = Rig('flap_joint', {'p': 2.0, 'i': 0.5, 'd': 0.01, 'i_clamp': 0.3, 'antiwindup': True})
    rig.at(0.1, 0.05)
    rig.start()
    rig.command(0.4)
    stamps = []
    for k in range(25):
        stamps.append(rig.t)
        rig.update()
    states = rig.states()
    assert len(states) == 3
    assert [s['stamp'] for s in states] == [stamps[0], stamps[10], stamps[20]]
    s = states[0]
    assert set(s) == STATE_FIELDS
    assert s['set_point'] == pytest.approx(0.4)
    assert s['process_value'] == pytest.approx(0.1)
    assert s['process_value_dot'] == pytest.approx(0.05)
    assert s['error'] == pytest.approx(0.3)
    assert s['time_step'] == pytest.approx(DT)
    assert s['command'] == pytest.approx(rig.c.pid.p * 0.3 + 0.5 * 0.3 * DT + 0.01 * 0.3 / DT)
    assert (s['p'], s['i'], s['d'], s['i_clamp']) == (2.0, 0.5, 0.01, 0.3)
    assert s['antiwindup'] is True


def test_state_set_point_reports_the_clamped_command():
    rig = Rig('slider_joint', {'p': 1.0})
    rig.start()
    rig.command(5.0)
    rig.update()
    assert rig.states()[-1]['set_point'] == pytest.approx(0.2)
    assert rig.states()[-1]['error'] == pytest.approx(0.2)


def test_state_nobody_subscribes_to_is_not_built_and_the_control_is_the_same():
    """As roscpp serialises nothing for a topic without subscribers: the state of the
    updates nobody listens to is skipped, the efforts and the every-tenth schedule are not."""
    heard, deaf = Rig('flap_joint', {'p': 2.0, 'd': 0.01}), Rig('flap_joint', {'p': 2.0, 'd': 0.01})
    (pub,) = deaf.ros.publishers[NS + '/c/state']
    pub.subscribed = False
    efforts = {id(heard): [], id(deaf): []}
    for rig in (heard, deaf):
        rig.at(0.1, 0.05)
        rig.start()
        rig.command(0.4)
        for k in range(25):
            if k == 15 and rig is deaf:
                pub.subscribed = True  # a subscriber comes: the next tenth update is sent
            rig.update()
            efforts[id(rig)].append(rig.c.joint.command)
    assert efforts[id(heard)] == efforts[id(deaf)]
    assert [s['stamp'] for s in deaf.states()] == [heard.states()[2]['stamp']]
    assert deaf.states()[0] == heard.states()[2]
