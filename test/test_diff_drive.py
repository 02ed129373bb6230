#!/usr/bin/env python
"""gazebo_ros_diff_drive under a real master: a two-wheeled robot of our own drives and turns
as geometry_msgs/Twist on its cmd_vel asks, and reports nav_msgs/Odometry on odom and the
odom -> base_footprint transform on /tf (tf2_msgs/TFMessage), stamped in sim time, whether
or not anyone listens."""

import math
import os
import sys

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(1, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'unit'))
from rostest_util import (  # noqa: E402
    Recorder,
    SpawningTestCase,
    sim_wait,
    spawn_urdf,
    wait_for,
)
from two_wheels import robot_urdf  # noqa: E402

RATE = 50  # updateRate, Hz
ROBOT = robot_urdf(
    updateRate=RATE,
    commandTopic='cmd_vel',
    odometryTopic='odom',
    odometryFrame='odom',
    robotBaseFrame='base_footprint',
    odometrySource='world',
    publishWheelJointState='true',
)


def yaw_of(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def odom_transforms(recorder):
    return [
        t
        for _, m in list(recorder.msgs)
        for t in m.transforms
        if (t.header.frame_id, t.child_frame_id) == ('odom', 'base_footprint')
    ]


class DiffDrive(SpawningTestCase):
    NODE = 'test_diff_drive'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        spawn_urdf('two_wheels', ROBOT, '/rover', (0, 0, 0.005))
        cls.cmd = rospy.Publisher('/rover/cmd_vel', Twist, queue_size=1)
        assert wait_for(lambda: cls.cmd.get_num_connections() > 0, 10), 'nobody on cmd_vel'
        sim_wait(0.5)  # let it settle on the ground: physics' time, not the machine's

    def drive(self, x, z):
        self.cmd.publish(Twist(linear=Vector3(x, 0, 0), angular=Vector3(0, 0, z)))

    def test_01_advertises_odom_tf_and_wheel_states_before_anyone_listens(self):
        pubs, _, _ = rosgraph.Master('/test_diff_drive').getSystemState()
        publishers = dict(pubs)
        for topic in ('/rover/odom', '/tf', '/rover/joint_states'):
            self.assertIn('/gazebo', publishers.get(topic, []), topic)

    def test_02_drives_forward_at_the_commanded_speed(self):
        odom = Recorder('/rover/odom', Odometry)
        tf = Recorder('/tf', TFMessage)
        try:
            assert wait_for(lambda: odom.last() is not None, 10), 'no odometry'
            start = odom.last().pose.pose.position
            self.drive(0.2, 0.0)
            sim_wait(2.0)
            msg = odom.last()
            self.assertEqual((msg.header.frame_id, msg.child_frame_id), ('odom', 'base_footprint'))
            self.assertAlmostEqual(msg.twist.twist.linear.x, 0.2, delta=0.02)
            self.assertAlmostEqual(msg.twist.twist.angular.z, 0.0, delta=0.05)
            self.assertGreater(msg.pose.pose.position.x - start.x, 0.25)
            self.assertAlmostEqual(msg.pose.pose.position.y, start.y, delta=0.03)
            # the odom -> base_footprint transform says the same, at the same stamps; /tf is
            # another socket, so its message of that step may arrive just after odom's
            stamp = msg.header.stamp
            assert wait_for(
                lambda: any(t.header.stamp >= stamp for t in odom_transforms(tf)), 10
            ), 'no /tf stamped at or after the odometry'
            transforms = {t.header.stamp: t for t in odom_transforms(tf)}
            self.assertIn(msg.header.stamp, transforms)
            t = transforms[msg.header.stamp].transform.translation
            self.assertAlmostEqual(t.x, msg.pose.pose.position.x, delta=1e-6)
            self.assertAlmostEqual(t.y, msg.pose.pose.position.y, delta=1e-6)
            # at the update rate, in sim time
            stamps = sorted(s.to_sec() for s in transforms)[-RATE:]
            gaps = [b - a for a, b in zip(stamps, stamps[1:])]
            self.assertAlmostEqual(sum(gaps) / len(gaps), 1.0 / RATE, delta=0.1 / RATE)
        finally:
            self.drive(0.0, 0.0)
            odom.sub.unregister()
            tf.sub.unregister()

    def test_03_turns_at_the_commanded_rate(self):
        odom = Recorder('/rover/odom', Odometry)
        try:
            self.drive(0.0, 1.0)
            sim_wait(1.0)
            first = odom.last()
            sim_wait(1.0)
            last = odom.last()
            turned = math.remainder(
                yaw_of(last.pose.pose.orientation) - yaw_of(first.pose.pose.orientation),
                2 * math.pi,
            )
            seconds = (last.header.stamp - first.header.stamp).to_sec()
            self.assertAlmostEqual(turned / seconds, 1.0, delta=0.1)  # counter-clockwise
            self.assertAlmostEqual(last.twist.twist.angular.z, 1.0, delta=0.1)
        finally:
            self.drive(0.0, 0.0)
            odom.sub.unregister()

    def test_04_wheel_joint_states(self):
        states = Recorder('/rover/joint_states', JointState)
        try:
            assert wait_for(lambda: states.last() is not None, 10), 'no wheel joint states'
            msg = states.last()
            self.assertEqual(msg.name, ['wheel_left_joint', 'wheel_right_joint'])
            self.assertEqual(len(msg.position), 2)
        finally:
            states.sub.unregister()


if __name__ == '__main__':
    rostest.rosrun('arm1', 'diff_drive', DiffDrive)
