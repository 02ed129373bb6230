#!/usr/bin/env python
"""display.launch for real: under Xvfb, RViz shows arm1's model."""

import os
import sys
import unittest

import numpy as np
import rosgraph
import rospy
import rostest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_util import SCREEN, Display, colours, orange  # noqa: E402
from rostest_util import wait_for  # noqa: E402


class DisplayGui(unittest.TestCase):
    def setUp(self):
        self.display = Display()

    def tearDown(self):
        self.display.close()

    def test_rviz_shows_the_robot_model(self):
        rospy.init_node('test_display_gui')
        self.display.roslaunch('arm1', 'display.launch', 'gui:=false')
        master = rosgraph.Master('/test_display_gui')
        self.assertTrue(
            wait_for(
                lambda: any(
                    '/rviz' in nodes
                    for topic, nodes in master.getSystemState()[1]
                    if topic == '/tf'
                ),
                60,
            ),
            'RViz did not subscribe to /tf',
        )

        last = []

        def arm_drawn_and_settled():
            # RViz draws the model before its layout settles (panels still moving the 3D
            # view): judge a screenshot only once the arm looks the same in two in a row.
            rgb = self.display.screen()
            mask = orange(rgb)
            seen = (int(mask.sum()), float(np.nonzero(mask)[1].mean()) if mask.any() else 0.0)
            previous = last[1] if last else (0, 0.0)
            last[:] = [rgb, seen]
            return (
                seen[0] > 300
                and abs(seen[0] - previous[0]) <= 0.02 * seen[0]
                and abs(seen[1] - previous[1]) <= 5
            )

        # wall time: RViz draws in software GL, slow on a loaded machine (no sim time to go by)
        drawn = wait_for(arm_drawn_and_settled, 120, poll=1.0)
        rgb = last[0]
        shot = self.display.save(rgb, 'arm1_rviz_screenshot.png')
        print('screenshot: %s' % shot)
        self.assertTrue(drawn, 'no orange link of the arm in RViz (%s)' % shot)
        self.assertGreater(colours(rgb), 50)
        # in RViz's 3D view, right of the Displays panel
        xs = np.nonzero(orange(rgb))[1]
        self.assertGreater(xs.mean() / SCREEN[0], 0.4)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_display_gui', DisplayGui)
