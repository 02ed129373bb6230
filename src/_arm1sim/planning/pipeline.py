"""MoveIt's planning pipeline without ROS: a motion plan request (start, goals as joint
values, link poses or named states, path constraints) in, a timed trajectory or MoveIt's
error code out.

As move_group's default pipeline (ompl_interface/OMPLPlanner with the default request
adapters): a start state a little outside its bounds is clamped (FixStartStateBounds,
start_state_max_bounds_error), one in collision jiggled free if it can be
(FixStartStateCollision: jiggle_fraction of each joint's range, max_sampling_attempts);
pose goals become joint goals through IK (several solutions, the first seeded from the
start); OMPL plans; the path is timed (AddTimeParameterization).
"""

from __future__ import annotations

import logging
import math
import random
import time
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from .cartesian import CartesianResult, cartesian_path
from .config import KinematicsConfig, OmplConfig
from .error_codes import (
    GOAL_IN_COLLISION,
    GOAL_VIOLATES_PATH_CONSTRAINTS,
    INVALID_GOAL_CONSTRAINTS,
    INVALID_GROUP_NAME,
    INVALID_LINK_NAME,
    INVALID_ROBOT_STATE,
    NO_IK_SOLUTION,
    START_STATE_IN_COLLISION,
    START_STATE_INVALID,
    START_STATE_VIOLATES_PATH_CONSTRAINTS,
    SUCCESS,
)
from .ik import IkRequest, solve_ik
from .kinematics import ModelError, RobotKinematics, Vector, quat_to_matrix
from .ompl_planner import JointSpacePlanner
from .scene import CollisionWorld
from .time_parameterization import time_parameterize

log = logging.getLogger(__name__)

# How many IK solutions a pose goal offers the planner (MoveIt samples its goal region).
GOAL_SAMPLES = 4
# Configs give IK KDL's C++ budget (kinematics_solver_timeout: 0.005 s); this solver is
# Python, about ten times slower an iteration, so it gets at least this much (s).
IK_MIN_TIMEOUT = 0.05


@dataclass
class JointGoal:
    joint: str
    position: float
    tolerance_above: float = 1e-4
    tolerance_below: float = 1e-4


@dataclass
class OrientationConstraint:
    link: str
    orientation: Vector  # x y z w, model frame
    tolerances: Sequence[float] = (0.001, 0.001, 0.001)  # about the target's x y z axes


@dataclass
class PositionConstraint:
    link: str
    center: Vector  # model frame
    box: Optional[Sequence[float]] = None  # full side lengths; None: a sphere
    radius: float = 1e-4
    orientation: Sequence[float] = (0, 0, 0, 1)  # of the box


@dataclass
class Constraints:
    joints: List[JointGoal] = field(default_factory=list)
    positions: List[PositionConstraint] = field(default_factory=list)
    orientations: List[OrientationConstraint] = field(default_factory=list)

    def empty(self) -> bool:
        return not (self.joints or self.positions or self.orientations)


@dataclass
class MotionRequest:
    group: str
    start: Dict[str, float]
    goals: List[Constraints]  # alternatives: any one reached is success
    path_constraints: Constraints = field(default_factory=Constraints)
    planner_id: str = ''
    allowed_planning_time: float = 5.0
    num_planning_attempts: int = 1
    max_velocity_scaling_factor: float = 0.0
    max_acceleration_scaling_factor: float = 0.0


@dataclass
class Trajectory:
    joint_names: List[str]
    positions: List[List[float]] = field(default_factory=list)
    velocities: List[List[float]] = field(default_factory=list)
    accelerations: List[List[float]] = field(default_factory=list)
    times: List[float] = field(default_factory=list)


@dataclass
class MotionResult:
    error_code: int
    trajectory: Optional[Trajectory] = None
    planning_time: float = 0.0
    message: str = ''
    start: Dict[str, float] = field(default_factory=dict)


@dataclass
class PipelineSettings:
    start_state_max_bounds_error: float = 0.05
    jiggle_fraction: float = 0.05
    max_sampling_attempts: int = 100


