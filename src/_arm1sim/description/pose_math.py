"""Quaternion (x, y, z, w) and roll-pitch-yaw math, pure Python: no ROS, no pybullet.

In description/, the lowest layer that needs it, so that physics/, sim/ and ros/ share it.
"""

from __future__ import annotations

import math
from typing import Sequence, Tuple

Vec = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]


def multiply(a: Sequence[float], b: Sequence[float]) -> Quat:
    """The rotation a∘b (b first, then a)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def conjugate(q: Sequence[float]) -> Quat:
    """The inverse of a unit quaternion."""
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Sequence[float], v: Sequence[float]) -> Vec:
    """v turned by q (q v q*)."""
    x, y, z, _ = multiply(multiply(q, (v[0], v[1], v[2], 0.0)), conjugate(q))
    return (x, y, z)


def normalized(q: Sequence[float]) -> Quat:
    """``q`` scaled to unit length. Scaled by its largest component first, so that neither
    huge (1e200: the squares overflow to inf) nor tiny components (the squares underflow to
    0) turn into NaN or identity; all-zero becomes identity, as upstream."""
    big = max(abs(c) for c in q)
    if big == 0:
        return (0.0, 0.0, 0.0, 1.0)
    s = [c / big for c in q]
    n = math.sqrt(sum(c * c for c in s))
    return (s[0] / n, s[1] / n, s[2] / n, s[3] / n)


def quat_from_rpy(roll: float, pitch: float, yaw: float) -> Quat:
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def rpy_from_quat(q: Sequence[float]) -> Vec:
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return (roll, pitch, yaw)
