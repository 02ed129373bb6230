"""gazebo_ros_diff_drive, a model plugin: the physics.diff_drive.DiffDrive that drives the
wheels, with upstream's parameters and defaults (gazebo_plugins/src/gazebo_ros_diff_drive.cpp)."""

from __future__ import annotations

import logging
import math
from typing import Optional

from ...description.gazebo_plugins import PluginSpec, topic
from ...description.limits import Limits
from ...physics.diff_drive import ENCODER, WORLD, DiffDrive
from ...physics.robot import Robot
from .registry import PluginType, register

log = logging.getLogger('_arm1sim.physics')


def build_diff_drive(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[DiffDrive]:
    """gazebo_ros_diff_drive with upstream's defaults. A wheel joint the model lacks stops
    its Load in Gazebo (GazeboRos::getJoint): warned and left out here."""
    wheels = (plugin.text('leftJoint', 'left_joint'), plugin.text('rightJoint', 'right_joint'))
    for tag, joint in zip(('leftJoint', 'rightJoint'), wheels):
        if joint not in robot.joint_index:
            log.warning(
                "model '%s': %s is not loaded, as in Gazebo: %s '%s' is not a joint of the model",
                model,
                plugin.where,
                tag,
                joint,
            )
            return None
    source = plugin.text('odometrySource', WORLD)
    if source not in (ENCODER, WORLD):
        log.warning(
            "model '%s': %s: odometrySource '%s' is neither encoder nor world: world, as upstream",
            model,
            plugin.where,
            source,
        )
        source = WORLD
    sizes = {
        t: plugin.number(t, d) for t, d in (('wheelSeparation', 0.34), ('wheelDiameter', 0.15))
    }
    for tag, value in sizes.items():
        if not (0.0 < value < math.inf):
            # upstream would divide by it: NaN wheel speeds
            log.warning(
                "model '%s': %s is not loaded: <%s> %r must be a positive length",
                model,
                plugin.where,
                tag,
                value,
            )
            return None
    rate = plugin.number('updateRate', 100.0)
    limits.check('sensor_update_rate', rate, plugin.where)
    root = next(n for n, i in robot.link_index.items() if i == -1)
    index, offset = robot.frame(root)
    drive = DiffDrive(
        model,
        plugin.name,
        robot,
        (index, (tuple(offset[0]), tuple(offset[1]))),
        wheels,
        wheel_separation=sizes['wheelSeparation'],
        wheel_diameter=sizes['wheelDiameter'],
        wheel_torque=plugin.number('wheelTorque', 5.0),
        wheel_acceleration=plugin.number('wheelAcceleration', 0.0),
        update_rate=rate,
        odometry_source=source,
        legacy_mode=plugin.flag('legacyMode', True),
    )
    drive.namespace = ns
    drive.command_topic = topic(ns, plugin.text('commandTopic', 'cmd_vel'))
    drive.odometry_topic = topic(ns, plugin.text('odometryTopic', 'odom'))
    drive.odometry_frame = plugin.text('odometryFrame', 'odom')
    drive.robot_base_frame = plugin.text('robotBaseFrame', 'base_footprint')
    drive.publish_tf = plugin.flag('publishTf', True)
    drive.publish_odom_tf = plugin.flag('publishOdomTF', True)
    drive.publish_wheel_tf = plugin.flag('publishWheelTF', False)
    drive.publish_wheel_joint_state = plugin.flag('publishWheelJointState', False)
    return drive


register(
    PluginType(
        'libgazebo_ros_diff_drive.so',
        build_model=build_diff_drive,
        publisher='diff_drive_plugin:diff_drive_plugin',
    )
)
