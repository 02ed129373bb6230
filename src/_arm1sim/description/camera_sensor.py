"""Camera sensors as a description declares them: Gazebo's ``<sensor type="camera">`` with
gazebo_ros_camera, ``<sensor type="depth">`` (or ``camera``, as tutorials write it) with
gazebo_ros_openni_kinect or gazebo_ros_depth_camera, the limits a spawned camera must keep, and
the camera's optics.

ROS-free and render-free: what is parsed here is handed to the sensor manager
(physics.sensor_manager) and, pickled, to the render processes (physics.render_process).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any, List, Optional

from .limits import Limits
from .names import legal_ros_name, shown
from .sdf_values import number
from .urdf_model import RobotModel, UrdfError

log = logging.getLogger('_arm1sim.physics')

CAMERA_PLUGIN = 'libgazebo_ros_camera.so'
OPENNI_KINECT_PLUGIN = 'libgazebo_ros_openni_kinect.so'
DEPTH_CAMERA_PLUGIN = 'libgazebo_ros_depth_camera.so'
DEPTH_PLUGINS = (OPENNI_KINECT_PLUGIN, DEPTH_CAMERA_PLUGIN)
# SDF <image><format> -> (sensor_msgs encoding, bytes per pixel)
ENCODINGS = {'R8G8B8': ('rgb8', 3), 'B8G8R8': ('bgr8', 3), 'L8': ('mono8', 1)}


@dataclass
class CameraSensor:
    """One camera as the description declares it; defaults are SDF's and gazebo_ros_camera's."""

    name: str
    link: str
    update_rate: float = 0.0  # Hz in sim time; 0: as fast as the renderer goes
    horizontal_fov: float = 1.047
    width: int = 320
    height: int = 240
    format: str = 'R8G8B8'
    near: float = 0.1
    far: float = 100.0
    pose: tuple = (0.0,) * 6  # of the sensor in its link's frame
    camera_name: str = ''
    image_topic_name: str = 'image_raw'
    camera_info_topic_name: str = 'camera_info'
    frame_name: str = 'world'
    robot_namespace: str = ''
    # A depth camera's plugin (one of DEPTH_PLUGINS; '' for a plain camera) and its parameters,
    # with gazebo_ros_openni_kinect's defaults. Renders also the depth buffer, in metres.
    depth_plugin: str = ''
    depth_image_topic_name: str = 'depth/image_raw'
    depth_image_camera_info_topic_name: str = 'depth/camera_info'
    point_cloud_topic_name: str = 'points'
    point_cloud_cutoff: float = 0.4
    point_cloud_cutoff_max: float = 5.0  # gazebo_ros_depth_camera has none: inf
    use_depth_16uc1: bool = False  # openni_kinect's useDepth16UC1Format: millimetres, 0 outside

    @property
    def plugin_filename(self) -> str:
        """The plugin that publishes it (sim/plugins' registry key)."""
        return self.depth_plugin or CAMERA_PLUGIN

    @property
    def encoding(self) -> str:
        return ENCODINGS[self.format][0]

    @property
    def step(self) -> int:
        """Bytes per image row."""
        return self.width * ENCODINGS[self.format][1]

    @property
    def pixels(self) -> int:
        return self.width * self.height

    @property
    def image_bytes(self) -> int:
        """Bytes of the image in a frame: ``step`` per row."""
        return self.step * self.height

    @property
    def frame_bytes(self) -> int:
        """Bytes of a rendered frame: the image, then for a depth camera the depth in metres
        (float32, native byte order, row-major, top row first)."""
        return self.image_bytes + (4 * self.pixels if self.depth_plugin else 0)

    def topic(self, name: str) -> str:
        """``/<robotNamespace>/<cameraName>/<name>``, as gazebo_ros_camera advertises it."""
        if name.startswith('/'):
            return name
        parts = [s.strip('/') for s in (self.robot_namespace, self.camera_name, name)]
        return '/' + '/'.join(s for s in parts if s)

    @property
    def image_topic(self) -> str:
        return self.topic(self.image_topic_name)

    @property
    def camera_info_topic(self) -> str:
        return self.topic(self.camera_info_topic_name)

    @property
    def depth_image_topic(self) -> str:
        return self.topic(self.depth_image_topic_name)

    @property
    def depth_image_camera_info_topic(self) -> str:
        return self.topic(self.depth_image_camera_info_topic_name)

    @property
    def point_cloud_topic(self) -> str:
        return self.topic(self.point_cloud_topic_name)

    def describe(self) -> str:
        rate = '%g Hz' % self.update_rate if self.update_rate > 0 else 'as fast as possible'
        kind = 'depth camera' if self.depth_plugin else 'camera'
        return "%s '%s' (%dx%d at %s)" % (kind, self.name, self.width, self.height, rate)


def _text(plugin: Any, tag: str, default: str) -> str:
    """A plugin parameter's text; an absent or empty element gives the default."""
    return (plugin.findtext(tag) or '').strip() or default


def _depth_parameters(s: CameraSensor, plugin: Any, what: str) -> None:
    """A depth plugin's parameters into ``s``, with gazebo_ros_openni_kinect's defaults
    (gazebo_ros_depth_camera: no max cutoff, no 16UC1)."""
    assert plugin.get('filename') in DEPTH_PLUGINS
    d = CameraSensor(s.name, s.link)
    s.depth_plugin = plugin.get('filename')
    s.depth_image_topic_name = _text(plugin, 'depthImageTopicName', d.depth_image_topic_name)
    s.depth_image_camera_info_topic_name = _text(
        plugin, 'depthImageCameraInfoTopicName', d.depth_image_camera_info_topic_name
    )
    s.point_cloud_topic_name = _text(plugin, 'pointCloudTopicName', d.point_cloud_topic_name)
    s.point_cloud_cutoff = number(plugin, 'pointCloudCutoff', d.point_cloud_cutoff, what)
    if s.depth_plugin == OPENNI_KINECT_PLUGIN:
        s.point_cloud_cutoff_max = number(
            plugin, 'pointCloudCutoffMax', d.point_cloud_cutoff_max, what
        )
        flag = _text(plugin, 'useDepth16UC1Format', 'false').lower()
        if flag not in ('true', '1', 'false', '0'):
            raise UrdfError('%s <useDepth16UC1Format>: %r is not a boolean' % (what, flag))
        s.use_depth_16uc1 = flag in ('true', '1')
    else:
        s.point_cloud_cutoff_max = math.inf


def camera_sensors(description: RobotModel, limits: Optional[Limits] = None) -> List[CameraSensor]:
    """The camera sensors with the gazebo_ros_camera plugin, and the depth cameras (sensor
    type depth, or camera as tutorials write it, with gazebo_ros_openni_kinect or
    gazebo_ros_depth_camera), in a urdf_model.RobotModel.

    Raises UrdfError for what cannot be rendered and limits.LimitError for a camera
    over ``limits`` (camera_pixels, sensor_update_rate); the world's render budget is
    the sensor manager's to check, as it knows the other cameras.
    """
    limits = limits or Limits()
    out = []
    for link, sensor in description.sensors:
        if sensor.get('type') not in ('camera', 'depth'):
            continue
        plugins = sensor.findall('plugin')
        plugin = next((pl for pl in plugins if pl.get('filename') in DEPTH_PLUGINS), None)
        if plugin is None:  # a depth sensor is a camera sensor too, for gazebo_ros_camera
            plugin = next((pl for pl in plugins if pl.get('filename') == CAMERA_PLUGIN), None)
        if plugin is None:
            continue
        depth_plugin = plugin.get('filename') if plugin.get('filename') in DEPTH_PLUGINS else ''
        name = sensor.get('name', 'camera')
        what = "sensor '%s' on link '%s'" % (name, link)
        if link not in description.links:
            raise UrdfError('%s: the link is not in the URDF' % what)
        cam = sensor.find('camera')
        if cam is None:
            raise UrdfError('%s has no <camera>' % what)
        pose_text = (sensor.findtext('pose') or '').split()
        try:
            pose = tuple(float(v) for v in pose_text) if pose_text else CameraSensor.pose
        except ValueError:
            pose = ()
        if pose_text and (len(pose) != 6 or not all(math.isfinite(v) for v in pose)):
            raise UrdfError('%s <pose>: %r is not 6 numbers' % (what, sensor.findtext('pose')))
        d = CameraSensor(name, link)
        if depth_plugin:  # the depth plugins' own defaults
            d.image_topic_name, d.camera_info_topic_name = 'ir/image_raw', 'ir/camera_info'
        s = CameraSensor(
            name,
            link,
            update_rate=number(sensor, 'update_rate', d.update_rate, what),
            horizontal_fov=number(cam, 'horizontal_fov', d.horizontal_fov, what),
            width=int(number(cam, 'image/width', d.width, what, int)),
            height=int(number(cam, 'image/height', d.height, what, int)),
            format=(cam.findtext('image/format') or d.format).strip(),
            near=number(cam, 'clip/near', d.near, what),
            far=number(cam, 'clip/far', d.far, what),
            pose=pose,
            camera_name=(plugin.findtext('cameraName') or '').strip(),
            image_topic_name=(plugin.findtext('imageTopicName') or d.image_topic_name).strip(),
            camera_info_topic_name=(
                plugin.findtext('cameraInfoTopicName') or d.camera_info_topic_name
            ).strip(),
            frame_name=(plugin.findtext('frameName') or d.frame_name).strip(),
            robot_namespace=(plugin.findtext('robotNamespace') or '').strip(),
        )
        if depth_plugin:
            _depth_parameters(s, plugin, what)
        if s.update_rate < 0:
            raise UrdfError(
                '%s <update_rate>: %g Hz is negative (0 means as fast as possible)'
                % (what, s.update_rate)
            )
        # The plugin's own <updateRate> throttles what the sensor produces.
        throttle = number(plugin, 'updateRate', 0.0, what)
        if throttle > 0:
            s.update_rate = min(s.update_rate, throttle) if s.update_rate > 0 else throttle
        if s.width <= 0 or s.height <= 0 or not 0 < s.horizontal_fov < math.pi:
            raise UrdfError(
                '%s: image %dx%d with horizontal_fov %g cannot be rendered'
                % (what, s.width, s.height, s.horizontal_fov)
            )
        if not 0 < s.near < s.far:
            raise UrdfError(
                '%s: clip near %g and far %g cannot be rendered (0 < near < far)'
                % (what, s.near, s.far)
            )
        limits.check('camera_pixels', s.pixels, '%s (%dx%d)' % (what, s.width, s.height))
        limits.check('sensor_update_rate', s.update_rate, what)
        if s.format not in ENCODINGS:
            log.warning(
                '%s: image format %s is not supported, rendering R8G8B8 (rgb8)', what, s.format
            )
            s.format = 'R8G8B8'
        topics = [s.image_topic, s.camera_info_topic]
        if s.depth_plugin:
            topics += [s.depth_image_topic, s.depth_image_camera_info_topic, s.point_cloud_topic]
        for name in topics:  # rospy would log FATAL and publish nothing, the spawn a success
            if not legal_ros_name(name):
                raise UrdfError('%s: topic %s is not a legal ROS name' % (what, shown(name)))
        out.append(s)
    return out
