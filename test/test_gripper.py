#!/usr/bin/env python
"""A gripper with a mimic finger (test/config/gripper_bot.urdf) and a box between its fingers,
under a real master: a control_msgs/GripperCommand goal closes on the box and is aborted as
stalled; the mimic finger mirrors the leader in joint_states; opening reaches its goal. Beside
it, a mimic plugin's <hasPID> follower (test/config/pid_mimic.urdf) reaches its target under
the gains the launch sets."""

import os
import sys

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import GripperCommandAction, GripperCommandGoal
from gazebo_msgs.srv import GetJointProperties, SpawnModel
from geometry_msgs.msg import Pose

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, WorldTestCase, wait_for, wait_for_controllers  # noqa: E402
from sensor_msgs.msg import JointState  # noqa: E402

NS = '/gripper_bot'
LEAD, FOLLOW = 'left_finger_joint', 'right_finger_joint'
CONTACT = 0.04  # where the 4 cm box stops the left finger (m)


def by_name(msg):
    return dict(zip(msg.name, msg.position))


class Gripper(WorldTestCase):
    NODE = 'test_gripper'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.states = Recorder(NS + '/joint_states', JointState)
        cls.list_controllers = wait_for_controllers(2, NS)
        cls.client = actionlib.SimpleActionClient(
            NS + '/gripper_controller/gripper_cmd', GripperCommandAction
        )
        assert cls.client.wait_for_server(rospy.Duration(60)), 'no gripper_cmd action server'
        assert wait_for(lambda: cls.states.last() is not None, 60), 'no joint_states'
        # The box only now: spawned before the gripper it would fall past the gripper's base.
        rospy.wait_for_service('/gazebo/spawn_urdf_model', 60)
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        pose = Pose()
        pose.position.z, pose.orientation.w = 0.335, 1.0
        response = spawn(
            model_name='gripper_box',
            model_xml=rospy.get_param('/gripper_box/robot_description'),
            initial_pose=pose,
        )
        assert response.success, response.status_message

    def send(self, position, max_effort):
        goal = GripperCommandGoal()
        goal.command.position, goal.command.max_effort = position, max_effort
        self.client.send_goal(goal)
        self.assertTrue(self.client.wait_for_result(rospy.Duration(60)), 'no result in 60 s')
        return self.client.get_state(), self.client.get_result()

    def test_1_the_gripper_controller_claims_the_leader_only(self):
        (c,) = [c for c in self.list_controllers().controller if c.name == 'gripper_controller']
        self.assertEqual(c.type, 'effort_controllers/GripperActionController')
        self.assertEqual(
            [(r.hardware_interface, list(r.resources)) for r in c.claimed_resources],
            [('hardware_interface::EffortJointInterface', [LEAD])],
        )

    def test_2_closing_on_the_box_reports_stalled(self):
        state, result = self.send(0.06, 2.0)  # fully closed would be 0.05: the box is in the way
        self.assertEqual(state, GoalStatus.ABORTED)
        self.assertTrue(result.stalled)
        self.assertFalse(result.reached_goal)
        self.assertAlmostEqual(result.position, CONTACT, delta=0.004)
        self.assertAlmostEqual(result.effort, 2.0, delta=1e-6)  # pressing at max_effort

    def test_3_the_mimic_finger_mirrors_the_leader_in_joint_states(self):
        recent = self.states.last_sim_seconds(1.0)  # joint_states at 50 Hz of sim time
        self.assertGreater(len(recent), 10)
        for msg in recent:
            pos = by_name(msg)
            self.assertAlmostEqual(pos[FOLLOW], -pos[LEAD], delta=0.002)
        self.assertAlmostEqual(by_name(recent[-1])[LEAD], CONTACT, delta=0.004)

    def test_4_opening_reaches_the_goal_and_the_mimic_follows(self):
        state, result = self.send(0.01, 2.0)
        self.assertEqual(state, GoalStatus.SUCCEEDED)
        self.assertTrue(result.reached_goal)
        self.assertFalse(result.stalled)
        self.assertAlmostEqual(result.position, 0.01, delta=0.002)
        self.assertTrue(
            wait_for(lambda: abs(by_name(self.states.last())[FOLLOW] + 0.01) < 0.003, 10),
            'mimic finger at %.4f, not -0.01' % by_name(self.states.last())[FOLLOW],
        )

    def test_5_a_has_pid_follower_reaches_its_target_under_its_gains(self):
        # pid_follow: offset 0.3 from the free pid_lead (at 0); p 2, d 0.05 from the launch's
        # /pid_mimic/gazebo_ros_control/pid_gains/pid_follow (without them: zero gains, at 0)
        rospy.wait_for_service('/gazebo/get_joint_properties', 60)
        joint = rospy.ServiceProxy('/gazebo/get_joint_properties', GetJointProperties)

        def position(name):
            answer = joint(name)
            return answer.position[0] if answer.success else None

        self.assertTrue(wait_for(lambda: position('pid_follow') is not None, 60))
        rospy.sleep(2.0)  # sim time: the PID settles in well under a second
        self.assertAlmostEqual(position('pid_lead'), 0.0, delta=0.01)
        self.assertAlmostEqual(position('pid_follow'), 0.3, delta=0.01)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'gripper', Gripper)
