#!/usr/bin/env python
"""Cameras against the world's limits and failures, in the default timing (physics never waits
for rendering): a 6000x6000 camera is refused, a one-link camera model streams, a killed render
process is replaced while /clock goes on, and a deleted model's camera is gone for good."""

import os
import signal
import sys
import time

import rosgraph
import rostest
from rosgraph_msgs.msg import Log

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import (  # noqa: E402
    ImageRecorder,
    camera_box_urdf,
    clock_rate,
    delete_model,
    node_pid,
    render_processes,
    spawn_urdf,
)
from faults_util import ClockPace  # noqa: E402
from rostest_util import WorldTestCase, wait_for  # noqa: E402

TOPIC = '/eye/image_raw'
# From the kill until the images are back, the real-time factor at least this share of the
# world's own pace right after, with the camera streaming again: the world is judged, not the
# machine. A world that waited out the 0.5 s before the new renderer would keep ~0.6 over the
# ~1.2 s; 0.93 of it was seen with four other busy sessions on the 2 cores, 1.0 otherwise.
MIN_PACE_RATIO = 0.8


def publishers(topic):
    for name, nodes in rosgraph.Master('/test_camera_limits').getSystemState()[0]:
        if name == topic:
            return nodes
    return []


class CameraLimits(WorldTestCase):
    NODE = 'test_camera_limits'
    RECORD = ('clock', 'rosout')
    SERVICES = ('/gazebo/spawn_urdf_model',)
    FIRST = ('clock',)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.world = node_pid('/gazebo')

    def clock_advances(self, seconds, timeout):
        start = self.clock.last().clock.to_sec()
        return wait_for(lambda: self.clock.last().clock.to_sec() - start >= seconds, timeout)

    def test_01_a_6000x6000_camera_at_30_hz_is_refused_naming_camera_pixels(self):
        ok, msg = spawn_urdf('big', camera_box_urdf(6000, 6000, 30), x=1.0)
        self.assertFalse(ok, msg)
        for words in ("'big'", 'camera pixels is 36000000', '16777216', '~limits/camera_pixels'):
            self.assertIn(words, msg)
        self.assertTrue(self.clock_advances(0.5, 10), 'the world stopped')
        self.assertEqual(render_processes(self.world), [])
        self.assertEqual(publishers(TOPIC), [])

    def test_02_a_model_without_joints_streams_its_camera(self):
        ok, msg = spawn_urdf('box', camera_box_urdf(320, 240, 30), x=1.0)
        self.assertTrue(ok, msg)
        images = ImageRecorder(TOPIC)
        try:
            # the render processes start with the first subscriber: measure after that
            self.assertTrue(wait_for(lambda: len(images.meta) >= 10, 60), 'images do not come')
            start = time.monotonic()
            self.assertTrue(wait_for(lambda: len(images.meta) >= 40, 60), 'images stop')
        finally:
            images.close()
        meta = images.meta
        self.assertEqual(meta[0][1:6], (320, 240, 'rgb8', 960, 320 * 240 * 3))
        stamps = [m[0] for m in meta]
        self.assertEqual(stamps, sorted(set(stamps)), 'stamps go back or repeat')
        rate = (len(stamps) - 11) / (stamps[-1] - stamps[10])
        rtf = clock_rate(self.clock, start)
        print('one-link camera: %.1f images per sim second, real-time factor %.3f' % (rate, rtf))
        self.assertLessEqual(rate, 30.5)
        self.assertGreater(rate, 10)  # a 320x240 frame is a few ms: most instants get theirs

    def test_03_a_killed_render_process_is_replaced_and_the_clock_goes_on(self):
        images = ImageRecorder(TOPIC)
        try:
            self.assertTrue(wait_for(lambda: images.meta, 30), 'no image')
            victims = render_processes(self.world)
            self.assertEqual(len(victims), 2)
            killed_at, sim_at = time.monotonic(), self.clock.last().clock.to_sec()
            os.kill(victims[0], signal.SIGKILL)
            back = wait_for(
                lambda: (
                    sum(m[0] > sim_at for m in images.meta) >= 20
                    and len(render_processes(self.world)) == 2
                    and victims[0] not in render_processes(self.world)
                ),
                60,
            )
            self.assertTrue(back, 'images or render processes did not come back')
            rtf = clock_rate(self.clock, killed_at)
            base = ClockPace(self.clock).baseline(3.0)
        finally:
            images.close()
        print(
            'killed render process %d: real-time factor since %.3f (%.3f after)'
            % (victims[0], rtf, base)
        )
        self.assertGreater(
            rtf, MIN_PACE_RATIO * base, 'the world slowed down for a dead render process'
        )
        errors = [m.msg for m in self.rosout.since(killed_at) if m.level == Log.ERROR]
        self.assertTrue(any("'eye'" in e and 'killed by signal 9' in e for e in errors), errors)

    def test_04_deleting_the_model_releases_its_camera_and_the_name_comes_back(self):
        ok, msg = delete_model('box')
        self.assertTrue(ok, msg)
        self.assertTrue(wait_for(lambda: not publishers(TOPIC), 10), publishers(TOPIC))
        ok, msg = spawn_urdf('box', camera_box_urdf(320, 240, 30), x=1.0)
        self.assertTrue(ok, msg)
        images = ImageRecorder(TOPIC)
        try:
            self.assertTrue(wait_for(lambda: len(images.meta) >= 3, 30), 'no images after respawn')
        finally:
            images.close()


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_camera_limits', CameraLimits)
