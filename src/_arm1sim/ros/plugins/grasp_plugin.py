"""The grasp plugin's events where a ROS user sees them.

Upstream's GazeboGraspFix publishes each attach and detach on the Gazebo topic
``~/grasp_events``, and gazebo_grasp_plugin_ros's grasp_event_republisher hands them on to
ROS as ``gazebo_grasp_plugin_ros/GazeboGraspEvent``. The stand-in has no Gazebo transport:
the world node publishes that message itself on ``/gazebo/grasp_events`` (its ``~/``).
"""

from __future__ import annotations

from typing import List, Tuple

import rospy
from gazebo_grasp_plugin_ros.msg import GazeboGraspEvent

from ...physics.grasp import GraspFix

GRASP_EVENTS_TOPIC = '/gazebo/grasp_events'


class GraspEventPublisher:
    """Publishes one robot's grasp plugin's events (every one: they are few)."""

    def __init__(self, fix: GraspFix) -> None:
        self.fix = fix
        self._pub = rospy.Publisher(GRASP_EVENTS_TOPIC, GazeboGraspEvent, queue_size=10)
        fix.deliver = self._deliver

    def _deliver(self, stamp_ns: int, events: List[Tuple[str, str, bool]]) -> None:
        for arm, obj, attached in events:
            self._pub.publish(GazeboGraspEvent(arm=arm, object=obj, attached=attached))

    def shutdown(self) -> None:
        self.fix.close()
        self._pub.unregister()


def grasp_event_publisher(fix: GraspFix) -> GraspEventPublisher:
    return GraspEventPublisher(fix)
