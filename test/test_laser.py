#!/usr/bin/env python
"""A hokuyo-like gpu_ray laser (test/config/laser_mast.urdf, rrbot's sensor block) 1.9 m in front
of a wall, under a real master: /ns/laser/scan comes at its 40 Hz of sim time, stamped in sim
time, framed as gazebo_ros_gpu_laser frames it, with the centre ranges at the wall's distance
within the noise and +inf where the rays pass the wall; it stops when nobody listens and its
first scan after a new subscription is a fresh one."""

import math
import os
import sys
import time

import rospy
import rostest
from sensor_msgs.msg import LaserScan

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, WorldTestCase, sim_wait, wait_for  # noqa: E402

TOPIC = '/ns/laser/scan'
FACE = 1.9  # the wall's face, from the sensor at the origin
HALF_WIDTH = 10.0  # the wall's half width


class Laser(WorldTestCase):
    NODE = 'test_laser'
    RECORD = ('clock',)
    FIRST = ('clock',)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.scans = Recorder(TOPIC, LaserScan)
        assert wait_for(lambda: cls.scans.last() is not None, 90), 'no scan on ' + TOPIC

    def test_01_rate_in_sim_time(self):
        self.scans.clear()
        sim_wait(2.0)
        stamps = [m.header.stamp.to_sec() for m in self.scans.since(0)]
        self.assertGreater(len(stamps), 20)
        rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        self.assertAlmostEqual(rate, 40.0, delta=2.0)  # 40 Hz +- 5 %
        gaps = [b - a for a, b in zip(stamps, stamps[1:])]
        self.assertTrue(all(abs(g - 0.025) < 1e-6 for g in gaps), gaps[:10])

    def test_02_message_fields_as_upstream(self):
        msg = self.scans.last()
        self.assertEqual(msg.header.frame_id, 'ns/hokuyo_link')  # tf_prefix = robotNamespace
        self.assertAlmostEqual(msg.angle_min, -1.570796, places=5)
        self.assertAlmostEqual(msg.angle_max, 1.570796, places=5)
        self.assertAlmostEqual(msg.angle_increment, 2 * 1.570796 / 719, places=7)
        self.assertEqual((msg.time_increment, msg.scan_time), (0.0, 0.0))
        self.assertAlmostEqual(msg.range_min, 0.1, places=6)
        self.assertAlmostEqual(msg.range_max, 30.0, places=5)
        self.assertEqual(len(msg.ranges), 720)
        self.assertEqual(len(msg.intensities), 720)

    def test_03_ranges_match_the_wall(self):
        msg = self.scans.last()
        errors = []
        for i, r in enumerate(msg.ranges):
            angle = msg.angle_min + i * msg.angle_increment
            if abs(FACE * math.tan(angle)) < HALF_WIDTH - 0.5:
                errors.append(r - FACE / math.cos(angle))
            elif abs(angle) > math.atan2(HALF_WIDTH + 0.5, FACE):
                self.assertTrue(math.isinf(r) and r > 0, (i, angle, r))  # past the wall
        self.assertGreater(len(errors), 600)
        centre = msg.ranges[359:361]
        for r in centre:
            self.assertAlmostEqual(r, FACE, delta=0.05)  # 5 sigma of rrbot's 0.01 noise
        mean = sum(errors) / len(errors)
        std = math.sqrt(sum((e - mean) ** 2 for e in errors) / len(errors))
        self.assertLess(abs(mean), 0.003)
        self.assertAlmostEqual(std, 0.01, delta=0.003)

    def test_04_nothing_while_nobody_listens(self):
        self.scans.sub.unregister()
        publisher = [None]

        def connections():
            from rosgraph.masterapi import Master

            _, subscribers, _ = Master('/test_laser').getSystemState()
            publisher[0] = dict(subscribers).get(TOPIC, [])
            return not publisher[0]

        self.assertTrue(wait_for(connections, 10), publisher[0])
        sim_wait(1.0)
        start = rospy.Time.now()
        got = []
        sub = rospy.Subscriber(TOPIC, LaserScan, lambda m: got.append((time.monotonic(), m)))
        try:
            self.assertTrue(wait_for(lambda: got, 30), 'no scan after subscribing again')
            first = got[0][1]
            # a fresh scan, not one measured while nobody listened and kept in a queue
            self.assertGreaterEqual(first.header.stamp, start)
        finally:
            sub.unregister()


if __name__ == '__main__':
    rostest.rosrun('arm1', 'laser', Laser)
