"""Where a point fixed to a Robot's link is and how it moves, in world axes, as the state
sensors (IMU, p3d, force-torque) read it; plus the small vector helpers they share.

pybullet reports centres of mass; Gazebo's sensors speak of link frames (and of points at an
offset from them): converted here.
"""

from __future__ import annotations

import random
from typing import Sequence, Tuple

import pybullet as p

from ..description.pose_math import conjugate, multiply
from .robot import Robot

Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]
Frame = Tuple[Vec3, Quat]  # position, quaternion xyzw
IDENTITY: Frame = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
# Pose of a point and its twist, all in world axes: position, orientation, velocity, angular
PointState = Tuple[Vec3, Quat, Vec3, Vec3]


def cross(a: Sequence[float], b: Sequence[float]) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def add(a: Sequence[float], b: Sequence[float]) -> Vec3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a: Sequence[float], b: Sequence[float]) -> Vec3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a: Sequence[float], k: float) -> Vec3:
    return (a[0] * k, a[1] * k, a[2] * k)


def rotate(q: Sequence[float], v: Sequence[float]) -> Vec3:
    """v turned by q (R v)."""
    x, y, z, w = q
    # v + 2 w (u x v) + 2 u x (u x v), u the quaternion's vector part
    t = cross((x, y, z), v)
    t = (2 * t[0], 2 * t[1], 2 * t[2])
    u = cross((x, y, z), t)
    return (v[0] + w * t[0] + u[0], v[1] + w * t[1] + u[1], v[2] + w * t[2] + u[2])


def unrotate(q: Sequence[float], v: Sequence[float]) -> Vec3:
    """v in the frame turned by q (Rᵀ v)."""
    return rotate(conjugate(q), v)


def quaternion_from_rpy(rpy: Sequence[float]) -> Quat:
    return tuple(p.getQuaternionFromEuler(list(rpy)))


def compose(a: Frame, b: Frame) -> Frame:
    """Frame b given in frame a, in a's parent (a∘b)."""
    return add(a[0], rotate(a[1], b[0])), multiply(a[1], b[1])


def gaussian(sigma: float) -> float:
    """One sample of N(0, sigma²); 0 when sigma is 0 (the plugins' GaussianKernel)."""
    return random.gauss(0.0, sigma) if sigma else 0.0


def point_state(robot: Robot, index: int, offset: Frame = IDENTITY) -> PointState:
    """World pose of the frame ``offset`` fixed in link ``index``'s frame (-1: the base), and
    the world velocity of its origin and the link's angular velocity, from one pybullet read."""
    cid, body = robot.client, robot.body
    if index == -1:
        com, com_orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
        v_com, w = p.getBaseVelocity(body, physicsClientId=cid)
        frame = compose((tuple(com), tuple(com_orn)), robot._base_from_com)
    else:
        s = p.getLinkState(
            body, index, computeLinkVelocity=1, computeForwardKinematics=1, physicsClientId=cid
        )
        com, v_com, w = s[0], s[6], s[7]
        frame = (tuple(s[4]), tuple(s[5]))
    pos, orn = compose(frame, offset)
    v = add(v_com, cross(w, sub(pos, com)))
    return pos, orn, v, (w[0], w[1], w[2])


def gravity(client: int) -> Vec3:
    """The world's gravity now (set_physics_properties may have changed it)."""
    params = p.getPhysicsEngineParameters(physicsClientId=client)
    return (
        params['gravityAccelerationX'],
        params['gravityAccelerationY'],
        params['gravityAccelerationZ'],
    )
