#!/usr/bin/env python
"""Pause stops /clock and the joints, unpause resumes, reset brings time and joints back to zero."""

import os
import sys
import time

import rospy
import rostest
from gazebo_msgs.srv import GetWorldProperties
from std_msgs.msg import Float64
from std_srvs.srv import Empty

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import JOINTS, WorldTestCase, positions, wait_for  # noqa: E402


def call(name):
    rospy.wait_for_service(name, 30)
    rospy.ServiceProxy(name, Empty)()


def sim_time():
    """The world's sim time in seconds (get_world_properties answers from its physics thread)."""
    rospy.wait_for_service('/gazebo/get_world_properties', 30)
    return rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)().sim_time


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
        mark = time.monotonic()
        call('/gazebo/pause_physics')
        paused_at = sim_time()  # the world's own time, read from its physics thread
        # Paused, physics stands still, so a wall second is the window: nothing may be
        # stamped after the pause. Messages still in flight (stamped before it) may arrive
        # late on a busy machine; they are told apart by their stamps, not by when they come.
        time.sleep(1.0)
        self.assertEqual(sim_time(), paused_at, 'the world stepped while paused')
        late = paused_at + 1e-6  # a float's rounding, far below a step (1 ms)
        self.assertEqual(
            [c.clock for c in self.clock.since(mark) if c.clock.to_sec() > late],
            [],
            '/clock moved while paused',
        )
        self.assertEqual(
            [m.header.stamp for m in self.states.since(mark) if m.header.stamp.to_sec() > late],
            [],
            'joint_states published while paused',
        )
        before = self.clock.last().clock
        call('/gazebo/unpause_physics')
        self.assertTrue(
            wait_for(lambda: (self.clock.last().clock - before).to_sec() > 0.5, 30),
            '/clock did not resume',
        )
        self.assertTrue(self.joint1_at(1.2), 'joint1 did not resume towards its target')

    def test_02_reset_simulation(self):
        self.pub.publish(1.0)
        self.assertTrue(self.joint1_at(1.0))
        # Past 1 s of sim time, so that the reset's time (under 0.5 s) tells: how far the
        # clock got during the tests before depends on how busy the machine is.
        self.assertTrue(
            wait_for(lambda: self.clock.last().clock.to_sec() > 1.0, 30), '/clock stalled'
        )
        mark = time.monotonic()
        call('/gazebo/reset_simulation')

        # Messages already in flight may carry the old time: take the first with the new one.
        def after():
            return [m for m in self.states.since(mark) if m.header.stamp.to_sec() < 0.5]

        self.assertTrue(wait_for(after, 30), 'no joint_states with the reset time')
        first = after()[0]
        for j in JOINTS:
            self.assertAlmostEqual(positions(first)[j], 0.0, delta=0.05, msg=j)
        self.assertTrue(
            wait_for(lambda: any(c.clock.to_sec() < 0.5 for c in self.clock.since(mark)), 30),
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
