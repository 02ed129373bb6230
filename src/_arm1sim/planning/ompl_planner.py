"""Joint-space planning with OMPL's own planners (PyPI ``ompl``), as MoveIt's
ompl_interface sets them up: the group's joints as a real vector space within their
bounds, a state valid when collision-free and within the path constraints, motions checked
every longest_valid_segment_fraction of the space's extent, the planner and its parameters
from ompl_planning.yaml; the solution simplified and interpolated (at least
minimum_waypoint_count states).
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence

from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

from .config import PlannerConfig
from .error_codes import (
    GOAL_STATE_INVALID,
    PLANNING_FAILED,
    START_STATE_INVALID,
    SUCCESS,
    TIMED_OUT,
)
from .kinematics import RobotKinematics

log = logging.getLogger(__name__)


# MoveIt's planner types and the class the PyPI wheel has for each
PLANNERS = {
    'geometric::RRTConnect': 'RRTConnect',
    'geometric::RRT': 'RRT',
    'geometric::RRTstar': 'RRTstar',
    'geometric::PRM': 'PRM',
    'geometric::PRMstar': 'PRMstar',
    'geometric::KPIECE': 'KPIECE1',
    'geometric::BKPIECE': 'BKPIECE1',
    'geometric::LBKPIECE': 'LBKPIECE1',
    'geometric::FMT': 'FMT',
    'geometric::BFMT': 'BFMT',
    'geometric::BITstar': 'BITstar',
    'geometric::InformedRRTstar': 'InformedRRTstar',
    'geometric::SORRTstar': 'SORRTstar',
}
DEFAULT_PLANNER = 'geometric::RRTConnect'  # OMPL's default for a sampleable goal

ou.setLogLevel(ou.LogLevel.LOG_WARN)
_said: set = set()


def say_once(message: str) -> None:
    if message not in _said:
        _said.add(message)
        log.warning(message)


def planner_type(config: Optional[PlannerConfig]) -> str:
    kind = config.type if config else DEFAULT_PLANNER
    if kind not in PLANNERS:
        say_once(
            "planner type '%s' is not in the ompl wheel's bindings; %s plans instead"
            % (kind, DEFAULT_PLANNER)
        )
        kind = DEFAULT_PLANNER
    return kind


def _camel(name: str) -> str:
    return 'set' + ''.join(part[:1].upper() + part[1:] for part in name.split('_'))


def _conversions(value: Any) -> List[Any]:
    """What a yaml value may be handed to a nanobind setter as (bool, int or double)."""
    if isinstance(value, bool):
        return [value]
    try:
        number = float(value)
    except (TypeError, ValueError):
        return [value]
    out: List[Any] = [number]
    if number.is_integer():
        out.append(int(number))
    return out


def make_planner(si: Any, config: Optional[PlannerConfig]) -> Any:
    kind = planner_type(config)
    planner = getattr(og, PLANNERS[kind])(si)
    for key, value in (config.params if config else {}).items():
        setter = getattr(planner, _camel(key), None)
        if setter is None:
            say_once(
                "planner %s: parameter '%s' cannot be set through the ompl wheel" % (kind, key)
            )
            continue
        for candidate in _conversions(value):
            try:
                setter(candidate)
                break
            except (TypeError, ValueError):
                continue
        else:
            say_once('planner %s: parameter %s=%r not applied' % (kind, key, value))
    return planner


@dataclass
class PlanResult:
    error_code: int
    waypoints: List[List[float]] = field(default_factory=list)  # group joint values
    planning_time: float = 0.0
    message: str = ''


class JointSpacePlanner:
    """Plans for one group; ``valid(full_positions)`` judges a state (collision, path
    constraints)."""

    def __init__(
        self,
        robot: RobotKinematics,
        joints: Sequence[str],
        valid: Callable[[Dict[str, float]], bool],
    ) -> None:
        self.robot = robot
        self.joints = list(joints)
        self.valid = valid

    def _setup(
        self,
        start: Dict[str, float],
        goals: List[Dict[str, float]],
        config: Optional[PlannerConfig],
        longest_valid_segment_fraction: float,
    ) -> Any:
        n = len(self.joints)
        space = ob.RealVectorStateSpace(n)
        bounds = ob.RealVectorBounds(n)
        for i, name in enumerate(self.joints):
            b = self.robot.bounds[name]
            bounds.setLow(i, b.lower)
            bounds.setHigh(i, b.upper)
        space.setBounds(bounds)
        ss = og.SimpleSetup(space)
        base = dict(start)
        joints = self.joints

        def check(state: Any) -> bool:
            values = dict(base)
            for i, name in enumerate(joints):
                values[name] = state[i]
            return self.valid(values)

        ss.setStateValidityChecker(check)
        si = ss.getSpaceInformation()
        si.setStateValidityCheckingResolution(longest_valid_segment_fraction)
        s = space.allocState()
        for i, name in enumerate(joints):
            s[i] = self.robot.clamp(name, start[name])
        ss.setStartState(s)
        goal = ob.GoalStates(si)
        for g in goals:
            gs = space.allocState()
            for i, name in enumerate(joints):
                gs[i] = g[name]
            goal.addState(gs)
        ss.setGoal(goal)
        ss.setPlanner(make_planner(si, config))
        return ss

    def plan(
        self,
        start: Dict[str, float],
        goals: List[Dict[str, float]],
        config: Optional[PlannerConfig],
        allowed_time: float = 5.0,
        longest_valid_segment_fraction: float = 0.005,
        simplify: bool = True,
        minimum_waypoint_count: int = 2,
        attempts: int = 1,
    ) -> PlanResult:
        """With ``attempts`` > 1, as MoveIt's num_planning_attempts: several plans (here one
        after another, sharing the time), the shortest kept."""
        t0 = time.monotonic()
        S = ob.PlannerStatus
        best: Any = None
        best_length = math.inf
        status: Any = None
        for k in range(max(1, attempts)):
            budget = (allowed_time - (time.monotonic() - t0)) / (max(1, attempts) - k)
            ss = self._setup(start, goals, config, longest_valid_segment_fraction)
            status = ss.solve(max(0.0, budget))
            if status.getStatus() == S.EXACT_SOLUTION and ss.haveExactSolutionPath():
                length = ss.getSolutionPath().length()
                if length < best_length:
                    best, best_length = ss, length
        if best is None:
            kind = status.getStatus()
            code = {
                S.TIMEOUT: TIMED_OUT,
                S.INVALID_START: START_STATE_INVALID,
                S.INVALID_GOAL: GOAL_STATE_INVALID,
            }.get(kind, PLANNING_FAILED)
            return PlanResult(code, planning_time=time.monotonic() - t0, message=status.asString())
        ss = best
        if simplify:
            remaining = allowed_time - (time.monotonic() - t0)
            if remaining > 0:
                ss.simplifySolution(remaining)
        space = ss.getStateSpace()
        path = ss.getSolutionPath()
        states = path.getStateCount()
        eventual = 1 + sum(
            space.validSegmentCount(path.getState(i), path.getState(i + 1))
            for i in range(states - 1)
        )
        if eventual < minimum_waypoint_count:
            path.interpolate(minimum_waypoint_count)
        else:
            path.interpolate()
        n = len(self.joints)
        waypoints = []
        for i in range(path.getStateCount()):
            st = path.getState(i)
            waypoints.append([float(st[k]) for k in range(n)])
        return PlanResult(SUCCESS, waypoints, time.monotonic() - t0)


def wrap(value: float) -> float:
    return math.atan2(math.sin(value), math.cos(value))
