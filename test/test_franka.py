#!/usr/bin/env python
"""franka_gazebo's FrankaHWSim under a real master (arm1_franka.test, a generated Panda-like
arm): the controller spawner got 'initialized', franka_state_controller publishes
franka_msgs/FrankaState agreeing with its joint_states, the effort trajectory controller
completes a FollowJointTrajectory goal, the gripper closes on franka_gripper/move and
control_msgs/GripperCommand goals, and franka_ros's C++ example controllers are refused by
name."""

import os
import sys

import actionlib
import numpy as np
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryGoal,
    GripperCommandAction,
    GripperCommandGoal,
)
from controller_manager_msgs.srv import LoadController
from franka_gripper.msg import MoveAction, MoveGoal
from franka_msgs.msg import FrankaState
from sensor_msgs.msg import JointState
from std_msgs.msg import Bool
from trajectory_msgs.msg import JointTrajectoryPoint

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, WorldTestCase, wait_for, wait_for_controllers  # noqa: E402

ARM = ['toy_joint%d' % i for i in range(1, 8)]
START = [0.0, -0.785398163, 0.0, -2.35619449, 0.0, 1.57079632679, 0.785398163397]
GOAL = [0.3, -0.5, 0.2, -2.0, 0.2, 1.8, 0.5]


class Franka(WorldTestCase):
    NODE = 'test_franka'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.states = Recorder('/franka_state_controller/franka_states', FrankaState)
        cls.joints = Recorder('/franka_state_controller/joint_states', JointState)
        cls.fingers = Recorder('/franka_gripper/joint_states', JointState)
        cls.initialized = Recorder('/initialized', Bool)
        cls.list_controllers = wait_for_controllers(3, '')
        assert wait_for(lambda: cls.states.last() is not None, 60), 'no franka_states'

    def test_1_initialized_and_the_state_agrees_with_joint_states(self):
        self.assertTrue(wait_for(lambda: self.initialized.last() is not None, 10))
        self.assertTrue(self.initialized.last().data)
        self.assertTrue(wait_for(lambda: self.joints.last() is not None, 10))
        state, joints = self.states.last(), self.joints.last()
        # Published together at each trigger: the same instant, the same q.
        pairs = [
            (s, j)
            for s in self.states.since(0)[-10:]
            for j in self.joints.since(0)[-10:]
            if s.header.stamp == j.header.stamp
        ]
        self.assertTrue(pairs, 'no franka_states and joint_states of one stamp')
        s, j = pairs[-1]
        self.assertEqual(list(j.name), ARM)
        np.testing.assert_allclose(s.q, j.position, atol=1e-12)
        np.testing.assert_allclose(s.tau_J, j.effort, atol=1e-12)
        self.assertEqual(state.robot_mode, FrankaState.ROBOT_MODE_MOVE)
        # Where the spawner put it, held by gravity compensation and the trajectory controller
        np.testing.assert_allclose(joints.position, START, atol=0.05)
        o_t_ee = np.array(state.O_T_EE).reshape(4, 4).T
        np.testing.assert_allclose(o_t_ee[:3, :3] @ o_t_ee[:3, :3].T, np.eye(3), atol=1e-6)
        self.assertAlmostEqual(state.m_ee, 0.76)
        self.assertAlmostEqual(state.O_ddP_O[2], -9.81)

    def test_2_trajectory_goal_completes(self):
        client = actionlib.SimpleActionClient(
            '/effort_joint_trajectory_controller/follow_joint_trajectory',
            FollowJointTrajectoryAction,
        )
        self.assertTrue(client.wait_for_server(rospy.Duration(30)))
        goal = FollowJointTrajectoryGoal()
        goal.trajectory.joint_names = ARM
        point = JointTrajectoryPoint(positions=GOAL, velocities=[0.0] * 7)
        point.time_from_start = rospy.Duration(2.0)
        goal.trajectory.points = [point]
        client.send_goal(goal)
        self.assertTrue(client.wait_for_result(rospy.Duration(60)), 'no result in 60 s')
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED, client.get_goal_status_text())
        self.assertEqual(client.get_result().error_code, 0)
        np.testing.assert_allclose(self.joints.last().position, GOAL, atol=0.05)

    def test_3_gripper_closes_on_move_and_gripper_command(self):
        move = actionlib.SimpleActionClient('/franka_gripper/move', MoveAction)
        self.assertTrue(move.wait_for_server(rospy.Duration(30)))
        move.send_goal(MoveGoal(width=0.06, speed=0.1))
        self.assertTrue(move.wait_for_result(rospy.Duration(30)))
        self.assertTrue(move.get_result().success, move.get_result().error)
        self.assertAlmostEqual(sum(self.fingers.last().position), 0.06, delta=0.004)
        grip = actionlib.SimpleActionClient('/franka_gripper/gripper_action', GripperCommandAction)
        self.assertTrue(grip.wait_for_server(rospy.Duration(30)))
        goal = GripperCommandGoal()
        goal.command.position, goal.command.max_effort = 0.01, 0.0  # each finger: 1 cm
        grip.send_goal(goal)
        self.assertTrue(grip.wait_for_result(rospy.Duration(30)))
        self.assertEqual(grip.get_state(), GoalStatus.SUCCEEDED)
        self.assertTrue(grip.get_result().reached_goal)
        self.assertAlmostEqual(sum(self.fingers.last().position), 0.02, delta=0.004)

    def test_4_cpp_example_controller_is_refused_by_name(self):
        load = rospy.ServiceProxy('/controller_manager/load_controller', LoadController)
        self.assertFalse(load('cartesian_impedance_example_controller').ok)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'franka', Franka)
