"""Cartesian paths as MoveIt's compute_cartesian_path answers them.

The link moves from its start pose through each waypoint on straight lines (positions
interpolated linearly, orientations by slerp), in steps of at most ``max_step`` metres and
3.5 * ``max_step`` radians; each step is one IK solution seeded from the previous one (a
single attempt: no random restarts, which would jump). The path stops at the first step
with no valid solution; ``fraction`` is the share of the waypoints followed. With
``jump_threshold`` > 0 (at least 10 steps are taken then), the path is cut before the
first step whose joint-space distance exceeds jump_threshold times the mean step.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
import pybullet as p

from .ik import IkRequest, solve_ik
from .kinematics import RobotKinematics, Vector, quat_to_matrix

MIN_STEPS_FOR_JUMP_THRESH = 10
ROTATION_STEP_FACTOR = 3.5  # MoveIt's MaxEEFStep(step): rotation = 3.5 * translation


@dataclass
class CartesianResult:
    fraction: float
    states: List[Dict[str, float]] = field(default_factory=list)  # group values, start first


def _angle(q1: Vector, q2: Vector) -> float:
    r = quat_to_matrix(q1).T @ quat_to_matrix(q2)
    return float(np.arccos(max(-1.0, min(1.0, (np.trace(r) - 1.0) / 2.0))))


def _slerp(q1: np.ndarray, q2: np.ndarray, t: float) -> np.ndarray:
    d = float(np.dot(q1, q2))
    if d < 0.0:
        q2, d = -q2, -d
    if d > 0.9995:
        out = q1 + t * (q2 - q1)
        return out / np.linalg.norm(out)
    theta = np.arccos(d)
    return (np.sin((1 - t) * theta) * q1 + np.sin(t * theta) * q2) / np.sin(theta)


def _segment(
    robot: RobotKinematics,
    joints: Sequence[str],
    link: str,
    state: Dict[str, float],
    target: Tuple[np.ndarray, np.ndarray],
    max_step: float,
    jump_factor: float,
    valid: Optional[Callable[[Dict[str, float]], bool]],
    timeout: float,
) -> Tuple[float, List[Dict[str, float]]]:
    robot.set_positions(state)
    start_p, start_q = robot.link_pose(link)
    translation_steps = int(np.floor(np.linalg.norm(target[0] - start_p) / max_step))
    rotation_steps = int(np.floor(_angle(start_q, target[1]) / (ROTATION_STEP_FACTOR * max_step)))
    steps = max(translation_steps, rotation_steps) + 1
    if jump_factor > 0 and steps < MIN_STEPS_FOR_JUMP_THRESH:
        steps = MIN_STEPS_FOR_JUMP_THRESH
    out: List[Dict[str, float]] = []
    done = 0.0
    current = dict(state)
    for i in range(1, steps + 1):
        t = i / steps
        pos = t * target[0] + (1 - t) * start_p
        orn = _slerp(np.asarray(start_q), np.asarray(target[1]), t)
        solution = solve_ik(
            robot,
            IkRequest(joints, link, pos, orn, current, timeout=timeout, attempts=1),
            accept=valid,
        )
        if solution is None:
            break
        current.update(solution)
        out.append(dict(current))
        done = t
    return done, out


def cartesian_path(
    robot: RobotKinematics,
    joints: Sequence[str],
    link: str,
    start: Dict[str, float],
    waypoints: Sequence[Tuple[Sequence[float], Sequence[float]]],
    max_step: float,
    jump_threshold: float = 0.0,
    valid: Optional[Callable[[Dict[str, float]], bool]] = None,
    ik_timeout: float = 0.05,
) -> CartesianResult:
    """Waypoints are (position, quaternion) of ``link`` in the model frame."""
    if max_step <= 0:
        raise ValueError('max_step must be > 0')
    states: List[Dict[str, float]] = [dict(start)]
    fraction = 0.0
    for i, (pos, orn) in enumerate(waypoints):
        done, part = _segment(
            robot,
            joints,
            link,
            states[-1],
            (np.asarray(pos, float), np.asarray(orn, float) / np.linalg.norm(orn)),
            max_step,
            0.0,
            valid,
            ik_timeout,
        )
        states += part
        if abs(done - 1.0) < 1e-12:
            fraction = (i + 1) / len(waypoints)
        else:
            fraction += done / len(waypoints)
            break
    if jump_threshold > 0 and len(states) > 1:
        fraction *= _cut_jumps(states, joints, jump_threshold)
    robot.set_positions(start)
    return CartesianResult(fraction, [{j: s[j] for j in joints} for s in states])


def _cut_jumps(states: List[Dict[str, float]], joints: Sequence[str], factor: float) -> float:
    dist = [
        sum(abs(states[i][j] - states[i - 1][j]) for j in joints) for i in range(1, len(states))
    ]
    threshold = factor * (sum(dist) / len(dist))
    for i, d in enumerate(dist):
        if d > threshold:
            percentage = (i + 1) / len(states)
            del states[i + 1 :]
            return percentage
    return 1.0


def multiply(
    a: Tuple[Sequence[float], Sequence[float]], b: Tuple[Sequence[float], Sequence[float]]
):
    pos, orn = p.multiplyTransforms(a[0], a[1], b[0], b[1])
    return np.array(pos), np.array(orn)
