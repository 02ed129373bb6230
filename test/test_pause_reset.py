#!/usr/bin/env python
"""Pause stops /clock and the joints, unpause resumes, reset brings time and joints back to zero."""

import os
import sys
import time

import rospy
import rostest
from std_msgs.msg import Float64
from std_srvs.srv import Empty

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import JOINTS, WorldTestCase, positions, wait_for  # noqa: E402


def call(name):
    rospy.wait_for_service(name, 30)
    rospy.ServiceProxy(name, Empty)()


class PauseReset(WorldTestCase):
    NODE = 'test_pause_reset'
    RECORD = ('clock', 'states')
    CONTROLLERS = 5

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.pub = rospy.Publisher(
            '/arm1/joint1_position_controller/command', Float64, queue_size=1, latch=True
        )

    def joint1_at(self, target, tol=0.03, timeout=30):
        return wait_for(
            lambda: (
                self.states.last() is not None
                and abs(positions(self.states.last())['joint1'] - target) < tol
            ),
            timeout,
        )

    def test_01_pause_and_unpause(self):
        self.pub.publish(1.2)
        wait_for(lambda: False, 0.2)
        call('/gazebo/pause_physics')
        time.sleep(0.3)  # let messages in flight arrive
        mark = time.monotonic()
        before = self.clock.last().clock
        joints_before = positions(self.states.last())
        time.sleep(1.0)
        self.assertEqual(self.clock.last().clock, before, '/clock moved while paused')
        self.assertEqual(self.states.since(mark), [], 'joint_states published while paused')
        self.assertEqual(positions(self.states.last()), joints_before)
        call('/gazebo/unpause_physics')
        self.assertTrue(
            wait_for(lambda: (self.clock.last().clock - before).to_sec() > 0.5, 10),
            '/clock did not resume',
        )
        self.assertTrue(self.joint1_at(1.2), 'joint1 did not resume towards its target')

    def test_02_reset_simulation(self):
        self.pub.publish(1.0)
        self.assertTrue(self.joint1_at(1.0))
        self.assertGreater(self.clock.last().clock.to_sec(), 1.0)
        mark = time.monotonic()
        call('/gazebo/reset_simulation')

        # Messages already in flight may carry the old time: take the first with the new one.
        def after():
            return [m for m in self.states.since(mark) if m.header.stamp.to_sec() < 0.5]

        self.assertTrue(wait_for(after, 5), 'no joint_states with the reset time')
        first = after()[0]
        for j in JOINTS:
            self.assertAlmostEqual(positions(first)[j], 0.0, delta=0.05, msg=j)
        self.assertTrue(
            wait_for(lambda: any(c.clock.to_sec() < 0.5 for c in self.clock.since(mark)), 5),
            '/clock was not reset',
        )

    def test_03_reset_world_keeps_time(self):
        self.pub.publish(-1.0)
        self.assertTrue(self.joint1_at(-1.0))
        # Paused, so that every joint_states from before the reset has arrived.
        call('/gazebo/pause_physics')
        stamps = []

        def settled():  # every joint_states from before the pause has arrived (slow machines)
            stamps.append(self.states.last().header.stamp)
            return len(stamps) > 3 and stamps[-1] == stamps[-4]

        self.assertTrue(wait_for(settled, 10, poll=0.1), 'joint_states went on while paused')
        before = stamps[-1]
        mark = time.monotonic()
        call('/gazebo/reset_world')
        call('/gazebo/unpause_physics')

        def after():
            return [m for m in self.states.since(mark) if m.header.stamp > before]

        self.assertTrue(wait_for(after, 10), 'no joint_states after reset_world')
        first = after()[0]
        # Time goes on from where it stopped: one joint_states period (20 ms) later, not 0.
        self.assertLess((first.header.stamp - before).to_sec(), 0.1, 'reset_world reset time')
        self.assertEqual(
            [m.header.stamp for m in self.states.since(mark) if m.header.stamp < before],
            [],
            'joint_states went back in time after reset_world',
        )
        # At zero angles link4 touches the ground plane, so the arm is kicked within the
        # 20 ms before joint_states go out: it is far from where it was, not exactly at zero.
        self.assertGreater(positions(first)['joint1'] - (-1.0), 0.5, positions(first))


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_pause_reset', PauseReset)
