"""What the plugin builders share: upstream's "not loaded" warning, rates within the world's
limits, vectors, and the link frames a plugin names (a link merged into its parent by
fixed-joint lumping lives on in the parent at an offset).

A plugin missing a parameter upstream requires, or naming a link or joint the model lacks,
does not load in Gazebo (ROS_FATAL, the model spawns without it): here too, with a warning
naming it (``not_loaded``)."""

from __future__ import annotations

import logging
from typing import Optional, Tuple

from ...description.gazebo_plugins import PluginSpec, SensorSpec
from ...description.limits import Limits
from ...description.sdf_values import vector3
from ...description.urdf_model import UrdfError
from ...physics.link_motion import Frame, compose, quaternion_from_rpy
from ...physics.robot import Robot

log = logging.getLogger('_arm1sim.physics')


def not_loaded(model: str, plugin: PluginSpec, why: str) -> None:
    log.warning("model '%s': %s is not loaded, as in Gazebo: %s", model, plugin.where, why)


def vector(plugin: PluginSpec, tag: str) -> Tuple[float, float, float]:
    text = plugin.text(tag)
    values = vector3(text)
    if values is None:
        raise UrdfError('%s <%s>: %r is not 3 numbers' % (plugin.where, tag, text))
    return values


def rate(limits: Limits, value: float, where: str) -> float:
    """A rate in Hz, within the world's limit for one sensor (0 or less: every step)."""
    limits.check('sensor_update_rate', value, where)
    return value


def plugin_rate(limits: Limits, plugin: PluginSpec) -> float:
    """The plugin's ``<updateRate>`` (absent: 0, every step), within the limit."""
    return rate(limits, plugin.number('updateRate', 0.0), plugin.where)


def has(plugin: PluginSpec, tag: str) -> bool:
    return plugin.element.find(tag) is not None


def link_frame(robot: Robot, name: str) -> Optional[Tuple[int, Frame]]:
    """The pybullet link carrying ``name``'s frame and the frame's offset in it (a link merged
    into its parent by fixed-joint lumping lives on in the parent at an offset); None for a
    name the model does not have."""
    try:
        index, offset = robot.frame(name)
    except KeyError:
        return None
    return index, (tuple(offset[0]), tuple(offset[1]))


def sensor_frame(robot: Robot, sensor: SensorSpec) -> Tuple[int, Frame]:
    found = link_frame(robot, sensor.link)
    if found is None:
        raise UrdfError('%s: the link is not in the model' % sensor.where)
    index, offset = found
    x, y, z, roll, pitch, yaw = sensor.pose
    return index, compose(offset, ((x, y, z), quaternion_from_rpy((roll, pitch, yaw))))


def body_frame(model: str, plugin: PluginSpec, robot: Robot) -> Optional[Tuple[int, Frame]]:
    """The link ``<bodyName>`` names, or None after a warning (Gazebo does not load it)."""
    if not has(plugin, 'bodyName'):
        not_loaded(model, plugin, 'missing <bodyName>')
        return None
    body = plugin.text('bodyName')
    found = link_frame(robot, body)
    if found is None:
        not_loaded(model, plugin, "bodyName '%s' is not a link of the model" % body)
    return found
