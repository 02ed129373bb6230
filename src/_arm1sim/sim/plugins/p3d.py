"""gazebo_ros_p3d, a model plugin, with upstream's parameters and defaults
(gazebo_plugins/src/gazebo_ros_p3d.cpp)."""

from __future__ import annotations

from typing import Optional, Tuple

from ...description.gazebo_plugins import PluginSpec, topic
from ...description.limits import Limits
from ...physics.link_motion import Frame
from ...physics.p3d import WORLD_FRAMES, P3d
from ...physics.robot import Robot
from .common import body_frame, has, link_frame, not_loaded, plugin_rate, vector
from .registry import PluginType, register


def build_p3d(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[P3d]:
    """gazebo_ros_p3d. ``<xyzOffsets>``/``<rpyOffsets>`` (plural, a tutorial typo) are not its
    parameters: ignored, as upstream."""
    body = plugin.text('bodyName')
    found = body_frame(model, plugin, robot)
    if found is None:
        return None
    if not has(plugin, 'topicName'):
        not_loaded(model, plugin, 'missing <topicName>')
        return None
    frame_name = plugin.text('frameName', 'world')
    frame: Optional[Tuple[int, Frame]] = None
    if frame_name not in WORLD_FRAMES:
        frame = link_frame(robot, frame_name)
        if frame is None:
            not_loaded(model, plugin, "frameName '%s' is not a link of the model" % frame_name)
            return None
    sensor = P3d(
        model,
        plugin.name,
        robot,
        *found,
        plugin_rate(limits, plugin),
        None if frame is None else frame[0],
        None if frame is None else frame[1],
        vector(plugin, 'xyzOffset'),
        vector(plugin, 'rpyOffset'),
        plugin.number('gaussianNoise', 0.0),
    )
    sensor.topic = topic(ns, plugin.text('topicName'))
    sensor.frame_id = frame_name
    sensor.namespace = ns
    sensor.child_frame_id = body
    return sensor


register(
    PluginType(
        'libgazebo_ros_p3d.so',
        build_model=build_p3d,
        publisher='state_sensor_plugins:p3d_publisher',
    )
)
