"""Cameras: Gazebo's ``<sensor type="camera">`` + gazebo_ros_camera, rendered by pybullet.

The parts live apart: camera_sensor (what a description declares, its limits
and optics), render_process (the child processes that render frames) and
sensor_manager (when frames are taken: by default physics never waits for
rendering; ``lockstep`` waits for every frame). The names are gathered here
for the code that imports them from ``physics.camera``.
"""
from .camera_sensor import (CAMERA_PLUGIN, ENCODINGS, CameraSensor, camera_sensors,  # noqa: F401
                            intrinsics, projection_matrix, sensor_pose, view_matrix)
from .render_process import (RENDER_TIMEOUT, RenderError, RenderProcess, encode,  # noqa: F401
                             render, render_process_main)
from .sensor_manager import (Camera, SensorManager, charged_rate,  # noqa: F401
                             default_render_processes)
