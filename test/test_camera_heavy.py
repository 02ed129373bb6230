#!/usr/bin/env python
"""With the limits raised, a 6000x6000 camera at 30 Hz on a one-link model beside arm1: its
images come slower than 30 Hz while the world keeps its pace (issue 15's done-when): real
time on a quiet machine, the pace it had before the camera on a busy one."""

import os
import sys
import time
import unittest

import rospy
import rostest
from std_msgs.msg import Float64

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import ImageRecorder, camera_box_urdf, clock_rate, delete_model, spawn_urdf  # noqa: E402,E501
from rostest_util import Recorder, clock_recorder, joint_recorder, wait_for  # noqa: E402

SIDE = 6000
CLEAR_OF_ARM1 = 1.0  # m along x
FRAMES = 3  # a frame takes seconds to render: enough to measure a rate
BASELINE_S = 6.0  # wall seconds of /gazebo/real_time_factor before the camera


class HeavyCamera(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_camera_heavy')
        cls.clock = clock_recorder()
        cls.rtf = Recorder('/gazebo/real_time_factor', Float64)
        states = joint_recorder()
        assert wait_for(lambda: states.last() is not None, 60), 'no joint_states: arm1 is not up'

    def test_a_6000x6000_camera_lowers_its_image_rate_not_the_real_time_factor(self):
        # The pace this machine gives the world without the camera: on a loaded machine it is
        # below 1 whatever the camera does, so the camera is judged against it.
        before = time.monotonic()
        wait_for(lambda: False, BASELINE_S, poll=0.5)
        baseline = sorted(m.data for t, m in self.rtf.msgs if before + 1 < t)
        self.assertTrue(baseline, 'no /gazebo/real_time_factor in %.0f s' % BASELINE_S)
        base = baseline[len(baseline) // 2]
        # clear of arm1: a box spawned inside its links sticks among their convex pieces
        ok, msg = spawn_urdf('big', camera_box_urdf(SIDE, SIDE, 30), x=CLEAR_OF_ARM1)
        self.assertTrue(ok, msg)
        images = ImageRecorder('/eye/image_raw', buff_size=1 << 28)
        try:
            start = time.monotonic()
            got = wait_for(lambda: len(images.meta) >= FRAMES, 150, poll=0.5)
            end = time.monotonic()
        finally:
            images.close()
            delete_model('big')
        self.assertTrue(got, 'only %d image(s) in %.0f s' % (len(images.meta), end - start))
        meta = images.meta
        self.assertEqual(meta[0][1:6], (SIDE, SIDE, 'rgb8', SIDE * 3, SIDE * SIDE * 3))
        stamps = [m[0] for m in meta]
        rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        rtf = clock_rate(self.clock, start)
        seconds = [(t - start, m.data) for t, m in self.rtf.msgs if start + 1 < t <= end]
        windows = ['%.0f:%.3f' % w for w in seconds]
        print(
            '%dx%d camera: %d images in %.1f s of wall time (at %s s), %.2f images per sim '
            'second; real-time factor %.4f over the run, per second %s'
            % (
                SIDE,
                SIDE,
                len(stamps),
                end - start,
                ' '.join('%.0f' % (t - start) for t in images.arrived),
                rate,
                rtf,
                ' '.join(windows),
            )
        )
        # Physics never waits for a frame: the frames come far slower than 30 per sim second.
        self.assertLess(rate, 30 * 0.5, 'the image rate did not drop')
        # The world's /gazebo/real_time_factor, once a wall second, keeps most of the pace it
        # had without the camera; in lockstep this camera would bring it down to a few
        # hundredths. Not all of it on a busy machine: the render process takes a core and the
        # world publishes 108 MB a frame, CPU the other processes no longer leave it (0.99
        # with the camera on a quiet machine; 0.84 against 0.98 before it at load 11).
        median = sorted(v for _, v in seconds)[len(seconds) // 2]
        print('real-time factor without the camera: median %.3f' % base)
        self.assertGreaterEqual(median, 0.8 * base, 'the camera slowed the world down')
        self.assertGreaterEqual(rtf, 0.75 * base, 'the camera slowed the world down')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_camera_heavy', HeavyCamera)
