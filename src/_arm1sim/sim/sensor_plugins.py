"""Which physics sensor stands in for which Gazebo sensor plugin or model plugin.

A builder takes the parsed ``<sensor>`` (or model ``<plugin>``), the spawned
robot and the namespace the plugin's topics go under, and returns the
physics.sim_sensor.SimSensor that measures it. Each implementation has one
line in ``SENSOR_PLUGINS`` (keyed by plugin filename, for plugins inside a
``<sensor>``) or ``MODEL_PLUGINS`` (plugins of ``<gazebo>`` without reference);
plugins in neither (nor description.gazebo_plugins.HANDLED_PLUGINS) are named
in a warning at spawn.
"""

from __future__ import annotations

import logging
from typing import Callable, Dict, List, Optional

from ..description.gazebo_plugins import (
    PluginSpec,
    SensorSpec,
    model_plugins,
    sensor_specs,
    unimplemented,
)
from ..description.limits import Limits
from ..description.urdf_model import RobotModel
from ..physics import diff_drive, laser
from ..physics.robot import Robot
from ..physics.sim_sensor import SimSensor
from . import grasp_plugin, state_sensors

log = logging.getLogger('_arm1sim.physics')

# (sensor, its plugin, robot, namespace for topics, limits) -> the sensor, or None when the
# plugin would not load in Gazebo either (it has said why, naming it)
SensorBuilder = Callable[[str, SensorSpec, PluginSpec, Robot, str, Limits], Optional[SimSensor]]
# (model name, plugin, robot, namespace for topics, limits) -> the sensor, or None as above
ModelPluginBuilder = Callable[[str, PluginSpec, Robot, str, Limits], Optional[SimSensor]]

SENSOR_PLUGINS: Dict[str, SensorBuilder] = {}
MODEL_PLUGINS: Dict[str, ModelPluginBuilder] = {}
SENSOR_PLUGINS['libgazebo_ros_imu_sensor.so'] = state_sensors.build_imu_sensor
SENSOR_PLUGINS['libgazebo_ros_bumper.so'] = state_sensors.build_bumper
SENSOR_PLUGINS['libgazebo_ros_laser.so'] = laser.build_laser
SENSOR_PLUGINS['libgazebo_ros_gpu_laser.so'] = laser.build_laser
MODEL_PLUGINS['libgazebo_ros_imu.so'] = state_sensors.build_imu_plugin
MODEL_PLUGINS['libgazebo_ros_p3d.so'] = state_sensors.build_p3d
MODEL_PLUGINS['libgazebo_ros_ft_sensor.so'] = state_sensors.build_ft_sensor
MODEL_PLUGINS['libgazebo_ros_diff_drive.so'] = diff_drive.build_diff_drive
MODEL_PLUGINS[grasp_plugin.GRASP_PLUGIN] = grasp_plugin.build_grasp_fix


def build_sensors(
    model: str, description: RobotModel, robot: Robot, namespace: str, limits: Limits
) -> List[SimSensor]:
    """The physics sensors of a spawned model; warns once about each plugin not implemented.

    ``namespace`` is the spawn request's, used by plugins without ``<robotNamespace>``.
    Raises description.urdf_model.UrdfError (or LimitError) naming a sensor that cannot be built.
    """
    for line in unimplemented(description, model, [*SENSOR_PLUGINS, *MODEL_PLUGINS]):
        log.warning(line)
    out: List[SimSensor] = []
    for sensor in sensor_specs(description):
        for plugin in sensor.plugins:
            build = SENSOR_PLUGINS.get(plugin.filename)
            if build is not None:
                ns = plugin.namespace(namespace, model)
                built = build(model, sensor, plugin, robot, ns, limits)
                if built is not None:
                    out.append(built)
    for plugin in model_plugins(description):
        model_build = MODEL_PLUGINS.get(plugin.filename)
        if model_build is not None:
            built = model_build(model, plugin, robot, plugin.namespace(namespace, model), limits)
            if built is not None:
                out.append(built)
    return out
