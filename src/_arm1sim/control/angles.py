"""Angle arithmetic of the ROS ``angles`` package, as the position controllers use it."""

from __future__ import annotations

import math
from typing import Tuple

TWO_PI = 2.0 * math.pi


def normalize_angle(angle: float) -> float:
    """Wrap to [-pi, pi]."""
    a = math.fmod(math.fmod(angle, TWO_PI) + TWO_PI, TWO_PI)
    return a - TWO_PI if a > math.pi else a


def shortest_angular_distance(from_angle: float, to_angle: float) -> float:
    return normalize_angle(to_angle - from_angle)


def two_pi_complement(angle: float) -> float:
    """The same direction reached by turning the other way round."""
    if abs(angle) > TWO_PI:
        angle = math.fmod(angle, TWO_PI)
    if angle < 0:
        return TWO_PI + angle
    if angle > 0:
        return -TWO_PI + angle
    return TWO_PI


def shortest_angular_distance_with_large_limits(
    from_angle: float, to_angle: float, left_limit: float, right_limit: float
) -> Tuple[float, bool]:
    """Shortest turn from ``from_angle`` to ``to_angle`` that stays inside the limits.

    Returns ``(distance, ok)``; ``ok`` is False when no turn stays inside, or when
    ``from_angle`` itself is outside them. Limits may span more than 2*pi.
    """
    delta = shortest_angular_distance(from_angle, to_angle)
    delta_2pi = two_pi_complement(delta)
    if abs(delta) > abs(delta_2pi):
        delta, delta_2pi = delta_2pi, delta
    if left_limit > right_limit:
        return delta, False
    inside = left_limit <= from_angle <= right_limit
    for candidate in (delta, delta_2pi):
        if left_limit <= from_angle + candidate <= right_limit:
            return candidate, inside
    return delta, False
