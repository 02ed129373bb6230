"""The ROS side of the state sensors: sensor_msgs/Imu (gazebo_ros_imu_sensor, gazebo_ros_imu),
nav_msgs/Odometry (gazebo_ros_p3d), gazebo_msgs/ContactsState (gazebo_ros_bumper) and
geometry_msgs/WrenchStamped (gazebo_ros_ft_sensor), filled as upstream fills them.

Each publishes only while its topic has a subscriber (ros.sensor_plugins.SensorPublisher).
Frame ids: p3d, bumper and ft_sensor pass theirs through tf::resolve with the
``<robotNamespace>/tf_prefix`` parameter; the IMU plugins use frameName as written.
"""

from __future__ import annotations

from typing import Any, List, Protocol, Sequence

import rospy
from gazebo_msgs.msg import ContactsState, ContactState
from geometry_msgs.msg import Vector3, Wrench, WrenchStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty, EmptyResponse

from ...description.gazebo_plugins import topic
from ...physics.contact import ContactPair, ContactSensor
from ...physics.force_torque import ForceTorque, WrenchReading
from ...physics.imu import ImuModelPlugin, ImuReading, ImuSensor
from ...physics.p3d import P3d, P3dReading
from ..common.stamps import to_time
from .frames import tf_resolve
from .sensor_publisher import SensorPublisher


def resolve_frame(name: str, namespace: str = '') -> str:
    """tf::resolve(tf_prefix, name), tf_prefix read as upstream reads it: the plugin node
    handle's own ``tf_prefix`` parameter (``<robotNamespace>/tf_prefix``), else none."""
    prefix = ''
    key = topic(namespace, 'tf_prefix')
    try:
        if rospy.has_param(key):
            prefix = str(rospy.get_param(key))
    except (OSError, rospy.ROSException):  # no master: as if unset
        pass
    return tf_resolve(prefix, name)


def imu_message(stamp_ns: int, frame_id: str, r: ImuReading) -> Imu:
    msg = Imu()
    msg.header.stamp = to_time(stamp_ns)
    msg.header.frame_id = frame_id
    o = msg.orientation
    o.x, o.y, o.z, o.w = r.orientation
    a = msg.angular_velocity
    a.x, a.y, a.z = r.angular_velocity
    la = msg.linear_acceleration
    la.x, la.y, la.z = r.linear_acceleration
    n2 = r.noise * r.noise
    diagonal = [n2, 0.0, 0.0, 0.0, n2, 0.0, 0.0, 0.0, n2]
    msg.orientation_covariance = list(diagonal)
    msg.angular_velocity_covariance = list(diagonal)
    msg.linear_acceleration_covariance = list(diagonal)
    return msg


class PoseTwist(Protocol):
    """A reading with a pose and a twist (p3d's, diff drive's)."""

    @property
    def position(self) -> Sequence[float]: ...
    @property
    def orientation(self) -> Sequence[float]: ...
    @property
    def linear(self) -> Sequence[float]: ...
    @property
    def angular(self) -> Sequence[float]: ...


def odometry_pose_twist(stamp_ns: int, frame_id: str, child: str, r: PoseTwist) -> Odometry:
    """An Odometry with header, pose and twist filled in; covariances left to the caller."""
    msg = Odometry()
    msg.header.stamp = to_time(stamp_ns)
    msg.header.frame_id = frame_id
    msg.child_frame_id = child
    pose, twist = msg.pose.pose, msg.twist.twist
    pose.position.x, pose.position.y, pose.position.z = r.position
    o = pose.orientation
    o.x, o.y, o.z, o.w = r.orientation
    twist.linear.x, twist.linear.y, twist.linear.z = r.linear
    twist.angular.x, twist.angular.y, twist.angular.z = r.angular
    return msg


def odometry_message(stamp_ns: int, frame_id: str, child: str, r: P3dReading) -> Odometry:
    msg = odometry_pose_twist(stamp_ns, frame_id, child, r)
    n2 = r.noise * r.noise
    covariance = [n2 if i % 7 == 0 else 0.0 for i in range(36)]
    msg.pose.covariance = list(covariance)
    msg.twist.covariance = list(covariance)
    return msg