class PlanningPipeline:
    def __init__(
        self,
        robot: RobotKinematics,
        world: CollisionWorld,
        ompl: OmplConfig,
        kinematics: Dict[str, KinematicsConfig],
        settings: Optional[PipelineSettings] = None,
        seed: Optional[int] = None,
    ) -> None:
        self.robot = robot
        self.world = world
        self.ompl = ompl
        self.kinematics = kinematics
        self.settings = settings or PipelineSettings()
        self.rng = random.Random(seed)

    # --- checks ----------------------------------------------------------------------------

    def satisfies(self, c: Constraints, values: Dict[str, float], tolerance: float = 0.0) -> bool:
        for jc in c.joints:
            v = values.get(jc.joint)
            if v is None:
                continue
            if not (
                jc.position - jc.tolerance_below - tolerance
                <= v
                <= jc.position + jc.tolerance_above + tolerance
            ):
                return False
        if c.positions or c.orientations:
            self.robot.set_positions(values)
        for pc in c.positions:
            pos, _ = self.robot.link_pose(pc.link)
            d = pos - np.asarray(pc.center, float)
            if pc.box is None:
                if np.linalg.norm(d) > pc.radius + tolerance:
                    return False
            else:
                local = quat_to_matrix(pc.orientation).T @ d
                if np.any(np.abs(local) > np.asarray(pc.box, float) / 2.0 + tolerance):
                    return False
        for oc in c.orientations:
            _, orn = self.robot.link_pose(oc.link)
            r = quat_to_matrix(oc.orientation).T @ quat_to_matrix(orn)
            # rotation vector of the difference, in the target's frame
            angle = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1.0) / 2.0)))
            if angle > 1e-9:
                axis = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
                n = np.linalg.norm(axis)
                rv = axis / n * angle if n > 1e-12 else np.array([angle, 0.0, 0.0])
                if np.any(np.abs(rv) > np.asarray(oc.tolerances, float) + tolerance):
                    return False
        return True

    def state_ok(self, values: Dict[str, float], path: Constraints) -> bool:
        if not path.empty() and not self.satisfies(path, values):
            return False
        return not self.world.in_collision(values)

    # --- IK ---------------------------------------------------------------------------------

    def ik(
        self,
        group: str,
        link: str,
        position: Vector,
        orientation: Optional[Vector],
        seed: Dict[str, float],
        timeout: Optional[float] = None,
        avoid_collisions: bool = True,
        path: Optional[Constraints] = None,
        attempts: int = 0,
    ) -> Optional[Dict[str, float]]:
        joints = self.robot.group_joints(group)
        cfg = self.kinematics.get(group, KinematicsConfig())
        if cfg.position_only:
            orientation = None
        constraints = path or Constraints()

        def accept(values: Dict[str, float]) -> bool:
            if not constraints.empty() and not self.satisfies(constraints, values):
                return False
            return not avoid_collisions or not self.world.in_collision(values)

        req = IkRequest(
            joints,
            link,
            position,
            orientation,
            seed,
            timeout=max(
                IK_MIN_TIMEOUT, cfg.timeout if timeout is None or timeout <= 0 else timeout
            ),
            attempts=attempts,
        )
        return solve_ik(self.robot, req, accept, self.rng)

    # --- planning ---------------------------------------------------------------------------

    def _fix_start(
        self, req: MotionRequest, joints: List[str]
    ) -> Tuple[int, Dict[str, float], bool]:
        """(code, start, changed): the adapters' repairs of the start state."""
        start = dict(req.start)
        changed = False
        s = self.settings
        for name in joints:
            b = self.robot.bounds[name]
            v = start[name]
            if b.continuous:
                w = self.robot.clamp(name, v)
                changed |= w != v
                start[name] = w
            elif v < b.lower or v > b.upper:
                if (
                    b.lower - s.start_state_max_bounds_error
                    <= v
                    <= b.upper + s.start_state_max_bounds_error
                ):
                    start[name] = min(b.upper, max(b.lower, v))
                    changed = True
                else:
                    return START_STATE_INVALID, start, False
        if self.world.in_collision(start):
            for _ in range(s.max_sampling_attempts):
                trial = dict(start)
                for name in joints:
                    b = self.robot.bounds[name]
                    span = s.jiggle_fraction * (b.upper - b.lower)
                    trial[name] = min(
                        b.upper, max(b.lower, start[name] + self.rng.uniform(-span, span))
                    )
                if not self.world.in_collision(trial):
                    log.info('Start state was in collision; jiggled it free')
                    return SUCCESS, trial, True
            contacts = self.world.contacts(start)
            log.error(
                'Start state appears to be in collision with respect to group %s: %s',
                req.group,
                ', '.join('%s-%s' % (a, b) for a, b, _ in contacts[:5]),
            )
            return START_STATE_IN_COLLISION, start, False
        if not req.path_constraints.empty() and not self.satisfies(req.path_constraints, start):
            return START_STATE_VIOLATES_PATH_CONSTRAINTS, start, False
        return SUCCESS, start, changed

    def goal_states(
        self, req: MotionRequest, joints: List[str], start: Dict[str, float]
    ) -> Tuple[int, List[Dict[str, float]]]:
        out: List[Dict[str, float]] = []
        saw_ik_failure = saw_collision = saw_path = False
        deadline = time.monotonic() + max(0.05, req.allowed_planning_time / 2.0)
        for goal in req.goals:
            targets = {jc.joint: jc.position for jc in goal.joints}
            if targets:
                unknown = [j for j in targets if j not in self.robot.bounds]
                if unknown:
                    raise ModelError('goal names joints %s, not in the robot' % unknown)
                state = dict(start)
                state.update(targets)
                if not self.robot.within_bounds({j: state[j] for j in joints}, 1e-9):
                    continue
                if self.world.in_collision(state):
                    saw_collision = True
                    continue
                if not req.path_constraints.empty() and not self.satisfies(
                    req.path_constraints, state
                ):
                    saw_path = True
                    continue
                if not (goal.positions or goal.orientations):
                    out.append(state)
                    continue
            # pose goals: a position constraint and/or an orientation constraint of one link
            links = {c.link for c in goal.positions} | {c.link for c in goal.orientations}
            for link in links:
                position: Optional[Vector] = next(
                    (c.center for c in goal.positions if c.link == link), None
                )
                orientation = next(
                    (c.orientation for c in goal.orientations if c.link == link), None
                )
                if position is None:
                    self.robot.set_positions(start)
                    position = self.robot.link_pose(link)[0]
                found = 0
                seed = dict(start)
                while found < GOAL_SAMPLES and time.monotonic() < deadline:
                    values = self.ik(
                        req.group,
                        link,
                        position,
                        orientation,
                        seed,
                        timeout=max(0.01, deadline - time.monotonic()) if found == 0 else 0.02,
                        path=req.path_constraints,
                    )
                    if values is None:
                        saw_ik_failure = found == 0
                        break
                    state = dict(start)
                    state.update(values)
                    if self.satisfies(goal, state, 1e-3):
                        out.append(state)
                    found += 1
                    seed = {
                        j: self.rng.uniform(self.robot.bounds[j].lower, self.robot.bounds[j].upper)
                        for j in joints
                    }
                    seed = {**start, **seed}
        if out:
            return SUCCESS, out
        if saw_collision:
            return GOAL_IN_COLLISION, out
        if saw_path:
            return GOAL_VIOLATES_PATH_CONSTRAINTS, out
        if saw_ik_failure:
            return NO_IK_SOLUTION, out
        return INVALID_GOAL_CONSTRAINTS, out

    def check_request(self, req: MotionRequest) -> Tuple[int, str]:
        """MoveIt's code and a message naming the culprit for a request it cannot plan."""
        bad = [j for j, v in req.start.items() if not math.isfinite(v)]
        if bad:
            return INVALID_ROBOT_STATE, 'start state: %s not finite' % ', '.join(bad)
        for c in req.goals + [req.path_constraints]:
            for link in [x.link for x in c.positions] + [x.link for x in c.orientations]:
                if link not in self.robot.link_index:
                    return INVALID_LINK_NAME, "constraint on link '%s', not in the robot" % link
            numbers = [
                v for jc in c.joints for v in (jc.position, jc.tolerance_above, jc.tolerance_below)
            ]
            numbers += [float(v) for x in c.positions for v in x.center]
            numbers += [float(v) for x in c.orientations for v in x.orientation]
            if not all(math.isfinite(v) for v in numbers):
                return INVALID_GOAL_CONSTRAINTS, 'a constraint holds a number that is not finite'
        return SUCCESS, ''

    def plan(self, req: MotionRequest) -> MotionResult:
        t0 = time.monotonic()
        if req.group not in self.robot.srdf.groups:
            return MotionResult(INVALID_GROUP_NAME, message="no group '%s'" % req.group)
        joints = self.robot.group_joints(req.group)
        missing = [j for j in self.robot.variables if j not in req.start]
        if missing:
            return MotionResult(
                INVALID_ROBOT_STATE, message='start state lacks joints %s' % missing
            )
        code, message = self.check_request(req)
        if code != SUCCESS:
            log.error(message)
            return MotionResult(code, message=message)
        code, start, fixed = self._fix_start(req, joints)
        if code != SUCCESS:
            return MotionResult(code, planning_time=time.monotonic() - t0, start=start)
        try:
            code, goals = self.goal_states(req, joints, start)
        except ModelError as exc:
            return MotionResult(INVALID_GOAL_CONSTRAINTS, message=str(exc))
        if code != SUCCESS:
            return MotionResult(code, planning_time=time.monotonic() - t0, start=start)
        group_cfg = self.ompl.groups.get(req.group)
        config = self.ompl.planner_for(req.group, req.planner_id)
        if req.planner_id and (
            config is None
            or req.planner_id not in (config.name, '%s[%s]' % (req.group, config.name))
        ):
            log.warning(
                "Cannot find planning configuration for group '%s' using planner '%s'. "
                'Will use defaults instead.',
                req.group,
                req.planner_id,
            )
        planner = JointSpacePlanner(
            self.robot, joints, lambda v: self.state_ok(v, req.path_constraints)
        )
        remaining = max(0.0, req.allowed_planning_time - (time.monotonic() - t0))
        result = planner.plan(
            start,
            goals,
            config,
            allowed_time=remaining,
            longest_valid_segment_fraction=group_cfg.longest_valid_segment_fraction
            if group_cfg
            else 0.005,
            simplify=self.ompl.simplify_solutions,
            minimum_waypoint_count=self.ompl.minimum_waypoint_count,
            attempts=req.num_planning_attempts,
        )
        if result.error_code != SUCCESS:
            return MotionResult(
                result.error_code,
                planning_time=time.monotonic() - t0,
                message=result.message,
                start=start,
            )
        waypoints = result.waypoints
        if fixed:  # the adapters put the state as it was first
            waypoints = [[req.start[j] for j in joints]] + waypoints
        traj = self.timed(
            joints, waypoints, req.max_velocity_scaling_factor, req.max_acceleration_scaling_factor
        )
        return MotionResult(SUCCESS, traj, time.monotonic() - t0, start=dict(req.start))

    def timed(
        self, joints: List[str], waypoints: List[List[float]], vs: float, accs: float
    ) -> Trajectory:
        times, vel, acc = time_parameterize(
            waypoints,
            [self.robot.bounds[j].max_velocity for j in joints],
            [self.robot.bounds[j].max_acceleration for j in joints],
            vs,
            accs,
        )
        return Trajectory(
            list(joints),
            [list(map(float, w)) for w in waypoints],
            vel.tolist(),
            acc.tolist(),
            times,
        )

    def cartesian(
        self,
        group: str,
        link: str,
        start: Dict[str, float],
        waypoints: Sequence[Tuple[Sequence[float], Sequence[float]]],
        max_step: float,
        jump_threshold: float,
        avoid_collisions: bool,
        path: Optional[Constraints] = None,
    ) -> Tuple[CartesianResult, Trajectory]:
        joints = self.robot.group_joints(group)
        constraints = path or Constraints()

        def valid(values: Dict[str, float]) -> bool:
            if not constraints.empty() and not self.satisfies(constraints, values):
                return False
            return not avoid_collisions or not self.world.in_collision(values)

        cfg = self.kinematics.get(group, KinematicsConfig())
        result = cartesian_path(
            self.robot,
            joints,
            link,
            start,
            waypoints,
            max_step,
            jump_threshold,
            valid,
            ik_timeout=max(cfg.timeout, 0.005),
        )
        waypoints_q = [[s[j] for j in joints] for s in result.states]
        # compute_cartesian_path times its path at full speed (scaling 1.0)
        return result, self.timed(joints, waypoints_q, 1.0, 1.0)
