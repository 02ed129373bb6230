"""gazebo_ros_camera and the depth camera plugins (gazebo_ros_openni_kinect,
gazebo_ros_depth_camera) in a ``camera`` or ``depth`` sensor.

Parsed on the spawning thread (description.camera_sensor.camera_sensors, in
Simulation.prepare_urdf) and built by physics.sensor_manager, which renders every camera of
the world together in its render processes: no builder of their own here, only their
registration, by which the ROS layer finds their publishers.
"""

from __future__ import annotations

from ...description.camera_sensor import CAMERA_PLUGIN, DEPTH_PLUGINS
from .registry import PluginType, register

BUILT_BY = 'physics.sensor_manager (render processes)'

register(
    PluginType(CAMERA_PLUGIN, built_by=BUILT_BY, publisher='camera_plugin:GazeboRosCamera'),
    *(
        PluginType(name, built_by=BUILT_BY, publisher='depth_camera_plugin:GazeboRosDepthCamera')
        for name in DEPTH_PLUGINS
    ),
)
