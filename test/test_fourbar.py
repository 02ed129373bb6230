#!/usr/bin/env python
"""A four-bar gripper with Robotiq 2F-85's kinematics (test/config/fourbar_gripper.urdf: one
driven knuckle, five followers declared by a URDF <mimic> and roboticsgroup's plugin, two of
them below a moving knuckle) closes on a box, lifts it and opens, each FollowJointTrajectory
goal SUCCEEDED; the followers keep the parallelogram and the leader never runs away."""

import os
import sys
import time

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal
from gazebo_msgs.srv import GetJointProperties, GetModelState
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import (  # noqa: E402
    Recorder,
    WorldTestCase,
    sim_wait,
    spawn_urdf,
    wait_for,
    wait_for_controllers,
)

NS = '/fourbar'
FOLLOWERS = [
    'left_inner_finger_joint',
    'left_inner_knuckle_joint',
    'right_outer_knuckle_joint',
    'right_inner_finger_joint',
    'right_inner_knuckle_joint',
]
CONTACT = 0.353  # drive_joint where the 5 cm box stops the pads (rad)
CLOSE = 0.40  # the close goal: past the contact, so the controller squeezes (p 10: 0.47 N m)
BOX = """<robot name="fourbar_box"><link name="box">
  <inertial><mass value="0.1"/><inertia ixx="4e-5" ixy="0" ixz="0" iyy="4e-5" iyz="0" izz="4e-5"/>
  </inertial>
  <visual><geometry><box size="0.05 0.05 0.05"/></geometry></visual>
  <collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>
  <gazebo reference="box"><mu1>1.0</mu1><mu2>1.0</mu2></gazebo>
</robot>"""


def by_name(msg, field='position'):
    return dict(zip(msg.name, getattr(msg, field)))


class FourBar(WorldTestCase):
    NODE = 'test_fourbar'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.states = Recorder(NS + '/joint_states', JointState)
        wait_for_controllers(3, NS)
        cls.gripper = actionlib.SimpleActionClient(
            NS + '/gripper_controller/follow_joint_trajectory', FollowJointTrajectoryAction
        )
        cls.lift = actionlib.SimpleActionClient(
            NS + '/lift_controller/follow_joint_trajectory', FollowJointTrajectoryAction
        )
        for client in (cls.gripper, cls.lift):
            assert client.wait_for_server(rospy.Duration(60)), 'no action server'
        assert wait_for(lambda: cls.states.last() is not None, 60), 'no joint_states'
        rospy.wait_for_service('/gazebo/get_joint_properties', 60)
        cls.joint = rospy.ServiceProxy('/gazebo/get_joint_properties', GetJointProperties)
        cls.model = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)

    def test_0_opens(self):
        """Opened first: until its controller started, the free knuckles swung half shut under
        their own weight (0.47 rad), where a box spawned now would sit inside the pads."""
        state, code, text = self.send(self.gripper, 'drive_joint', 0.0, 0.5)
        self.assertEqual(state, GoalStatus.SUCCEEDED, '%d %s' % (code, text))
        self.assert_followers_mimic()
        # Spawned now, on the ground between the open pads (they reach 7 mm above it).
        spawn_urdf('fourbar_box', BOX, '', (0, 0, 0.026))
        sim_wait(0.5)

    def send(self, client, joint, position, seconds):
        goal = FollowJointTrajectoryGoal()
        goal.trajectory.joint_names = [joint]
        goal.trajectory.points = [
            JointTrajectoryPoint(positions=[position], time_from_start=rospy.Duration(seconds))
        ]
        client.send_goal(goal)
        self.assertTrue(client.wait_for_result(rospy.Duration(60)), 'no result in 60 s')
        result = client.get_result()
        return client.get_state(), result.error_code, result.error_string

    def box_z(self):
        return self.model('fourbar_box', 'world').pose.position.z

    def drive(self):
        msg = self.states.last()
        return by_name(msg)['drive_joint'], by_name(msg, 'velocity')['drive_joint']

    def assert_followers_mimic(self):
        lead = self.joint('drive_joint').position[0]
        for name in FOLLOWERS:
            self.assertAlmostEqual(
                self.joint(name).position[0], lead, delta=0.01, msg='%s vs %.3f' % (name, lead)
            )

    def assert_leader_calm(self, seconds):
        """The leader's speed in the last ``seconds`` of sim time stays a gripper's."""
        for msg in self.states.last_sim_seconds(seconds):
            self.assertLess(abs(by_name(msg, 'velocity')['drive_joint']), 3.0)

    def test_1_closes_on_the_box_lifts_it_and_opens(self):
        start = time.monotonic()
        state, code, text = self.send(self.gripper, 'drive_joint', CLOSE, 1.0)
        self.assertEqual(state, GoalStatus.SUCCEEDED, '%d %s' % (code, text))
        sim_wait(0.5)
        position, velocity = self.drive()
        self.assertAlmostEqual(position, CONTACT, delta=0.01)  # held by the box
        self.assertLess(abs(velocity), 0.05)
        self.assert_followers_mimic()
        self.assert_leader_calm(1.5)

        state, code, text = self.send(self.lift, 'lift_joint', 0.1, 1.5)
        self.assertEqual(state, GoalStatus.SUCCEEDED, '%d %s' % (code, text))
        sim_wait(1.0)
        self.lifted, self.held = self.box_z(), self.drive()[0]
        self.assertAlmostEqual(self.lifted, 0.126, delta=0.01)  # lifted with the gripper
        self.assertAlmostEqual(self.held, CONTACT, delta=0.01)
        self.assert_followers_mimic()
        self.assert_leader_calm(2.5)

        state, code, text = self.send(self.gripper, 'drive_joint', 0.0, 1.0)
        self.assertEqual(state, GoalStatus.SUCCEEDED, '%d %s' % (code, text))
        self.assertTrue(wait_for(lambda: self.box_z() < 0.03, 20), 'the box was not let go')
        self.assert_followers_mimic()
        self.assert_leader_calm(1.5)
        fastest = max(abs(by_name(m, 'velocity')['drive_joint']) for m in self.states.since(start))
        print(
            'fourbar: held at drive_joint %.4f, box lifted to %.4f m, leader at most %.2f rad/s'
            % (self.held, self.lifted, fastest)
        )


if __name__ == '__main__':
    rostest.rosrun('arm1', 'fourbar', FourBar)
