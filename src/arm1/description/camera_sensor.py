"""Camera sensors as a description declares them: Gazebo's ``<sensor type="camera">`` with
gazebo_ros_camera, the limits a spawned camera must keep, and the camera's optics.

ROS-free and render-free: what is parsed here is handed to the sensor manager
(physics.sensor_manager) and, pickled, to the render processes (physics.render_process).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any, Callable, List, Optional

from .limits import Limits
from .urdf_model import RobotModel, UrdfError

log = logging.getLogger('arm1.physics')

CAMERA_PLUGIN = 'libgazebo_ros_camera.so'
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

    def describe(self) -> str:
        rate = '%g Hz' % self.update_rate if self.update_rate > 0 else 'as fast as possible'
        return "camera '%s' (%dx%d at %s)" % (self.name, self.width, self.height, rate)


def _number(
    element: Any, path: str, default: float, what: str, kind: Callable[[str], float] = float
) -> float:
    text = element.findtext(path)
    if text is None or not text.strip():
        return default
    try:
        value = kind(text.strip())
    except ValueError:
        raise UrdfError('%s <%s>: %r is not a number' % (what, path, text))
    if not math.isfinite(value):
        raise UrdfError('%s <%s>: %r is not a finite number' % (what, path, text))
    return value


def camera_sensors(description: RobotModel, limits: Optional[Limits] = None) -> List[CameraSensor]:
    """The camera sensors with the gazebo_ros_camera plugin in a urdf_model.RobotModel.

    Raises UrdfError for what cannot be rendered and limits.LimitError for a camera
    over ``limits`` (camera_pixels, sensor_update_rate); the world's render budget is
    the sensor manager's to check, as it knows the other cameras.
    """
    limits = limits or Limits()
    out = []
    for link, sensor in description.sensors:
        plugin = next(
            (pl for pl in sensor.findall('plugin') if pl.get('filename') == CAMERA_PLUGIN), None
        )
        if sensor.get('type') != 'camera' or plugin is None:
            continue
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
        s = CameraSensor(
            name,
            link,
            update_rate=_number(sensor, 'update_rate', d.update_rate, what),
            horizontal_fov=_number(cam, 'horizontal_fov', d.horizontal_fov, what),
            width=int(_number(cam, 'image/width', d.width, what, int)),
            height=int(_number(cam, 'image/height', d.height, what, int)),
            format=(cam.findtext('image/format') or d.format).strip(),
            near=_number(cam, 'clip/near', d.near, what),
            far=_number(cam, 'clip/far', d.far, what),
            pose=pose,
            camera_name=(plugin.findtext('cameraName') or '').strip(),
            image_topic_name=(plugin.findtext('imageTopicName') or d.image_topic_name).strip(),
            camera_info_topic_name=(
                plugin.findtext('cameraInfoTopicName') or d.camera_info_topic_name
            ).strip(),
            frame_name=(plugin.findtext('frameName') or d.frame_name).strip(),
            robot_namespace=(plugin.findtext('robotNamespace') or '').strip(),
        )
        if s.update_rate < 0:
            raise UrdfError(
                '%s <update_rate>: %g Hz is negative (0 means as fast as possible)'
                % (what, s.update_rate)
            )
        # The plugin's own <updateRate> throttles what the sensor produces.
        throttle = _number(plugin, 'updateRate', 0.0, what)
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
        out.append(s)
    return out
