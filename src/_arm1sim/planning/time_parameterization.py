"""Timing a path as MoveIt's default planning adapter (AddTimeParameterization, the
iterative parabolic time parameterization) does.

Each segment first gets the least time that keeps every joint within its velocity limit
(times the velocity scaling factor); then, joint by joint, forward and backward passes
stretch segments whose parabolic blend would exceed the acceleration limit (times the
acceleration scaling factor), by at most 10 ms a pass, up to 100 rounds. Velocities are the
mean of the neighbouring segments' and accelerations the blend's. Joints without a limit
get MoveIt's defaults of 1 rad/s and 1 rad/s^2.
"""

from __future__ import annotations

import logging
from typing import List, Optional, Sequence, Tuple

import numpy as np

DEFAULT_VELOCITY = 1.0
DEFAULT_ACCELERATION = 1.0
ROUNDING = 0.01
MAX_ITERATIONS = 100
MAX_TIME_CHANGE = 0.01
GROWTH = 1.01

log = logging.getLogger(__name__)


def _scaling(value: float, what: str) -> float:
    if 0.0 < value <= 1.0:
        return value
    if value != 0.0:
        log.warning(
            'Invalid max_%s_scaling_factor %g specified, defaulting to 1.0 instead.', what, value
        )
    return 1.0


def _grow(dq1: float, dq2: float, dt1: float, dt2: float, a_max: float, first: bool) -> float:
    """Stretch dt1 (first) or dt2 by 1 % steps until the blend's acceleration is within a_max."""
    while True:
        a = 2.0 * (dq2 / dt2 - dq1 / dt1) / (dt1 + dt2)
        if abs(a) <= a_max:
            return dt1 if first else dt2
        if first:
            dt1 *= GROWTH
        else:
            dt2 *= GROWTH


def time_parameterize(
    positions: Sequence[Sequence[float]],
    max_velocity: Sequence[Optional[float]],
    max_acceleration: Sequence[Optional[float]],
    velocity_scaling: float = 1.0,
    acceleration_scaling: float = 1.0,
) -> Tuple[List[float], np.ndarray, np.ndarray]:
    """(time_from_start per point, velocities, accelerations) for the N x J ``positions``."""
    q = np.asarray(positions, dtype=float)
    n = len(q)
    if n == 0:
        return [], np.zeros((0, 0)), np.zeros((0, 0))
    vs = _scaling(velocity_scaling, 'velocity')
    accs = _scaling(acceleration_scaling, 'acceleration')
    v_max = np.array([abs(v) * vs if v else DEFAULT_VELOCITY for v in max_velocity])
    a_max = np.array([abs(a) * accs if a else DEFAULT_ACCELERATION for a in max_acceleration])
    dt = np.zeros(max(n - 1, 0))
    if n > 1:
        dt = np.max(np.abs(np.diff(q, axis=0)) / v_max, axis=1)
    _acceleration_passes(q, dt, a_max)
    times = [0.0]
    for d in dt:
        times.append(times[-1] + float(d))
    vel = np.zeros_like(q)
    acc = np.zeros_like(q)
    if n > 1:
        for i in range(n):
            if i == 0:
                q1, q2, q3, dt1, dt2 = q[1], q[0], q[1], dt[0], dt[0]
            elif i < n - 1:
                q1, q2, q3, dt1, dt2 = q[i - 1], q[i], q[i + 1], dt[i - 1], dt[i]
            else:
                q1, q2, q3, dt1, dt2 = q[i - 1], q[i], q[i - 1], dt[i - 1], dt[i - 1]
            if dt1 == 0.0 or dt2 == 0.0:
                continue
            v1 = (q2 - q1) / dt1
            v2 = (q3 - q2) / dt2
            vel[i] = (v1 + v2) / 2.0
            acc[i] = 2.0 * (v2 - v1) / (dt1 + dt2)
    return times, vel, acc


def _acceleration_passes(q: np.ndarray, dt: np.ndarray, a_max: np.ndarray) -> None:
    n = len(q)
    if n < 2:
        return
    backwards = False
    for _ in range(MAX_ITERATIONS):
        updates = 0
        for j in range(q.shape[1]):
            for _ in range(2):
                for k in range(n - 1):
                    i = (n - 1) - k if backwards else k
                    if i == 0:
                        q1, q2, q3, dt1, dt2 = q[1, j], q[0, j], q[1, j], dt[0], dt[0]
                    elif i < n - 1:
                        q1, q2, q3 = q[i - 1, j], q[i, j], q[i + 1, j]
                        dt1, dt2 = dt[i - 1], dt[i]
                    else:
                        q1, q2, q3, dt1, dt2 = (
                            q[i - 1, j],
                            q[i, j],
                            q[i - 1, j],
                            dt[i - 1],
                            dt[i - 1],
                        )
                    if dt1 == 0.0 or dt2 == 0.0:
                        continue
                    a = 2.0 * ((q3 - q2) / dt2 - (q2 - q1) / dt1) / (dt1 + dt2)
                    if abs(a) > a_max[j] + ROUNDING:
                        if not backwards:
                            dt[i] = min(
                                dt2 + MAX_TIME_CHANGE,
                                _grow(q2 - q1, q3 - q2, dt1, dt2, a_max[j], False),
                            )
                        else:
                            dt[i - 1] = min(
                                dt1 + MAX_TIME_CHANGE,
                                _grow(q2 - q1, q3 - q2, dt1, dt2, a_max[j], True),
                            )
                        updates += 1
                backwards = not backwards
        if updates == 0:
            break
