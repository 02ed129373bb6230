#!/usr/bin/env python
"""simple_mover's sine (amplitude pi/2, 0.1 Hz) moves every joint through its clamped range."""

import math
import os
import sys
import time
import unittest

import rospy
import rostest
from std_msgs.msg import Float64

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import JOINTS, Recorder, joint_recorder, positions, wait_for  # noqa: E402

LIMITS = {
    'joint1': (-1.57, 1.57),
    'joint2': (0.01, 1.57),
    'joint3': (-1.0, 1.57),
    'joint4': (-0.8, 1.57),
}


class SimpleMover(unittest.TestCase):
    def test_every_joint_sweeps_its_range(self):
        rospy.init_node('test_simple_mover')
        states = joint_recorder()
        command = Recorder('/arm1/joint1_position_controller/command', Float64)
        self.assertTrue(wait_for(lambda: command.last() is not None, 60), 'simple_mover is silent')
        start = time.monotonic()
        # One period of the sine is 10 s of sim time; watch 12 s.
        self.assertTrue(wait_for(lambda: len(states.since(start)) >= 12 * 50, 120))
        msgs = states.since(start)
        cmds = [m.data for m in command.since(start)]
        self.assertGreater(max(cmds), 1.5)
        self.assertLess(min(cmds), -1.5)
        for j in JOINTS:
            pos = [positions(m)[j] for m in msgs]
            lo, hi = LIMITS[j]
            # Within the URDF limits (a little give for contact) ...
            self.assertGreaterEqual(min(pos), lo - 0.05, j)
            self.assertLessEqual(max(pos), hi + 0.05, j)
            # ... and up to the upper limit, which the sine (peak pi/2) exceeds for every joint.
            self.assertGreater(max(pos), hi - 0.05, '%s peaked at %.3f' % (j, max(pos)))
            self.assertGreater(
                max(pos) - min(pos),
                0.6 * (hi - lo),
                '%s swept only [%.3f, %.3f]' % (j, min(pos), max(pos)),
            )
            self.assertTrue(all(math.isfinite(p) for p in pos))


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_simple_mover', SimpleMover)
