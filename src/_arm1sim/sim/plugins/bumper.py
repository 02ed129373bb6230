"""gazebo_ros_bumper in a ``contact`` sensor, with upstream's parameters and defaults
(gazebo_plugins/src/gazebo_ros_bumper.cpp)."""

from __future__ import annotations

import logging
from typing import Optional

from ...description.gazebo_plugins import PluginSpec, SensorSpec, topic
from ...description.limits import Limits
from ...physics.contact import ContactSensor
from ...physics.robot import Robot
from .common import not_loaded, rate, sensor_frame
from .registry import PluginType, register

log = logging.getLogger('_arm1sim.physics')


def build_bumper(
    model: str, sensor: SensorSpec, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[ContactSensor]:
    """gazebo_ros_bumper in a ``contact`` sensor."""
    if sensor.type != 'contact':
        not_loaded(model, plugin, "its sensor is of type '%s', not contact" % sensor.type)
        return None
    index, _ = sensor_frame(robot, sensor)
    collision = (sensor.element.findtext('contact/collision') or '').strip()
    if not collision:
        log.warning(
            "model '%s': %s has no <contact><collision>: it reports no contacts, as in Gazebo",
            model,
            sensor.where,
        )
    contact = ContactSensor(
        model,
        sensor.name,
        robot,
        index,
        '%s::%s::%s' % (model, _owner(robot, sensor.link), collision),
        rate(limits, sensor.update_rate, sensor.where),
    )
    contact.enabled = bool(collision)
    contact.topic = topic(ns, plugin.text('bumperTopicName', 'bumper_states'))
    contact.frame_id = plugin.text('frameName', 'world')
    contact.namespace = ns
    return contact


def _owner(robot: Robot, link: str) -> str:
    """The link a (possibly lumped) link's sensors belong to in Gazebo's model."""
    lumped = robot.lumped_link(link)
    return link if lumped is None else str(lumped[0])


register(
    PluginType(
        'libgazebo_ros_bumper.so',
        build_sensor=build_bumper,
        publisher='state_sensor_plugins:bumper_publisher',
    )
)