def _vector(v: Any) -> Vector3:
    return Vector3(v[0], v[1], v[2])


def contacts_message(stamp_ns: int, frame_id: str, pairs: List[ContactPair]) -> ContactsState:
    msg = ContactsState()
    msg.header.stamp = to_time(stamp_ns)
    msg.header.frame_id = frame_id
    stamp = to_time(stamp_ns)
    for i, pair in enumerate(pairs):
        state = ContactState()
        state.collision1_name, state.collision2_name = pair.collision1, pair.collision2
        # upstream's debug text, ROS time printed as sec.nsec
        state.info = 'Debug:  i:(%d/%d)     my geom:%s   other geom:%s         time:%d.%09d\n' % (
            i,
            len(pairs),
            pair.collision1,
            pair.collision2,
            stamp.secs,
            stamp.nsecs,
        )
        total = Wrench()
        for force, torque in pair.wrenches:
            state.wrenches.append(Wrench(_vector(force), _vector(torque)))
            total.force.x += force[0]
            total.force.y += force[1]
            total.force.z += force[2]
            total.torque.x += torque[0]
            total.torque.y += torque[1]
            total.torque.z += torque[2]
        state.total_wrench = total
        state.contact_positions = [_vector(v) for v in pair.positions]
        state.contact_normals = [_vector(v) for v in pair.normals]
        state.depths = list(pair.depths)
        msg.states.append(state)
    return msg


def wrench_message(stamp_ns: int, frame_id: str, r: WrenchReading) -> WrenchStamped:
    msg = WrenchStamped()
    msg.header.stamp = to_time(stamp_ns)
    msg.header.frame_id = frame_id
    msg.wrench.force = _vector(r.force)
    msg.wrench.torque = _vector(r.torque)
    return msg


def imu_sensor_publisher(sensor: ImuSensor) -> SensorPublisher:
    frame = sensor.frame_id
    return SensorPublisher(sensor, sensor.topic, Imu, lambda t, r: imu_message(t, frame, r))


class ImuPluginPublisher:
    """gazebo_ros_imu: its topic and the Empty service upstream offers (it does nothing)."""

    def __init__(self, sensor: ImuModelPlugin) -> None:
        frame = sensor.frame_id
        self.publisher = SensorPublisher(
            sensor, sensor.topic, Imu, lambda t, r: imu_message(t, frame, r)
        )
        self.service = rospy.Service(sensor.service, Empty, lambda req: EmptyResponse())

    def shutdown(self) -> None:
        self.service.shutdown()
        self.publisher.shutdown()


class Unpublished:
    """A plugin whose upstream advertises nothing (gazebo_ros_imu with an empty topicName)."""

    def __init__(self, sensor: Any) -> None:
        self.sensor = sensor

    def shutdown(self) -> None:
        self.sensor.close()


def imu_plugin_publisher(sensor: ImuModelPlugin) -> Any:
    if not sensor.topic:
        return Unpublished(sensor)
    return ImuPluginPublisher(sensor)


def p3d_publisher(sensor: P3d) -> SensorPublisher:
    frame, child = resolve_frame(sensor.frame_id, sensor.namespace), sensor.child_frame_id
    return SensorPublisher(
        sensor, sensor.topic, Odometry, lambda t, r: odometry_message(t, frame, child, r)
    )


def bumper_publisher(sensor: ContactSensor) -> SensorPublisher:
    frame = resolve_frame(sensor.frame_id, sensor.namespace)
    return SensorPublisher(
        sensor, sensor.topic, ContactsState, lambda t, r: contacts_message(t, frame, r)
    )


def ft_publisher(sensor: ForceTorque) -> SensorPublisher:
    frame = resolve_frame(sensor.frame_id, sensor.namespace)
    return SensorPublisher(
        sensor, sensor.topic, WrenchStamped, lambda t, r: wrench_message(t, frame, r)
    )
