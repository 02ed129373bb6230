"""The ROS side of the physics sensors (physics.sim_sensor): one publisher each.

``ROS_SENSOR_PLUGINS`` maps a SimSensor class to what publishes it; each sensor
implementation adds one line. A sensor is measured only while its topic has a
subscriber (``wanted``), and its message is built and handed to rospy on the
physics thread: rospy's queued publishers write to sockets from threads of their own.
"""

from __future__ import annotations

import logging
from typing import Any, Callable, Dict, Optional, Type

import rospy

from ..physics.diff_drive import DiffDrive
from ..physics.laser import Laser
from ..physics.sim_sensor import SimSensor
from ..sim.simulation import Model, Plugin
from . import diff_drive_plugin, laser_plugin
from . import state_sensor_plugins as state

log = logging.getLogger('rosout')


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


PluginFactory = Callable[[Any], Plugin]
ROS_SENSOR_PLUGINS: Dict[Type[SimSensor], PluginFactory] = {}
ROS_SENSOR_PLUGINS[state.ImuSensor] = state.imu_sensor_publisher
ROS_SENSOR_PLUGINS[state.ImuModelPlugin] = state.imu_plugin_publisher
ROS_SENSOR_PLUGINS[state.P3d] = state.p3d_publisher
ROS_SENSOR_PLUGINS[state.ContactSensor] = state.bumper_publisher
ROS_SENSOR_PLUGINS[state.ForceTorque] = state.ft_publisher
ROS_SENSOR_PLUGINS[Laser] = laser_plugin.laser_publisher
ROS_SENSOR_PLUGINS[DiffDrive] = diff_drive_plugin.diff_drive_plugin


def attach_sensor_plugins(model: Model) -> None:
    """Give each of the model's physics sensors its ROS publisher (in ``model.plugins``)."""
    for sensor in model.sensors:
        factory: Optional[PluginFactory] = None
        for cls in type(sensor).__mro__:
            factory = ROS_SENSOR_PLUGINS.get(cls)
            if factory is not None:
                break
        if factory is None:
            log.warning(
                "model '%s': %s '%s' has no ROS publisher in the stand-in",
                model.name,
                sensor.kind,
                sensor.name,
            )
            continue
        model.plugins.append(factory(sensor))
