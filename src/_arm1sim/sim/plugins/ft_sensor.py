"""gazebo_ros_ft_sensor, a model plugin, with upstream's parameters and defaults
(gazebo_plugins/src/gazebo_ros_ft_sensor.cpp). Unlike Gazebo, its joint needs no
``<provideFeedback>``."""

from __future__ import annotations

from typing import Optional

from ...description.gazebo_plugins import PluginSpec, topic
from ...description.limits import Limits
from ...physics.force_torque import ForceTorque
from ...physics.robot import Robot
from .common import has, not_loaded, plugin_rate
from .registry import PluginType, register


def build_ft_sensor(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[ForceTorque]:
    """gazebo_ros_ft_sensor: the wrench in the joint's child link frame."""
    joint = plugin.text('jointName')
    if not has(plugin, 'jointName'):
        not_loaded(model, plugin, 'missing <jointName>')
        return None
    if joint not in robot.joint_index:
        not_loaded(model, plugin, "jointName '%s' is not a joint of the model" % joint)
        return None
    if not has(plugin, 'topicName'):
        not_loaded(model, plugin, 'missing <topicName>')
        return None
    # upstream reads gaussianNoise from the plugin element itself
    sensor = ForceTorque(
        model,
        plugin.name,
        robot,
        robot.joint_index[joint],
        plugin_rate(limits, plugin),
        plugin.number('gaussianNoise', 0.0),
    )
    sensor.topic = topic(ns, plugin.text('topicName'))
    sensor.frame_id = _child_link(robot, sensor.joint)
    sensor.namespace = ns
    return sensor


def _child_link(robot: Robot, joint: int) -> str:
    for name, index in robot.link_index.items():
        if index == joint:
            return name
    return ''


register(
    PluginType(
        'libgazebo_ros_ft_sensor.so',
        build_model=build_ft_sensor,
        publisher='state_sensor_plugins:ft_publisher',
    )
)
