"""The ROS side of gazebo_ros_diff_drive (physics.diff_drive): a geometry_msgs/Twist
subscriber on ``commandTopic``, nav_msgs/Odometry on ``odometryTopic`` (with ``publishTf``),
the odometry frame -> robot base frame transform on /tf (``publishOdomTF``), and with their
flags the wheels' frames on /tf and their positions on ``joint_states``.

As upstream it publishes whether or not anyone subscribes, at the plugin's update rate,
stamped with sim time; frame ids go through tf::resolve with ``<robotNamespace>/tf_prefix``.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional

import rospy
from geometry_msgs.msg import TransformStamped, Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

from ...description.gazebo_plugins import topic
from ...physics.diff_drive import DiffDrive, DiffDriveReading
from ..common.stamps import to_time
from .state_sensor_plugins import odometry_pose_twist, resolve_frame

# upstream's fixed odometry pose covariance (x, y well known; z, roll, pitch unknown)
POSE_COVARIANCE = {0: 1e-5, 7: 1e-5, 14: 1e12, 21: 1e12, 28: 1e12, 35: 1e-3}


def odometry_message(stamp_ns: int, frame_id: str, child: str, r: DiffDriveReading) -> Odometry:
    msg = odometry_pose_twist(stamp_ns, frame_id, child, r)
    msg.pose.covariance = [POSE_COVARIANCE.get(i, 0.0) for i in range(36)]
    return msg


def transform(stamp_ns: int, parent: str, child: str, position: Any, orientation: Any) -> Any:
    t = TransformStamped()
    t.header.stamp = to_time(stamp_ns)
    t.header.frame_id = parent
    t.child_frame_id = child
    tr, rot = t.transform.translation, t.transform.rotation
    tr.x, tr.y, tr.z = position
    rot.x, rot.y, rot.z, rot.w = orientation
    return t


class DiffDrivePlugin:
    """One diff drive's topics; ``shutdown`` when its model goes."""

    def __init__(self, drive: DiffDrive) -> None:
        self.drive = drive
        ns = drive.namespace
        self.odom_frame = resolve_frame(drive.odometry_frame, ns)
        self.base_frame = resolve_frame(drive.robot_base_frame, ns)
        self._frames: Dict[str, str] = {}
        self._odom: Optional[rospy.Publisher] = None
        self._joints: Optional[rospy.Publisher] = None
        self._tf: Optional[rospy.Publisher] = None
        if drive.publish_tf:
            self._odom = rospy.Publisher(drive.odometry_topic, Odometry, queue_size=1)
        if drive.publish_wheel_joint_state:
            self._joints = rospy.Publisher(topic(ns, 'joint_states'), JointState, queue_size=1000)
        if (drive.publish_tf and drive.publish_odom_tf) or drive.publish_wheel_tf:
            self._tf = rospy.Publisher('/tf', TFMessage, queue_size=100)
        self._sub = rospy.Subscriber(drive.command_topic, Twist, self._command, queue_size=1)
        drive.deliver = self._deliver

    def _frame(self, name: str) -> str:
        """A wheel frame, resolved once (a parameter lookup is a call to the master)."""
        resolved = self._frames.get(name)
        if resolved is None:
            resolved = self._frames[name] = resolve_frame(name, self.drive.namespace)
        return resolved

    def _command(self, msg: Twist) -> None:
        try:
            self.drive.set_command(msg.linear.x, msg.angular.z)
        except ValueError as exc:  # a flood of them: one warning per 5 s
            rospy.logwarn_throttle(
                5.0, 'diff drive: refusing %s: %s' % (self.drive.command_topic, exc)
            )

    def _deliver(self, stamp_ns: int, r: DiffDriveReading) -> None:
        """Physics thread: rospy's queued publishers write from threads of their own."""
        transforms: List[Any] = []
        if self._odom is not None:
            if self.drive.publish_odom_tf:
                transforms.append(
                    transform(stamp_ns, self.odom_frame, self.base_frame, r.position, r.orientation)
                )
            self._odom.publish(odometry_message(stamp_ns, self.odom_frame, self.base_frame, r))
        for parent, child, position, orientation in r.wheel_frames:
            transforms.append(
                transform(stamp_ns, self._frame(parent), self._frame(child), position, orientation)
            )
        if transforms and self._tf is not None:
            self._tf.publish(TFMessage(transforms=transforms))
        if self._joints is not None and r.wheel_positions:
            msg = JointState()
            msg.header.stamp = to_time(stamp_ns)
            msg.name = [n for n, _ in r.wheel_positions]
            msg.position = [pos for _, pos in r.wheel_positions]
            self._joints.publish(msg)

    def shutdown(self) -> None:
        self.drive.close()
        self._sub.unregister()
        for pub in (self._odom, self._joints, self._tf):
            if pub is not None:
                pub.unregister()


def diff_drive_plugin(drive: DiffDrive) -> DiffDrivePlugin:
    return DiffDrivePlugin(drive)
