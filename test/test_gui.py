#!/usr/bin/env python
"""gui:=true for real: under Xvfb, start the world with pybullet's window and look at the screen."""

import os
import sys
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import JointState

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_util import SCREEN, Display, colours, orange  # noqa: E402


class Gui(unittest.TestCase):
    def setUp(self):
        self.display = Display()

    def tearDown(self):
        self.display.close()

    def test_the_arm_is_in_the_pybullet_window(self):
        rospy.init_node('test_gui')
        self.assertEqual(colours(self.display.screen()), 1)  # a blank screen to begin with
        self.display.roslaunch('arm1', 'gazebo.launch', 'gui:=true')
        rospy.wait_for_message('/arm1/joint_states', JointState, 90)
        rospy.sleep(2.0)  # a few frames drawn
        rgb = self.display.screen()
        shot = self.display.save(rgb, 'arm1_gui_screenshot.png')
        print('screenshot: %s' % shot)
        self.assertGreater(colours(rgb), 50, 'the screen is (nearly) one colour (%s)' % shot)
        arm = orange(rgb)
        self.assertGreater(arm.sum(), 300, 'no orange link of the arm on the screen (%s)' % shot)
        # the window's default view looks at the arm: it is near the middle
        ys, xs = np.nonzero(arm)
        self.assertTrue(0.2 < xs.mean() / SCREEN[0] < 0.8, xs.mean())
        self.assertTrue(0.2 < ys.mean() / SCREEN[1] < 0.8, ys.mean())


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_gui', Gui)
