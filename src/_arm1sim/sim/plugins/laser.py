"""gazebo_ros_laser (in a ``ray`` sensor) and gazebo_ros_gpu_laser (``gpu_ray``): the
physics.laser.Laser that casts the rays, with the plugin's parameters
(description.ray_sensor)."""

from __future__ import annotations

import logging
from typing import Optional, Tuple

from ...description.gazebo_plugins import PluginSpec, SensorSpec, topic
from ...description.limits import Limits
from ...description.ray_sensor import PLUGIN_SENSOR_TYPE, laser_plugin
from ...description.ray_sensor import ray_spec as parse_ray_spec
from ...description.urdf_model import UrdfError
from ...physics.laser import Laser
from ...physics.link_motion import Frame
from ...physics.robot import Robot
from ...physics.sim_sensor import compose, pose_of
from .registry import PluginType, register

log = logging.getLogger('_arm1sim.physics')


def _sensor_link(robot: Robot, sensor: SensorSpec) -> Optional[Tuple[str, Frame]]:
    """The pybullet link carrying the sensor's link frame and its offset there (a link merged
    into its parent by fixed-joint lumping lives on in the parent)."""
    if sensor.link in robot.link_index:
        return sensor.link, ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    resolve = getattr(robot, 'lumped_link', None)
    found = resolve(sensor.link) if resolve is not None else None
    if found is None:
        return None
    parent, offset = found
    return parent, (tuple(offset[0]), tuple(offset[1]))


def build_laser(
    model: str, sensor: SensorSpec, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[Laser]:
    """gazebo_ros_laser (ray) or gazebo_ros_gpu_laser (gpu_ray). A plugin in a sensor of the
    other type does not load in Gazebo (its Load throws): warned and left out here too."""
    wanted_type = PLUGIN_SENSOR_TYPE.get(plugin.filename, 'ray')
    if sensor.type != wanted_type:
        log.warning(
            "model '%s': %s is not loaded, as in Gazebo: it needs a sensor of type '%s', not '%s'",
            model,
            plugin.where,
            wanted_type,
            sensor.type,
        )
        return None
    spec = parse_ray_spec(sensor, limits)
    found = _sensor_link(robot, sensor)
    if found is None:
        raise UrdfError('%s: the link is not in the model' % sensor.where)
    link, offset = found
    laser = Laser(
        model,
        sensor.name,
        robot,
        link,
        compose(offset, pose_of(sensor.pose)),
        spec,
        sensor.update_rate,
    )
    laser.sensor_type = sensor.type
    laser.plugin = laser_plugin(plugin, ns)
    name = laser.plugin.topic_name
    laser.topic = topic(laser.plugin.namespace, name) if name else ''
    if spec.vertical_range_count > 1:
        log.warning(
            "model '%s': %s has %d vertical layers: its LaserScan carries all of them one after "
            'another (%d ranges) with one layer\'s angles, as gazebo_ros_laser publishes them',
            model,
            sensor.where,
            spec.vertical_range_count,
            spec.vertical_range_count * spec.range_count,
        )
    return laser


register(
    *(
        PluginType(name, build_sensor=build_laser, publisher='laser_plugin:laser_publisher')
        for name in ('libgazebo_ros_laser.so', 'libgazebo_ros_gpu_laser.so')
    )
)
