"""Inverse kinematics for a group, as MoveIt's KDL plugin answers it: a pose (or, with
position_only_ik, a position) of one link the group moves, solved from a seed by damped
least squares within the joints' limits, restarted from random states until the timeout.

The first attempt starts at the seed (the current state), so the answer is the solution
nearest it when there is one nearby. A solution may further have to pass ``accept`` (e.g.
no collision), as MoveIt's IK callbacks.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass
from typing import Callable, Dict, Optional, Sequence

import numpy as np

from .kinematics import RobotKinematics, Vector, rotation_error

# KDL's epsilon is 1e-5 on the twist; these are on the error itself.
POSITION_TOLERANCE = 1e-5  # m
ORIENTATION_TOLERANCE = 1e-4  # rad
DAMPING = 1e-3
MAX_STEP = 0.3  # rad (or m) per iteration and joint: keeps a step inside the linear range
ITERATIONS = 200  # per attempt
# An attempt whose error has not shrunk by STALL_GAIN over STALL_ITERATIONS is stuck (at a
# joint limit, a singularity): a restart from elsewhere does better with the time left.
STALL_ITERATIONS = 15
STALL_GAIN = 0.99


@dataclass
class IkRequest:
    joints: Sequence[str]
    link: str
    position: Vector
    orientation: Optional[Vector]  # x y z w; None: position only
    seed: Dict[str, float]
    timeout: float = 0.005
    attempts: int = 0  # 0: restart until the timeout


def _solve_from(robot: RobotKinematics, req: IkRequest, q: np.ndarray) -> Optional[np.ndarray]:
    target = np.asarray(req.position, dtype=float)
    names = list(req.joints)
    lower = np.array([robot.bounds[n].lower for n in names])
    upper = np.array([robot.bounds[n].upper for n in names])
    best, since_best = np.inf, 0
    for _ in range(ITERATIONS):
        robot.set_positions(dict(zip(names, q)))
        pos, orn = robot.link_pose(req.link)
        err_p = target - pos
        if req.orientation is None:
            err = err_p
            if np.linalg.norm(err_p) < POSITION_TOLERANCE:
                return q
            jac = robot.jacobian(req.link, names)[:3]
        else:
            err_r = rotation_error(req.orientation, orn)
            if (
                np.linalg.norm(err_p) < POSITION_TOLERANCE
                and np.linalg.norm(err_r) < ORIENTATION_TOLERANCE
            ):
                return q
            err = np.concatenate([err_p, err_r])
            jac = robot.jacobian(req.link, names)
        size = float(np.linalg.norm(err))
        if size < best * STALL_GAIN:
            best, since_best = size, 0
        else:
            since_best += 1
            if since_best >= STALL_ITERATIONS:
                return None
        jjt = jac @ jac.T + DAMPING**2 * np.eye(jac.shape[0])
        dq = jac.T @ np.linalg.solve(jjt, err)
        largest = np.max(np.abs(dq))
        if largest > MAX_STEP:
            dq *= MAX_STEP / largest
        q = np.clip(q + dq, lower, upper)
    return None


def solve_ik(
    robot: RobotKinematics,
    req: IkRequest,
    accept: Optional[Callable[[Dict[str, float]], bool]] = None,
    rng: Optional[random.Random] = None,
) -> Optional[Dict[str, float]]:
    """Joint values of ``req.joints`` putting ``req.link`` at the pose, or None.

    The robot model's state is left at the seed with the solution laid over it (or the
    seed, on failure).
    """
    rng = rng or random.Random()
    names = list(req.joints)
    start = dict(req.seed)
    deadline = time.monotonic() + max(0.0, req.timeout)
    seed = np.array([robot.clamp(n, start.get(n, robot.positions[n])) for n in names])
    q = seed
    attempt = 0
    while True:
        robot.set_positions(start)
        solution = _solve_from(robot, req, q)
        if solution is not None:
            values = dict(zip(names, (float(v) for v in solution)))
            if accept is None or accept({**start, **values}):
                robot.set_positions({**start, **values})
                return values
        attempt += 1
        if req.attempts and attempt >= req.attempts:
            break
        if time.monotonic() >= deadline:
            break
        q = np.array([rng.uniform(robot.bounds[n].lower, robot.bounds[n].upper) for n in names])
    robot.set_positions(start)
    return None
