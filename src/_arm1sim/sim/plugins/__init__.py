"""The Gazebo plugins a robot brings (gazebo_plugins and friends), one module each, registered
by file name in ``registry.PLUGINS``. Adding one: a module here that builds it and calls
``register``, its import below, and its ROS publisher in ``ros/plugins/``."""

from . import bumper, camera, diff_drive, ft_sensor, grasp, imu, laser, mimic, p3d  # noqa: F401
from .registry import PLUGINS, PluginType, build_sensors, register

__all__ = ['PLUGINS', 'PluginType', 'build_sensors', 'register']
