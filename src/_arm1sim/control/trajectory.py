"""Joint trajectories as joint_trajectory_controller builds and samples them, ROS-free.

Each joint has its own list of segments (times in seconds of the controller's uptime).
A segment is a polynomial between two states; its order is set by what *both* end
points carry: positions only -> linear, + velocities -> cubic, + accelerations ->
quintic (upstream's QuinticSplineSegment). Sampling before a segment gives its start
position at rest, after it its end position at rest.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass, field
from typing import Any, List, Optional, Sequence, Tuple

from .angles import shortest_angular_distance


@dataclass
class State:
    """A joint's position with, optionally, velocity and acceleration (None: not given)."""

    position: float
    velocity: Optional[float] = None
    acceleration: Optional[float] = None

    def order(self) -> int:
        """0: position only, 1: with velocity, 2: with velocity and acceleration."""
        if self.velocity is None:
            return 0
        return 1 if self.acceleration is None else 2


@dataclass
class Tolerance:
    """A StateTolerance of upstream: 0 means unchecked."""

    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0

    def holds(
        self, position_error: float, velocity_error: float, acceleration_error: float = 0.0
    ) -> bool:
        return not (
            (self.position > 0 and abs(position_error) > self.position)
            or (self.velocity > 0 and abs(velocity_error) > self.velocity)
            or (self.acceleration > 0 and abs(acceleration_error) > self.acceleration)
        )


@dataclass
class Tolerances:
    """One joint's tolerances for the segments of one goal."""

    path: Tolerance = field(default_factory=Tolerance)
    goal: Tolerance = field(default_factory=Tolerance)
    goal_time: float = 0.0


class Segment:
    """p(t) = sum c_k (t - start)^k between ``start`` and ``end`` (seconds of uptime)."""

    __slots__ = ('start', 'end', 'coefs', 'goal', 'tolerances', 'start_point_time')

    def __init__(
        self,
        start: float,
        start_state: State,
        end: float,
        end_state: State,
        goal: Any = None,
        tolerances: Optional[Tolerances] = None,
    ) -> None:
        if not (math.isfinite(start) and math.isfinite(end)) or end < start:
            raise ValueError('segment end %r before its start %r' % (end, start))
        self.start, self.end = start, end
        self.goal = goal  # the goal handle this segment executes (None: no goal)
        self.tolerances = tolerances or Tolerances()
        self.start_point_time = start  # time_from_start of the waypoint it starts at (uptime)
        self.coefs = spline_coefficients(start_state, end_state, end - start)

    def sample(self, t: float) -> Tuple[float, float, float]:
        """(position, velocity, acceleration) at uptime ``t``, at rest outside the segment."""
        c = self.coefs
        if t < self.start:
            return c[0], 0.0, 0.0
        if t > self.end:
            p, _, _ = _poly(c, self.end - self.start)
            return p, 0.0, 0.0
        return _poly(c, t - self.start)


def _poly(c: Sequence[float], x: float) -> Tuple[float, float, float]:
    p = ((((c[5] * x + c[4]) * x + c[3]) * x + c[2]) * x + c[1]) * x + c[0]
    v = (((5 * c[5] * x + 4 * c[4]) * x + 3 * c[3]) * x + 2 * c[2]) * x + c[1]
    a = ((20 * c[5] * x + 12 * c[4]) * x + 6 * c[3]) * x + 2 * c[2]
    return p, v, a


def spline_coefficients(s0: State, s1: State, T: float) -> List[float]:
    """Coefficients c0..c5 of the lowest-order spline both states allow."""
    p0, p1 = s0.position, s1.position
    if T == 0.0:
        return [p1, 0.0, 0.0, 0.0, 0.0, 0.0]  # a zero-length segment is its end point
    order = min(s0.order(), s1.order())
    if order == 0:
        return [p0, (p1 - p0) / T, 0.0, 0.0, 0.0, 0.0]
    v0, v1 = s0.velocity or 0.0, s1.velocity or 0.0
    if order == 1:
        return [
            p0,
            v0,
            (3 * (p1 - p0) - (2 * v0 + v1) * T) / T**2,
            (2 * (p0 - p1) + (v0 + v1) * T) / T**3,
            0.0,
            0.0,
        ]
    a0, a1 = s0.acceleration or 0.0, s1.acceleration or 0.0
    return [
        p0,
        v0,
        a0 / 2,
        (20 * (p1 - p0) - (8 * v1 + 12 * v0) * T - (3 * a0 - a1) * T**2) / (2 * T**3),
        (30 * (p0 - p1) + (14 * v1 + 16 * v0) * T + (3 * a0 - 2 * a1) * T**2) / (2 * T**4),
        (12 * (p1 - p0) - (6 * v1 + 6 * v0) * T - (a0 - a1) * T**2) / (2 * T**5),
    ]


JointTrajectory = List[Segment]  # one joint's segments, in time order


def find_segment(traj: JointTrajectory, t: float) -> int:
    """Index of the segment active at ``t``: the last one starting at or before it (the
    first one before the trajectory starts); -1 for an empty trajectory. A binary search
    (upstream's std::upper_bound): a 100 000-point trajectory costs ~17 comparisons a step."""
    if not traj:
        return -1
    return max(bisect_right(traj, t, key=_start) - 1, 0)


def _start(segment: Segment) -> float:
    return segment.start


def sample(traj: JointTrajectory, t: float) -> Tuple[int, Tuple[float, float, float]]:
    k = find_segment(traj, t)
    if k < 0:
        raise ValueError('no trajectory')
    return k, traj[k].sample(t)


def hold_segment(
    t: float, position: float, velocity: float = 0.0, stop_duration: float = 0.0
) -> Segment:
    """The hold of upstream's setHoldPosition: at ``position`` from ``t`` on; with a stop
    duration, a quintic from (position, velocity) reaching rest after it (the midpoint of a
    symmetric spline to (position, -velocity) over twice the duration)."""
    if stop_duration <= 0.0:
        return Segment(t, State(position), t, State(position))
    full = Segment(
        t, State(position, velocity, 0.0), t + 2 * stop_duration, State(position, -velocity, 0.0)
    )
    p_mid, _, _ = full.sample(t + stop_duration)
    return Segment(t, State(position, velocity, 0.0), t + stop_duration, State(p_mid, 0.0, 0.0))


def wrap_offset(first_position: float, current: float) -> float:
    """The multiple of 2*pi that brings a continuous joint's new trajectory (its first point
    at ``first_position``) within +-pi of ``current``."""
    target = current + shortest_angular_distance(current, first_position)
    return target - first_position
