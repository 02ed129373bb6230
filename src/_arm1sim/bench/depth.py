"""What one depth camera frame costs: a 640 x 480 gazebo_ros_openni_kinect frame of a wall and
the ground, made as the world makes it, every part timed in one process (no master needed).

Parts: rendering (the render process's backend, ``ARM1_RENDERER`` or the default, RGB and
depth buffer to metres and bytes), then on the plugin's publishing thread the depth image
(32FC1) and the point cloud (x y z rgb) with their serialization. Off the physics thread all;
the sum is the CPU a subscribed depth camera takes per frame.
"""

from __future__ import annotations

import io
import os
import tempfile
from typing import Any, Dict

from ..description.camera_sensor import OPENNI_KINECT_PLUGIN, CameraSensor
from ..description.sdf_world import WorldConfig
from ..physics import depth_camera, renderers
from ..physics.render_process import render
from .probes import median_ms

WALL_URDF = """<robot name="wall">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="wall"/>
    <origin xyz="2.5 0 1"/></joint>
  <link name="wall">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><box size="0.2 2 2"/></geometry></visual>
  </link>
</robot>
"""
CAMERA_POSE = ((0.0, 0.0, 0.8), (0.0, 0.0871557, 0.0, 0.9961947))  # 10 degrees down at the wall


def sensor(width: int = 640, height: int = 480) -> CameraSensor:
    return CameraSensor(
        'bench',
        'camera_link',
        width=width,
        height=height,
        near=0.05,
        far=8.0,
        depth_plugin=OPENNI_KINECT_PLUGIN,
        frame_name='camera_link_optical',
    )


def depth_frame(count: int = 60) -> Dict[str, Any]:
    """Median milliseconds over ``count`` frames of each part, and their sum."""
    from ..ros.plugins.depth_camera_plugin import (
        depth_image_message,
        point_cloud_message,
        point_fields,
    )

    s = sensor()
    backend = renderers.open_backend()
    world = backend.open_world(WorldConfig())
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, 'wall.urdf')
        with open(path, 'w') as f:
            f.write(WALL_URDF)
        world.load_robot(path, (0, 0, 0), (0, 0, 0, 1), True)
        try:
            frame = render(world.client, s, *CAMERA_POSE, backend)
            image, depth = depth_camera.split_frame(s, frame)
            render_ms = median_ms(lambda: render(world.client, s, *CAMERA_POSE, backend), count)
        finally:
            backend.close()
            world.close()

    def depth_image() -> None:
        depth_image_message(s, depth).serialize(io.BytesIO())

    fields = point_fields()
    cloud = depth_camera.PointCloudBuilder(s)

    def points() -> None:
        point_cloud_message(s, fields, cloud, depth, image).serialize(io.BytesIO())

    depth_ms = median_ms(depth_image, count)
    points_ms = median_ms(points, count)
    return {
        'frame_ms': render_ms + depth_ms + points_ms,
        'render_ms': render_ms,
        'depth_image_ms': depth_ms,
        'point_cloud_ms': points_ms,
        'renderer': backend.name,  # a label in the raw results
    }
