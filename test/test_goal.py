#!/usr/bin/env python
"""The seed's goal through robot_spawn.launch: the camera publishes, `rosservice call
/arm_mover/safe_move` moves the arm and returns, and look_away turns it away from a blank view."""

import os
import struct
import subprocess
import sys
import tempfile
import time

import rostest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import LOOK, UP, ImageRecorder, JointCommander, uniform  # noqa: E402
from rostest_util import WorldTestCase, sim_wait, wait_for  # noqa: E402


def rosservice_call(*pose):
    req = '{joint1: %g, joint2: %g, joint3: %g, joint4: %g}' % pose
    return subprocess.run(
        ['rosservice', 'call', '/arm_mover/safe_move', req],
        timeout=60,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )


class Goal(WorldTestCase):
    NODE = 'test_goal'
    RECORD = ('states', 'rosout')
    SERVICES = ('/arm_mover/safe_move',)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.arm = JointCommander(cls.states)

    def test_01_the_camera_publishes(self):
        images = ImageRecorder()
        try:
            self.assertTrue(wait_for(lambda: images.meta, 30), 'no image on /rgb_camera/image_raw')
            self.assertEqual(images.meta[0][1:4], (640, 480, 'rgb8'))
        finally:
            images.close()
        # and a user can look at it on a headless machine
        path = os.path.join(tempfile.mkdtemp(prefix='arm1-goal-'), 'view.png')
        out = subprocess.run(
            ['rosrun', 'arm1', 'camera_snapshot', path],
            timeout=60,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        self.assertEqual(out.returncode, 0, out.stdout)
        with open(path, 'rb') as f:
            head = f.read(24)
        self.assertEqual(head[:8], b'\x89PNG\r\n\x1a\n')
        self.assertEqual(struct.unpack('>II', head[16:24]), (640, 480))

    def test_02_safe_move_moves_and_returns(self):
        out = rosservice_call(0.4, 0.6, -0.4, -0.4)
        self.assertEqual(out.returncode, 0, out.stdout)
        self.assertIn('time_elapsed', out.stdout)
        self.assertIsNotNone(self.arm.wait_at((0.4, 0.6, -0.4, -0.4), 0.05, 0), 'not there')
        # the horizon is in view: look_away leaves the arm alone
        sim_wait(2.0)
        self.assertIsNotNone(self.arm.wait_at((0.4, 0.6, -0.4, -0.4), 0.05, 0), 'it moved')

    def test_03_look_away_turns_the_arm_from_a_blank_view(self):
        start = time.monotonic()
        out = rosservice_call(*UP)  # camera to the sky
        self.assertEqual(out.returncode, 0, out.stdout)
        at = self.arm.wait_at(LOOK, 0.05, 30)
        self.assertIsNotNone(at, 'look_away did not turn the arm to %s' % (LOOK,))
        self.assertTrue(
            any(m.name == '/look_away' and 'safe_move' in m.msg for m in self.rosout.since(start)),
            'look_away said nothing',
        )
        images = ImageRecorder()
        try:
            view = images.frame_after(at)
            self.assertIsNotNone(view, 'no frame')
            self.assertFalse(uniform(view), 'still a blank view')
        finally:
            images.close()


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_goal', Goal)
