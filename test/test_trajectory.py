#!/usr/bin/env python
"""The effort JointTrajectoryController on arm1 (gazebo.launch controllers:=trajectory): a
FollowJointTrajectory goal reaches its points and succeeds, bad goals are rejected with
upstream's codes, cancel holds the arm, and goals still work after reset_simulation."""

import math
import os
import subprocess
import sys
import time

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryGoal,
    FollowJointTrajectoryResult,
    JointTrajectoryControllerState,
)
from control_msgs.srv import QueryTrajectoryState
from std_srvs.srv import Empty
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import JOINTS, Recorder, WorldTestCase, positions, sim_wait, wait_for  # noqa: E402

ACTION = '/arm1/arm_controller/follow_joint_trajectory'
GOAL_TOL = 0.05  # config/controllers_trajectory.yaml's constraints/<joint>/goal


def make_goal(waypoints, joints=JOINTS):
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = list(joints)
    for t, pos in waypoints:
        point = JointTrajectoryPoint(positions=list(pos))
        point.time_from_start = rospy.Duration.from_sec(t)
        goal.trajectory.points.append(point)
    return goal


class Trajectory(WorldTestCase):
    NODE = 'test_trajectory'
    RECORD = ('states',)
    FIRST = ('states',)
    CONTROLLERS = 2

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.client = actionlib.SimpleActionClient(ACTION, FollowJointTrajectoryAction)
        assert cls.client.wait_for_server(rospy.Duration(60)), 'no action server ' + ACTION

    def run_goal(self, goal, timeout=60):
        self.client.send_goal(goal)
        self.assertTrue(self.client.wait_for_result(rospy.Duration(timeout)), 'no result')
        return self.client.get_state(), self.client.get_result()

    def now(self):
        return positions(self.states.last())

    def test_01_goal_reaches_its_points_and_succeeds(self):
        mid, end = [0.5, 0.7, 0.3, 0.2], [-0.4, 1.0, 0.1, -0.1]
        self.states.clear()
        state, result = self.run_goal(make_goal([(2.0, mid), (4.0, end)]))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.SUCCESSFUL)
        self.assertEqual(result.error_string, '')
        final = self.now()
        for j, target in zip(JOINTS, end):
            self.assertLess(
                abs(final[j] - target), GOAL_TOL, '%s at %.3f, not %.3f' % (j, final[j], target)
            )
        # the arm passed near the middle point on its way
        passes = [
            max(abs(positions(m)[j] - p) for j, p in zip(JOINTS, mid)) for m in self.states.since(0)
        ]
        self.assertLess(min(passes), 0.15, 'never within 0.15 rad of the middle point')

    def test_02_unknown_joint_returns_invalid_joints(self):
        goal = make_goal([(1.0, [0.0, 0.5, 0.0, 0.0])], ['joint1', 'joint2', 'joint3', 'elbow'])
        state, result = self.run_goal(goal, 30)
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.INVALID_JOINTS)
        self.assertIn("'elbow'", result.error_string)

    def test_03_nan_point_returns_invalid_goal_naming_the_joint(self):
        state, result = self.run_goal(make_goal([(1.0, [0.0, float('nan'), 0.0, 0.0])]), 30)
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.INVALID_GOAL)
        self.assertIn('joint2', result.error_string)

    def test_04_cancel_preempts_and_holds_the_arm(self):
        self.run_goal(make_goal([(1.0, [0.0, 1.0, 0.0, 0.0])]))
        self.client.send_goal(make_goal([(8.0, [1.2, 0.4, 0.8, 0.8])]))
        sim_wait(2.0)
        self.client.cancel_goal()
        self.assertTrue(self.client.wait_for_result(rospy.Duration(30)))
        self.assertEqual(self.client.get_state(), GoalStatus.PREEMPTED)
        sim_wait(1.0)
        held = self.now()
        self.assertGreater(held['joint1'], 0.1, 'the arm had not moved before the cancel')
        sim_wait(2.0)
        later = self.now()
        for j in JOINTS:
            self.assertLess(
                abs(later[j] - held[j]),
                0.05,
                '%s drifted from %.3f to %.3f' % (j, held[j], later[j]),
            )

    def test_05_state_topic_and_query_state(self):
        rec = Recorder('/arm1/arm_controller/state', JointTrajectoryControllerState)
        try:
            self.assertTrue(wait_for(lambda: rec.last() is not None, 30), 'no state message')
            msg = rec.last()
            self.assertEqual(list(msg.joint_names), JOINTS)
            self.assertEqual(len(msg.actual.positions), 4)
        finally:
            rec.sub.unregister()
        rospy.wait_for_service('/arm1/arm_controller/query_state', 30)
        query = rospy.ServiceProxy('/arm1/arm_controller/query_state', QueryTrajectoryState)
        out = query(rospy.Time.now())
        self.assertEqual(list(out.name), JOINTS)
        self.assertTrue(all(math.isfinite(p) for p in out.position))

    def test_06_goals_still_succeed_after_reset_simulation(self):
        rospy.wait_for_service('/gazebo/reset_simulation', 30)
        rospy.ServiceProxy('/gazebo/reset_simulation', Empty)()
        sim_wait(0.5)
        state, result = self.run_goal(make_goal([(2.0, [0.3, 0.8, 0.2, 0.1])]))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result)
        self.assertLess(abs(self.now()['joint1'] - 0.3), GOAL_TOL)

    def test_07_paused_goal_waits_then_runs_on_unpause(self):
        self.run_goal(make_goal([(1.0, [0.0, 1.0, 0.0, 0.0])]))
        call = rospy.ServiceProxy
        call('/gazebo/pause_physics', Empty)()
        try:
            self.client.send_goal(make_goal([(1.5, [0.4, 1.0, 0.0, 0.0])]))
            self.assertTrue(
                wait_for(lambda: self.client.get_state() == GoalStatus.ACTIVE, 10),
                'goal not accepted while paused',
            )
            time.sleep(1.0)  # wall time: sim time stands still
            self.assertEqual(self.client.get_state(), GoalStatus.ACTIVE)
            self.assertLess(abs(self.now()['joint1']), 0.05, 'the arm moved while paused')
        finally:
            call('/gazebo/unpause_physics', Empty)()
        self.assertTrue(self.client.wait_for_result(rospy.Duration(30)))
        self.assertEqual(self.client.get_state(), GoalStatus.SUCCEEDED)
        self.assertLess(abs(self.now()['joint1'] - 0.4), GOAL_TOL)

    def test_08_command_topic_moves_the_arm(self):
        pub = rospy.Publisher(
            '/arm1/arm_controller/command', JointTrajectory, queue_size=1, latch=True
        )
        msg = make_goal([(1.5, [-0.3, 0.9, 0.2, 0.1])]).trajectory
        pub.publish(msg)
        self.assertTrue(
            wait_for(lambda: abs(self.now()['joint1'] + 0.3) < GOAL_TOL, 30),
            'joint1 at %.3f, not -0.3' % self.now()['joint1'],
        )
        pub.unregister()

    def test_09_trajectory_demo_prints_a_successful_result(self):
        out = subprocess.run(
            ['rosrun', 'arm1', 'trajectory_demo'],
            timeout=120,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        self.assertEqual(out.returncode, 0, out.stdout)
        self.assertIn('SUCCEEDED', out.stdout)
        self.assertIn('SUCCESSFUL', out.stdout)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'trajectory', Trajectory)
