"""What the move_group stand-in makes of a *_moveit_config's parameters: the planning
pipeline's place (MoveIt 1.1's planning_pipelines/ or the older flat layout), the
controller list, and how a trajectory is shared among controllers.

Needs the built workspace (moveit_msgs): tools/ws-run python -m pytest ...
"""

from __future__ import annotations

import pytest
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from _arm1sim.planning.config import ConfigError, controller_list, execution_config
from _arm1sim.ros.moveit.execution import select_controllers, split
from _arm1sim.ros.moveit.move_group import MoveGroup

ARM = ['j1', 'j2', 'j3']
CONTROLLERS = controller_list(
    [
        {'name': 'arm', 'action_ns': 'follow_joint_trajectory', 'joints': ARM, 'default': True},
        {'name': 'gripper', 'type': 'GripperCommand', 'joints': ['f1', 'f2'], 'max_effort': 5},
        {'name': 'wrist_only', 'joints': ['j3']},
    ]
)


def test_pipelines_as_moveit_1_1_lays_them_out_and_the_older_flat_layout():
    ompl = {'planning_plugin': 'ompl_interface/OMPLPlanner', 'planner_configs': {'RRT': {}}}
    chomp = {'planning_plugin': 'chomp_interface/CHOMPPlanner'}
    private = {'planning_pipelines': {'ompl': ompl, 'chomp': chomp}}
    assert MoveGroup._pipeline_params({**private, 'default_planning_pipeline': 'ompl'}) == ompl
    # a pipeline of another planner: OMPL's plans
    assert MoveGroup._pipeline_params({**private, 'default_planning_pipeline': 'chomp'}) == ompl
    flat = {'planning_plugin': 'ompl_interface/OMPLPlanner', 'planner_configs': {}}
    assert MoveGroup._pipeline_params(flat) is flat


def test_controller_list_entries_and_defaults():
    arm, gripper, _ = CONTROLLERS
    assert (arm.type, arm.action_ns, arm.default) == (
        'FollowJointTrajectory',
        'follow_joint_trajectory',
        True,
    )
    assert (gripper.type, gripper.max_effort) == ('GripperCommand', 5.0)
    with pytest.raises(ConfigError, match="'x' lists no joints"):
        controller_list([{'name': 'x', 'joints': []}])
    with pytest.raises(ConfigError, match='no name'):
        controller_list([{'joints': ['a']}])
    cfg = execution_config({'allowed_start_tolerance': 0.02})
    assert (cfg.allowed_start_tolerance, cfg.allowed_execution_duration_scaling) == (0.02, 1.1)


def test_controllers_covering_a_trajectory():
    assert [c.name for c in select_controllers(ARM, CONTROLLERS)] == ['arm']
    both = select_controllers(ARM + ['f1', 'f2'], CONTROLLERS)
    assert [c.name for c in both] == ['arm', 'gripper']
    assert [c.name for c in select_controllers(['j3'], CONTROLLERS)] == ['arm']  # default first
    assert select_controllers(['elbow'], CONTROLLERS) is None


def test_a_controllers_part_of_a_trajectory():
    traj = JointTrajectory(joint_names=['j1', 'f1', 'j2'])
    traj.points = [
        JointTrajectoryPoint(positions=[1, 2, 3], velocities=[4, 5, 6]),
        JointTrajectoryPoint(positions=[7, 8, 9]),
    ]
    part = split(traj, ['j1', 'j2', 'j3'])
    assert part.joint_names == ['j1', 'j2']
    assert [list(p.positions) for p in part.points] == [[1, 3], [7, 9]]
    assert list(part.points[0].velocities) == [4, 6] and not part.points[1].velocities
