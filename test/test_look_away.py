#!/usr/bin/env python
"""look_away alone, against stand-ins of arm_mover, the camera and joint_states: when it moves."""

import threading
import time
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import Image, JointState

from arm1.srv import GoToPosition, GoToPositionResponse

POSE = [0.1, 0.2, 0.3, 0.4]  # ~pose in the launch file
RETRY_AFTER = 1.0  # s (ROS time, the wall's here) look_away waits after a failed safe_move
W, H = 64, 48


def image(uniform):
    px = np.full((H, W, 3), 255, np.uint8)
    if not uniform:
        px[H // 2 :] = (191, 191, 191)  # ground below the horizon
    msg = Image(height=H, width=W, encoding='rgb8', step=W * 3, data=px.tobytes())
    msg.header.stamp = rospy.Time.now()
    return msg


class World:
    """Publishes joint_states (50 Hz) and images (15 Hz), and serves /arm_mover/safe_move."""

    def __init__(self):
        self.uniform = False
        self.moving = False
        self.delay = 0.0  # how long a safe_move takes
        self.fail = False
        self.lock = threading.Lock()
        self.calls = []  # (wall start, wall end, request)
        self.active = 0
        self.max_active = 0
        self.service = rospy.Service('/arm_mover/safe_move', GoToPosition, self._safe_move)
        self.states = rospy.Publisher('/arm1/joint_states', JointState, queue_size=10)
        self.images = rospy.Publisher('/rgb_camera/image_raw', Image, queue_size=2)
        threading.Thread(target=self._run, daemon=True).start()

    def _safe_move(self, req):
        with self.lock:
            self.active += 1
            self.max_active = max(self.max_active, self.active)
        start = time.monotonic()
        time.sleep(self.delay)
        with self.lock:
            self.active -= 1
            self.calls.append((start, time.monotonic(), req))
        if self.fail:
            raise rospy.ServiceException('joint2 did not arrive')
        return GoToPositionResponse(rospy.Duration.from_sec(self.delay))

    def _run(self):
        n = 0
        while not rospy.is_shutdown():
            n += 1
            pos = [0.0, 1.57 + (0.001 * (n % 2) if self.moving else 0.0), 0.0, 0.0]
            msg = JointState(name=['joint1', 'joint2', 'joint3', 'joint4'], position=pos)
            msg.header.stamp = rospy.Time.now()
            self.states.publish(msg)
            if n % 3 == 0:
                self.images.publish(image(self.uniform))
            time.sleep(0.02)

    def calls_during(self, seconds):
        with self.lock:
            self.calls = []
        time.sleep(seconds)
        with self.lock:
            return list(self.calls)


class LookAway(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_look_away')
        cls.world = World()
        deadline = time.monotonic() + 30
        while cls.world.images.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.1)
        assert cls.world.images.get_num_connections(), 'look_away does not subscribe to images'

    def setUp(self):
        w = self.world
        w.uniform, w.moving, w.fail = False, False, False
        deadline = time.monotonic() + 10
        while w.active and time.monotonic() < deadline:  # a call of the test before
            time.sleep(0.05)
        w.delay = 0.0
        time.sleep(0.3)
        with w.lock:
            w.calls = []

    def test_uniform_view_and_still_arm_looks_away(self):
        self.world.uniform = True
        deadline = time.monotonic() + 5
        while not self.world.calls and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertTrue(self.world.calls, 'no safe_move call')
        req = self.world.calls[0][2]
        self.assertEqual([req.joint1, req.joint2, req.joint3, req.joint4], POSE)

    def test_structure_in_view_does_not_look_away(self):
        self.assertEqual(self.world.calls_during(2.0), [])

    def test_a_moving_arm_does_not_look_away(self):
        self.world.moving = True
        self.world.uniform = True
        self.assertEqual(self.world.calls_during(2.0), [])

    def test_one_call_at_a_time(self):
        self.world.delay = 1.0
        self.world.uniform = True
        calls = self.world.calls_during(3.5)
        self.assertGreaterEqual(len(calls), 2)  # the view stays blank: it tries again ...
        self.assertEqual(self.world.max_active, 1)  # ... but never while a call runs
        for (_, end, _), (start, _, _) in zip(calls, calls[1:]):
            self.assertGreaterEqual(start, end)

    def test_a_failed_move_is_retried_later(self):
        self.world.fail = True
        self.world.uniform = True
        calls = self.world.calls_during(2.5)
        # The promise is the wait between a failure and the next try, judged on each pair of
        # calls (a busy machine only makes it longer); 2.5 s leaves 1.4 s for the next image
        # and the call to arrive, so only a retry that never comes fails the count.
        self.assertGreaterEqual(len(calls), 2, 'no retry in 2.5 s')
        for (_, end, _), (start, _, _) in zip(calls, calls[1:]):
            wait = start - end
            self.assertGreaterEqual(wait, RETRY_AFTER, 'retried %.3f s after' % wait)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_look_away', LookAway)
