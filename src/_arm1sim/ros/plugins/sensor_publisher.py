"""SensorPublisher: one physics sensor (physics.sim_sensor) published on one topic.

A sensor is measured only while its topic has a subscriber (``wanted``), and its message is
built and handed to rospy on the physics thread: rospy's queued publishers write to sockets
from threads of their own.
"""

from __future__ import annotations

from typing import Any, Callable, Type

import rospy

from ...physics.sim_sensor import SimSensor


class SensorPublisher:
    """Publishes ``to_message(stamp_ns, reading)`` on ``topic`` for one sensor."""

    def __init__(
        self,
        sensor: SimSensor,
        topic: str,
        msg_class: Type[Any],
        to_message: Callable[[int, Any], Any],
        queue_size: int = 10,
    ) -> None:
        self.sensor = sensor
        self.topic = topic
        self._to_message = to_message
        self._pub = rospy.Publisher(topic, msg_class, queue_size=queue_size)
        sensor.wanted = lambda: self._pub.get_num_connections() > 0
        sensor.deliver = self._deliver

    def _deliver(self, stamp_ns: int, reading: Any) -> None:
        self._pub.publish(self._to_message(stamp_ns, reading))

    def shutdown(self) -> None:
        self.sensor.close()
        self._pub.unregister()
