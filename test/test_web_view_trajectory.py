#!/usr/bin/env python
"""The browser view with gazebo.launch controllers:=trajectory: arm_controller's slider for
joint1, moved with the keyboard in headless Chromium, sends the one-point trajectory a user's
node would send on /arm1/arm_controller/command, and joint1 follows it."""

import os
import sys

import rospy
import rostest
from trajectory_msgs.msg import JointTrajectory

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import JOINTS, Recorder, WorldTestCase, positions, wait_for  # noqa: E402
from web_util import open_page, page_has_js  # noqa: E402

LOWER = -1.57  # joint1's lower limit: where the slider's Home key puts it
TOL = 0.05  # rad: arm_controller's goal tolerance (config/controllers_trajectory.yaml)


class WebViewTrajectory(WorldTestCase):
    NODE = 'test_web_view_trajectory'
    RECORD = ('states',)
    FIRST = ('states',)
    CONTROLLERS = 2  # joint_state_controller, arm_controller

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        assert wait_for(lambda: rospy.has_param('/gazebo/web_url'), 30), 'no ~web_url'
        cls.commands = Recorder('/arm1/arm_controller/command', JointTrajectory)
        cls.browser = open_page(rospy.get_param('/gazebo/web_url'), 'arm_controller')

    @classmethod
    def tearDownClass(cls):
        cls.browser.close()

    def test_a_trajectory_slider_moves_its_joint(self):
        sliders = self.browser.wait_js("document.querySelectorAll('[role=slider]').length", 30)
        self.assertEqual(sliders, 4, 'not one slider per arm_controller joint')
        held = positions(self.states.last())
        # the first slider is joint1's: Home puts it at its minimum, the joint's lower limit
        self.browser.js("document.querySelectorAll('[role=slider]')[0].focus()")
        self.browser.key('Home', 'Home', 36)
        self.assertTrue(wait_for(self.commands.last, 60), 'nothing on arm_controller/command')
        goal = self.commands.last()
        self.assertEqual(list(goal.joint_names), JOINTS)
        self.assertEqual(len(goal.points), 1)
        self.assertAlmostEqual(goal.points[0].positions[0], LOWER, places=6)
        self.assertEqual(goal.points[0].time_from_start, rospy.Duration(1.0))
        # the others asked to stay where they were (their sliders start at their positions)
        for j, v in zip(JOINTS[1:], goal.points[0].positions[1:]):
            self.assertAlmostEqual(v, held[j], delta=0.01, msg=j)

        def there():
            return abs(positions(self.states.last())['joint1'] - LOWER) < TOL

        self.assertTrue(wait_for(there, 60), 'joint1 did not follow its slider')
        shown = self.browser.wait_js(page_has_js('command %.3f' % LOWER), 60)
        self.assertTrue(shown, 'the page does not show the new command')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'web_view_trajectory', WebViewTrajectory)
