"""gazebo_ros_laser and gazebo_ros_gpu_laser: a ray sensor's scans as sensor_msgs/LaserScan.

As upstream: queue 1, stamp = the scan's sim time, angle_increment = Gazebo's
AngleResolution, time_increment = scan_time = 0 (an instantaneous scan), ranges and
intensities copied from the sensor (all vertical layers one after another). The
frame id is ``tf::resolve(tf_prefix, frameName)``, where tf_prefix is the
``tf_prefix`` parameter found upward from the plugin's namespace, else that
namespace itself without its trailing '/': so ``<robotNamespace>/rrbot`` with
``<frameName>hokuyo_link`` stamps ``rrbot/hokuyo_link``. Measured only while the
topic has a subscriber; an empty ``<topicName>`` advertises nothing.
"""

from __future__ import annotations

from typing import Any, Optional

from sensor_msgs.msg import LaserScan

from ...physics.laser import Laser, LaserReading
from ..common.stamps import to_time
from .frames import tf_prefix, tf_resolve
from .sensor_publisher import SensorPublisher


def laser_message(stamp_ns: int, frame_id: str, laser: Laser, r: LaserReading) -> LaserScan:
    spec = laser.spec
    msg = LaserScan()
    msg.header.stamp = to_time(stamp_ns)
    msg.header.frame_id = frame_id
    msg.angle_min = spec.min_angle
    msg.angle_max = spec.max_angle
    msg.angle_increment = spec.angle_increment
    msg.time_increment = 0.0  # instantaneous simulator scan
    msg.scan_time = 0.0
    msg.range_min = spec.range_min
    msg.range_max = spec.range_max
    msg.ranges = r.ranges.tolist()
    msg.intensities = r.intensities.tolist()
    return msg


class LaserPublisher:
    """The plugin's part in the ROS layer: the LaserScan topic, if it has one."""

    def __init__(self, laser: Laser) -> None:
        self.laser = laser
        self.frame_id = tf_resolve(
            tf_prefix(laser.plugin.namespace, laser.plugin.namespace), laser.plugin.frame_name
        )
        self.publisher: Optional[SensorPublisher] = None
        if laser.topic:
            frame = self.frame_id
            self.publisher = SensorPublisher(
                laser,
                laser.topic,
                LaserScan,
                lambda t, r: laser_message(t, frame, laser, r),
                queue_size=1,
            )

    def shutdown(self) -> None:
        if self.publisher is not None:
            self.publisher.shutdown()
        else:
            self.laser.close()


def laser_publisher(sensor: Any) -> LaserPublisher:
    return LaserPublisher(sensor)
