#!/usr/bin/env python
"""Gazebo's grasp plugin under a real master: gripper_bot (test/config/gripper_bot.urdf) with
libgazebo_grasp_fix.so closes on a box; the attach and the detach when it opens are published
as gazebo_grasp_plugin_ros/GazeboGraspEvent on /gazebo/grasp_events."""

import os
import sys

import actionlib
import rospy
import rostest
from control_msgs.msg import GripperCommandAction, GripperCommandGoal
from gazebo_grasp_plugin_ros.msg import GazeboGraspEvent

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import (  # noqa: E402
    Recorder,
    SpawningTestCase,
    spawn_urdf,
    wait_for,
    wait_for_controllers,
)

NS = '/gripper_bot'
BOX = 'gripper_box::box::box_collision'
# 10 Hz, attached after 3 updates of a grip, let go 2 updates after it ends
PLUGIN = """<gazebo><plugin name="gazebo_grasp_fix" filename="libgazebo_grasp_fix.so">
  <arm><arm_name>gripper</arm_name><palm_link>base</palm_link>
    <gripper_link>left_finger</gripper_link><gripper_link>right_finger</gripper_link></arm>
  <update_rate>10</update_rate><grip_count_threshold>2</grip_count_threshold>
  <max_grip_count>4</max_grip_count><release_tolerance>0.005</release_tolerance>
</plugin></gazebo></robot>"""


class Grasp(SpawningTestCase):
    NODE = 'test_grasp'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.events = Recorder('/gazebo/grasp_events', GazeboGraspEvent)
        urdf = rospy.get_param(NS + '/robot_description').replace('</robot>', PLUGIN)
        spawn_urdf('gripper_bot', urdf, '', (0, 0, 0))
        wait_for_controllers(2, NS)
        cls.client = actionlib.SimpleActionClient(
            NS + '/gripper_controller/gripper_cmd', GripperCommandAction
        )
        assert cls.client.wait_for_server(rospy.Duration(60)), 'no gripper_cmd action server'
        # between the open fingers, on the gripper's base
        spawn_urdf(
            'gripper_box', rospy.get_param('/gripper_box/robot_description'), '', (0, 0, 0.335)
        )

    def send(self, position):
        goal = GripperCommandGoal()
        goal.command.position, goal.command.max_effort = position, 2.0
        self.client.send_goal(goal)
        self.assertTrue(self.client.wait_for_result(rospy.Duration(60)), 'no result in 60 s')

    def seen(self):
        return [(e.arm, e.object, e.attached) for e in self.events.since(0)]

    def test_1_closing_on_the_box_attaches_it(self):
        self.assertEqual(self.seen(), [])
        self.send(0.06)  # stalls on the box and keeps pressing
        self.assertTrue(wait_for(lambda: self.seen(), 60), 'no grasp event')
        self.assertEqual(self.seen(), [('gripper', BOX, True)])

    def test_2_opening_lets_it_go(self):
        self.send(0.0)
        self.assertTrue(wait_for(lambda: len(self.seen()) > 1, 60), 'no detach event')
        self.assertEqual(self.seen(), [('gripper', BOX, True), ('gripper', BOX, False)])


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_grasp', Grasp)
