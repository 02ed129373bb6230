#!/usr/bin/env python
"""A depth camera (gazebo_ros_openni_kinect) in front of a wall: depth image, point cloud, RGB
image and camera infos with upstream's topics, encodings, layout, frames and rate."""

import math
import os
import struct
import sys

import rosgraph
import rostest
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import node_pid, render_processes  # noqa: E402
from rostest_util import Recorder, WorldTestCase, sim_wait, wait_for  # noqa: E402

NS = '/depth_cam'
W, H, RATE = 160, 120, 10.0
F = W / (2 * math.tan(1.0471976 / 2))
WALL = 1.3  # camera_link 0.1 m in front of the base, the wall's near face 1.4 m
FRAME = 'camera_link_optical'
STEP = 0.001  # s of sim time: the world's step


def topics():
    return {name for name, _ in rosgraph.Master('/test_depth_camera').getPublishedTopics('')}


def stamps(recorder):
    return [m.header.stamp.to_sec() for _, m in recorder.msgs]


class DepthCamera(WorldTestCase):
    NODE = 'test_depth_camera'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        assert wait_for(lambda: NS + '/points' in topics(), 60), 'depth_bot did not spawn'
        cls.world = node_pid('/gazebo')
        # An update instant: camera_info alone goes out at each, without rendering. Not the
        # first, at the world's first step: the next is one period after the start of time.
        info = Recorder(NS + '/depth/camera_info', CameraInfo)
        assert wait_for(lambda: len(info.msgs) >= 3, 60), 'no depth camera_info'
        info.sub.unregister()
        cls.instant = info.last().header.stamp.to_sec()

    def check_rate(self, recorder, what, every_instant=False):
        """Judged by the stamps against the sensor's update instants, every 1/RATE s of sim
        time: no more messages than instants in their span, and with ``every_instant`` each
        stamped with its instant. A frame rendered at its instant is stamped with it; one that
        waited for a busy render process (they run at nice 10, so a busy machine starves them)
        or was lost with a failed one shows the state of when it was rendered. How many
        instants get their frame in default timing depends on the machine, not on the world."""
        t = stamps(recorder)
        self.assertGreaterEqual(len(t), 2, 'one %s only' % what)
        self.assertEqual(t, sorted(set(t)), '%s: stamps repeat or go back' % what)
        self.assertLessEqual(len(t), (t[-1] - t[0]) * RATE + 2, '%s faster than 10 Hz' % what)
        if every_instant:
            periods = [(x - self.instant) * RATE for x in t]
            off = [x for x, p in zip(t, periods) if abs(p - round(p)) > STEP * RATE]
            self.assertEqual(off, [], '%s off the %g Hz instants' % (what, RATE))

    def test_01_nothing_rendered_for_camera_infos_alone(self):
        expected = ('/ir/image_raw', '/ir/camera_info', '/depth/image_raw', '/depth/camera_info')
        self.assertLessEqual({NS + t for t in expected}, topics())
        sim_wait(1.0)
        self.assertEqual(render_processes(self.world), [], 'a render process runs for nobody')
        info = Recorder(NS + '/depth/camera_info', CameraInfo)
        self.assertTrue(wait_for(lambda: len(info.msgs) >= 6, 30), 'no depth camera_info')
        info.sub.unregister()
        self.check_rate(info, 'depth/camera_info', every_instant=True)
        m = info.last()
        self.assertEqual((m.width, m.height, m.header.frame_id), (W, H, FRAME))
        self.assertEqual(list(m.K), [F, 0, 79.5, 0, F, 59.5, 0, 0, 1])
        self.assertEqual(render_processes(self.world), [])

    def test_02_depth_image_is_32fc1_metres(self):
        depth = Recorder(NS + '/depth/image_raw', Image)
        self.assertTrue(wait_for(lambda: len(depth.msgs) >= 8, 60), 'no depth images')
        depth.sub.unregister()
        m = depth.last()
        self.assertEqual((m.encoding, m.width, m.height, m.step), ('32FC1', W, H, 4 * W))
        self.assertEqual((m.is_bigendian, m.header.frame_id, len(m.data)), (0, FRAME, 4 * W * H))
        values = struct.unpack('<%df' % (W * H), m.data)
        self.assertAlmostEqual(values[60 * W + 80], WALL, delta=0.01)  # the centre pixel
        self.assertAlmostEqual(values[30 * W + 60], WALL, delta=0.01)  # z-depth: a flat wall
        self.assertTrue(math.isnan(values[0]), 'sky beside the wall is not NaN')
        self.check_rate(depth, 'depth/image_raw')

    def test_03_point_cloud_is_organised_xyz_rgb(self):
        points = Recorder(NS + '/points', PointCloud2)
        self.assertTrue(wait_for(lambda: len(points.msgs) >= 4, 60), 'no point clouds')
        points.sub.unregister()
        m = points.last()
        self.assertEqual((m.width, m.height, m.header.frame_id), (W, H, FRAME))
        self.assertEqual((m.point_step, m.row_step, m.is_bigendian), (32, 32 * W, False))
        self.assertEqual(
            [(f.name, f.offset, f.datatype, f.count) for f in m.fields],
            [(n, o, PointField.FLOAT32, 1) for n, o in (('x', 0), ('y', 4), ('z', 8), ('rgb', 16))],
        )
        self.assertEqual(len(m.data), 32 * W * H)
        self.assertFalse(m.is_dense)  # the sky's points are NaN
        x, y, z = struct.unpack_from('<3f', m.data, (60 * W + 80) * 32)
        self.assertAlmostEqual(z, WALL, delta=0.01)
        self.assertAlmostEqual(x, z * 0.5 / F, delta=1e-4)  # optical frame: x right
        self.assertAlmostEqual(y, z * 0.5 / F, delta=1e-4)  # y down
        x, y, z = struct.unpack_from('<3f', m.data, (30 * W + 60) * 32)
        self.assertAlmostEqual(x, z * (60 - 79.5) / F, delta=1e-3)
        self.assertAlmostEqual(y, z * (30 - 59.5) / F, delta=1e-3)
        self.assertTrue(all(math.isnan(v) for v in struct.unpack_from('<3f', m.data, 0)))
        self.check_rate(points, 'points')

    def test_04_rgb_image_and_its_camera_info(self):
        image = Recorder(NS + '/ir/image_raw', Image)
        info = Recorder(NS + '/ir/camera_info', CameraInfo)
        self.assertTrue(wait_for(lambda: len(image.msgs) >= 4, 60), 'no images')
        image.sub.unregister()
        info.sub.unregister()
        m = image.last()
        self.assertEqual((m.encoding, m.width, m.height, m.step), ('rgb8', W, H, 3 * W))
        self.assertEqual(m.header.frame_id, FRAME)
        self.assertIn(m.header.stamp, [i.header.stamp for _, i in info.msgs])
        self.assertTrue(all(i.header.frame_id == FRAME for _, i in info.msgs))
        self.check_rate(image, 'ir/image_raw')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_depth_camera', DepthCamera)
