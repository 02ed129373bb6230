"""The ROS side of the physics sensors (physics.sim_sensor): which plugin publishes each.

``ROS_SENSOR_PLUGINS`` maps a SimSensor class to what publishes it
(plugins/sensor_publisher.py's SensorPublisher, mostly); each sensor implementation adds one line.
"""

from __future__ import annotations

import logging
from typing import Any, Callable, Dict, Optional, Type

from ...physics.diff_drive import DiffDrive
from ...physics.grasp import GraspFix
from ...physics.laser import Laser
from ...physics.sim_sensor import SimSensor
from ...sim.simulation import Model, Plugin
from . import diff_drive_plugin, grasp_plugin, laser_plugin
from . import state_sensor_plugins as state

log = logging.getLogger('rosout')


PluginFactory = Callable[[Any], Plugin]
ROS_SENSOR_PLUGINS: Dict[Type[SimSensor], PluginFactory] = {}
ROS_SENSOR_PLUGINS[state.ImuSensor] = state.imu_sensor_publisher
ROS_SENSOR_PLUGINS[state.ImuModelPlugin] = state.imu_plugin_publisher
ROS_SENSOR_PLUGINS[state.P3d] = state.p3d_publisher
ROS_SENSOR_PLUGINS[state.ContactSensor] = state.bumper_publisher
ROS_SENSOR_PLUGINS[state.ForceTorque] = state.ft_publisher
ROS_SENSOR_PLUGINS[Laser] = laser_plugin.laser_publisher
ROS_SENSOR_PLUGINS[DiffDrive] = diff_drive_plugin.diff_drive_plugin
ROS_SENSOR_PLUGINS[GraspFix] = grasp_plugin.grasp_event_publisher


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
