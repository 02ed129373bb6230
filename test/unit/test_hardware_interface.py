"""Effort saturation (joint_limits_interface as gazebo_ros_control uses it) and
DefaultRobotHWSim."""

import math

import pytest
from conftest import MIXED_URDF, FakeRobot

from _arm1sim.control.controller import ControllerError
from _arm1sim.control.hardware_interface import EFFORT_JOINT_INTERFACE, enforce_effort_limits
from _arm1sim.description.joint_limits import JointLimits, canonical_interface
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim

ARM1_LIMITS = JointLimits(lower=-1.57, upper=1.57, effort=1.0, velocity=0.5)


# ----------------------------------------------------------------------------- saturation
@pytest.mark.parametrize(
    'command, expected',
    [
        (0.3, 0.3),
        (-0.3, -0.3),
        (1.0, 1.0),
        (5.0, 1.0),
        (-5.0, -1.0),
        (1e9, 1.0),
        (-1e9, -1.0),
    ],
)
def test_effort_is_clamped_to_the_urdf_effort_limit(command, expected):
    assert enforce_effort_limits(command, 0.0, 0.0, ARM1_LIMITS) == expected


def test_beyond_upper_position_limit_pushing_further_out_is_zero():
    assert enforce_effort_limits(0.4, 1.6, 0.0, ARM1_LIMITS) == 0.0
    assert enforce_effort_limits(-0.4, 1.6, 0.0, ARM1_LIMITS) == -0.4  # back in is allowed
    assert enforce_effort_limits(-3.0, 1.6, 0.0, ARM1_LIMITS) == -1.0  # still clamped


def test_beyond_lower_position_limit_pushing_further_out_is_zero():
    assert enforce_effort_limits(-0.4, -1.6, 0.0, ARM1_LIMITS) == 0.0
    assert enforce_effort_limits(0.4, -1.6, 0.0, ARM1_LIMITS) == 0.4
    assert enforce_effort_limits(3.0, -1.6, 0.0, ARM1_LIMITS) == 1.0


def test_at_the_limit_exactly_effort_is_not_cut():
    assert enforce_effort_limits(0.4, 1.57, 0.0, ARM1_LIMITS) == 0.4
    assert enforce_effort_limits(-0.4, -1.57, 0.0, ARM1_LIMITS) == -0.4


def test_beyond_velocity_limit_effort_in_that_direction_is_zero():
    assert enforce_effort_limits(0.5, 0.0, 0.6, ARM1_LIMITS) == 0.0
    assert enforce_effort_limits(-0.5, 0.0, 0.6, ARM1_LIMITS) == -0.5  # braking is allowed
    assert enforce_effort_limits(-0.5, 0.0, -0.6, ARM1_LIMITS) == 0.0
    assert enforce_effort_limits(0.5, 0.0, -0.6, ARM1_LIMITS) == 0.5
    # at or below the limit nothing is cut
    assert enforce_effort_limits(0.5, 0.0, 0.5, ARM1_LIMITS) == 0.5
    assert enforce_effort_limits(0.5, 0.0, 0.49, ARM1_LIMITS) == 0.5


def test_position_and_velocity_cuts_combine():
    # beyond the upper limit and moving down too fast: neither direction may push
    assert enforce_effort_limits(0.5, 1.6, -0.6, ARM1_LIMITS) == 0.0
    assert enforce_effort_limits(-0.5, 1.6, -0.6, ARM1_LIMITS) == 0.0


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_effort_becomes_zero(bad):
    assert enforce_effort_limits(bad, 0.0, 0.0, ARM1_LIMITS) == 0.0


def test_continuous_joint_has_no_position_cut():
    limits = JointLimits(effort=2.0, velocity=10.0)
    assert not limits.has_position_limits
    assert enforce_effort_limits(1.5, 100.0, 0.0, limits) == 1.5
    assert enforce_effort_limits(-3.0, -100.0, 0.0, limits) == -2.0


def test_canonical_interface_accepts_names_with_and_without_prefix():
    assert canonical_interface('EffortJointInterface') == EFFORT_JOINT_INTERFACE
    assert (
        canonical_interface(' hardware_interface/EffortJointInterface\n') == EFFORT_JOINT_INTERFACE
    )
    assert (
        canonical_interface('PositionJointInterface') == 'hardware_interface/PositionJointInterface'
    )


# ----------------------------------------------------------------------------- DefaultRobotHWSim
@pytest.fixture
def mixed_hw():
    model = parse_urdf(MIXED_URDF)
    robot = FakeRobot(list(model.joints))
    return DefaultRobotHWSim(model, robot), robot


def test_hw_exposes_every_transmission_joint_sorted_with_its_interface(mixed_hw):
    hw, _ = mixed_hw
    assert hw.joint_names() == ['flap_joint', 'passive_joint', 'slider_joint', 'wheel_joint']
    assert hw.handles['passive_joint'].interface == 'hardware_interface/PositionJointInterface'
    assert hw.handles['wheel_joint'].interface == EFFORT_JOINT_INTERFACE
    assert hw.handles['wheel_joint'].type == 'continuous'
    assert hw.handles['slider_joint'].limits.upper == pytest.approx(0.2)


def test_get_handle_of_unknown_joint_names_joint_and_controller(mixed_hw):
    hw, _ = mixed_hw
    with pytest.raises(ControllerError) as exc:
        hw.get_handle('passive_joint', EFFORT_JOINT_INTERFACE, '/mixed_ns/passive_controller')
    assert 'passive_joint' in str(exc.value)
    assert '/mixed_ns/passive_controller' in str(exc.value)


def test_get_handle_of_wrong_interface_is_refused(mixed_hw):
    hw, _ = mixed_hw
    with pytest.raises(ControllerError, match='PositionJointInterface'):
        hw.get_handle('flap_joint', 'hardware_interface/PositionJointInterface', '/x/c')
    assert hw.get_handle('flap_joint', None, '/x/c') is hw.handles['flap_joint']


def test_hw_read_and_saturated_write(mixed_hw):
    hw, robot = mixed_hw
    robot.set('flap_joint', 0.5, 0.1)
    robot.set('slider_joint', 0.25, 0.0)  # beyond its upper limit 0.2
    robot.set('wheel_joint', 7.0, 30.0)  # beyond its velocity limit 20
    hw.read()
    assert (hw.handles['flap_joint'].position, hw.handles['flap_joint'].velocity) == (0.5, 0.1)
    hw.handles['flap_joint'].command = 5.0
    hw.handles['slider_joint'].command = 3.0
    hw.handles['wheel_joint'].command = 0.7
    hw.write()
    indices, efforts = robot.applied[-1]
    effort_joints = ['flap_joint', 'slider_joint', 'wheel_joint']
    assert indices == robot.indices(effort_joints)
    by_name = dict(zip(effort_joints, efforts))
    assert by_name == {'flap_joint': 1.0, 'slider_joint': 0.0, 'wheel_joint': 0.0}
    # the handle's effort reports what was applied
    assert hw.handles['flap_joint'].effort == 1.0
    hw.handles['slider_joint'].command = -30.0
    hw.handles['wheel_joint'].command = math.nan
    hw.write()
    by_name = dict(zip(effort_joints, robot.applied[-1][1]))
    assert by_name['slider_joint'] == -10.0
    assert by_name['wheel_joint'] == 0.0
