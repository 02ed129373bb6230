"""Camera geometry: a sensor's pose, view and projection matrices, and its pinhole intrinsics."""

from __future__ import annotations

import math
from typing import List, Sequence, Tuple

import numpy as np
import pybullet as p

from ..description.camera_sensor import CameraSensor


def intrinsics(width: int, height: int, horizontal_fov: float) -> Tuple[List[float], List[float]]:
    """CameraInfo's K (3x3) and P (3x4), row-major, of an ideal pinhole with square pixels.

    The principal point is the image centre in ROS's pixel convention (pixel
    centres at integers), i.e. (w - 1) / 2; gazebo_ros_camera puts it at
    (w + 1) / 2, one pixel off the image it renders.
    """
    f = width / (2.0 * math.tan(horizontal_fov / 2.0))
    cx, cy = (width - 1) / 2.0, (height - 1) / 2.0
    return [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0], [
        f,
        0.0,
        cx,
        0.0,
        0.0,
        f,
        cy,
        0.0,
        0.0,
        0.0,
        1.0,
        0.0,
    ]


def sensor_pose(
    sensor: CameraSensor, link_position: Sequence[float], link_orientation: Sequence[float]
) -> Tuple[Sequence[float], Sequence[float]]:
    """World pose of the sensor: its link's pose composed with the sensor's <pose>."""
    return p.multiplyTransforms(
        link_position, link_orientation, sensor.pose[:3], p.getQuaternionFromEuler(sensor.pose[3:])
    )


def view_matrix(position: Sequence[float], orientation: Sequence[float]) -> Sequence[float]:
    """Gazebo's camera looks along its frame's +x with +z up."""
    r = p.getMatrixFromQuaternion(orientation)  # row-major 3x3
    forward, up = (r[0], r[3], r[6]), (r[2], r[5], r[8])
    target = [a + b for a, b in zip(position, forward)]
    return p.computeViewMatrix(position, target, up)


def projection_matrix(sensor: CameraSensor) -> Sequence[float]:
    aspect = sensor.width / float(sensor.height)
    vertical_fov = 2.0 * math.atan(math.tan(sensor.horizontal_fov / 2.0) / aspect)
    return p.computeProjectionMatrixFOV(math.degrees(vertical_fov), aspect, sensor.near, sensor.far)


SKY_DEPTH = 1.0 - 2.0**-22  # window z from which a depth buffer counts as nothing drawn


def depth_metres(buffer: np.ndarray, near: float, far: float) -> np.ndarray:
    """Distance along the optical axis (z-depth, metres, float32) from an OpenGL depth buffer
    (window z in [0, 1], as pybullet's getCameraImage gives it); +inf where nothing was drawn.

    z = far * near / (far - (far - near) * d), the inverse of the perspective projection.
    """
    d = np.asarray(buffer, dtype=np.float32)
    denominator = d * np.float32(near - far)  # float32 throughout: a few ms less at 640x480
    denominator += np.float32(far)
    with np.errstate(divide='ignore'):
        z = np.float32(far * near) / denominator
    # the far plane's clear value: no surface within the clip range (TinyRenderer's sky can
    # read one or two float32 steps under 1)
    z[d >= SKY_DEPTH] = np.inf
    return z
