"""A depth camera's outputs from a rendered frame, as gazebo_ros_openni_kinect and
gazebo_ros_depth_camera make them: the depth image (32FC1 metres, or 16UC1 millimetres) and
the organised XYZ+RGB point cloud's bytes. ROS-free (plain numpy); ros.depth_camera_plugin wraps
them in messages.

Depth is z-depth (along the optical axis, metres, physics.camera_geometry.depth_metres), +inf
where nothing was drawn. Points are in the optical convention upstream hard-codes (x right, y
down, z forward), whatever frame ``frameName`` names.
"""

from __future__ import annotations

import math
from typing import Any, Tuple

import numpy as np

from ..description.camera_sensor import OPENNI_KINECT_PLUGIN, CameraSensor

POINT_STEP = 32  # PointCloud2Modifier's "xyz" (x 0, y 4, z 8, padded to 16) then "rgb" (16)
RGB_OFFSET = 16
# (name, offset) of the point cloud's fields, all FLOAT32 (sensor_msgs/PointField 7), count 1
POINT_FIELDS = (('x', 0), ('y', 4), ('z', 8), ('rgb', RGB_OFFSET))


def split_frame(sensor: CameraSensor, data: Any) -> Tuple[memoryview, np.ndarray]:
    """A rendered frame's image bytes and its depth (height x width float32 metres)."""
    view = memoryview(data).cast('B')
    if len(view) != sensor.frame_bytes:
        raise ValueError(
            "camera '%s': a frame of %d bytes, not %d"
            % (sensor.name, len(view), sensor.frame_bytes)
        )
    image = view[: sensor.image_bytes]
    depth = np.frombuffer(view[sensor.image_bytes :], np.float32)
    return image, depth.reshape(sensor.height, sensor.width)


def in_range(sensor: CameraSensor, depth: np.ndarray) -> np.ndarray:
    """Where the plugin keeps a depth: beyond pointCloudCutoff and, for openni_kinect, short of
    pointCloudCutoffMax (gazebo_ros_depth_camera has no maximum and keeps +inf)."""
    valid = depth > sensor.point_cloud_cutoff
    if sensor.depth_plugin == OPENNI_KINECT_PLUGIN:
        valid &= depth < sensor.point_cloud_cutoff_max
    return valid


def depth_image(sensor: CameraSensor, depth: np.ndarray) -> Tuple[str, int, bytes]:
    """(encoding, step, data) of the depth image: 32FC1 metres with NaN outside the cutoffs,
    or with useDepth16UC1Format 16UC1 millimetres (truncated, as C++'s cast) with 0 outside."""
    valid = in_range(sensor, depth)
    if sensor.use_depth_16uc1:
        mm = np.where(valid, depth * 1000.0, 0.0)
        return '16UC1', 2 * sensor.width, np.clip(mm, 0, 65535).astype('<u2').tobytes()
    return '32FC1', 4 * sensor.width, np.where(valid, depth, np.nan).astype('<f4').tobytes()


def focal_length(sensor: CameraSensor) -> float:
    """Pixels: width / (2 tan(hfov / 2)), as the plugins compute it."""
    return sensor.width / (2.0 * math.tan(sensor.horizontal_fov / 2.0))


def point_cloud(sensor: CameraSensor, depth: np.ndarray, image: Any) -> Tuple[memoryview, bool]:
    """(data, is_dense) of the organised point cloud, POINT_STEP bytes a point, row-major.

    x = d (i - (W-1)/2) / f, y = d (j - (H-1)/2) / f, z = d for a depth d in range, else
    NaN; rgb: openni_kinect copies the image's first three bytes of each pixel to bytes 16,
    17, 18 (which readers of the packed float take as blue, green, red: with rgb8 red and
    blue swap, gazebo_ros_pkgs#484); gazebo_ros_depth_camera packs them as PCL does (blue
    first, alpha 255). A mono image's byte goes to all three.
    """
    return PointCloudBuilder(sensor).build(depth, image)


class PointCloudBuilder:
    """``point_cloud`` for one camera, frame after frame: the pixels' directions and the output
    buffer (its padding zeroed once) are kept, so a frame costs a few passes over memory already
    mapped. What ``build`` returns is a view of that buffer, valid until the next build."""

    def __init__(self, sensor: CameraSensor) -> None:
        self.sensor = s = sensor
        h, w = s.height, s.width
        f = focal_length(s)
        u = (np.arange(w) - 0.5 * (w - 1)) / f if w > 1 else np.zeros(1)
        v = (np.arange(h) - 0.5 * (h - 1)) / f if h > 1 else np.zeros(1)
        # x and y of each pixel's point at depth 1
        self.u, self.v = u.astype(np.float32)[None, :], v.astype(np.float32)[:, None]
        self.out = np.zeros((h, w, POINT_STEP // 4), np.float32)
        self.alpha = 0 if s.depth_plugin == OPENNI_KINECT_PLUGIN else 255

    def build(self, depth: np.ndarray, image: Any) -> Tuple[memoryview, bool]:
        s, out = self.sensor, self.out
        h, w = s.height, s.width
        valid = in_range(s, depth)
        d = np.where(valid, depth, np.float32(np.nan))
        with np.errstate(invalid='ignore'):  # inf (depth_camera keeps it) x 0 is NaN, as in C++
            # contiguous products, then one strided copy each: faster than strided products
            out[:, :, 0] = d * self.u
            out[:, :, 1] = d * self.v
        out[:, :, 2] = d
        pixels = np.frombuffer(image, np.uint8)
        if pixels.size == 3 * h * w:
            rgb = pixels.reshape(h, w, 3).astype(np.uint32)
            first, second, third = rgb[:, :, 0], rgb[:, :, 1], rgb[:, :, 2]
        elif pixels.size == h * w:
            first = second = third = pixels.reshape(h, w).astype(np.uint32)
        else:  # no image of 1 or 3 bytes a pixel: black
            first = second = third = np.zeros((h, w), np.uint32)
        if s.depth_plugin != OPENNI_KINECT_PLUGIN:  # PCL's packing: blue in the first byte
            first, third = third, first
        # the four bytes at RGB_OFFSET as one little-endian word
        packed = first | (second << 8) | (third << 16) | np.uint32(self.alpha << 24)
        out.view(np.uint32)[:, :, RGB_OFFSET // 4] = packed
        view = memoryview(out.view(np.uint8).reshape(-1))  # type: ignore[arg-type]
        return view, bool(valid.all())
