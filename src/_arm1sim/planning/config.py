"""What a *_moveit_config package loads as parameters, read into plain values.

kinematics.yaml (robot_description_kinematics/<group>/...), joint_limits.yaml
(robot_description_planning/...), ompl_planning.yaml (move_group/planner_configs and
move_group/<group>/...) and the execution settings. ROS-free: the ROS layer hands in the
parameter dictionaries as rosparam returns them. Defaults are MoveIt 1 noetic's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional


class ConfigError(ValueError):
    """A configuration value is unusable; the message names the parameter."""


def _number(value: Any, where: str) -> float:
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise ConfigError('%s: %r is not a number' % (where, value)) from None
    if not math.isfinite(out):
        raise ConfigError('%s: %r is not finite' % (where, value))
    return out


@dataclass
class KinematicsConfig:
    """One group's entry of kinematics.yaml (the KDL plugin's parameters)."""

    solver: str = ''
    search_resolution: float = 0.005
    timeout: float = 0.005
    attempts: int = 3
    position_only: bool = False


def kinematics_config(params: Mapping[str, Any]) -> Dict[str, KinematicsConfig]:
    out = {}
    for group, entry in (params or {}).items():
        if not isinstance(entry, Mapping):
            continue
        where = 'robot_description_kinematics/%s' % group
        out[group] = KinematicsConfig(
            solver=str(entry.get('kinematics_solver', '')),
            search_resolution=_number(
                entry.get('kinematics_solver_search_resolution', 0.005), where
            ),
            timeout=_number(entry.get('kinematics_solver_timeout', 0.005), where),
            attempts=int(_number(entry.get('kinematics_solver_attempts', 3), where)),
            position_only=bool(entry.get('position_only_ik', False)),
        )
    return out


@dataclass
class JointBounds:
    """A joint's limits as MoveIt holds them: the URDF's, overridden by joint_limits.yaml."""

    lower: float = -math.pi
    upper: float = math.pi
    max_velocity: Optional[float] = None
    max_acceleration: Optional[float] = None
    continuous: bool = False


@dataclass
class JointLimitsConfig:
    joints: Dict[str, Dict[str, Any]] = field(default_factory=dict)
    default_velocity_scaling: float = 0.1
    default_acceleration_scaling: float = 0.1


def joint_limits_config(params: Mapping[str, Any]) -> JointLimitsConfig:
    """robot_description_planning: joint_limits/<joint>/{has_,max_}{velocity,acceleration,
    position}, default_velocity_scaling_factor, default_acceleration_scaling_factor."""
    params = params or {}
    where = 'robot_description_planning'
    cfg = JointLimitsConfig(
        joints={
            k: dict(v)
            for k, v in (params.get('joint_limits') or {}).items()
            if isinstance(v, Mapping)
        },
        default_velocity_scaling=_number(params.get('default_velocity_scaling_factor', 0.1), where),
        default_acceleration_scaling=_number(
            params.get('default_acceleration_scaling_factor', 0.1), where
        ),
    )
    return cfg


def apply_joint_limits(bounds: JointBounds, name: str, cfg: JointLimitsConfig) -> JointBounds:
    """bounds with joint_limits.yaml's entry for ``name`` laid over them (as MoveIt's
    RobotModelLoader does: has_X true and max_X given replaces the URDF's)."""
    entry = cfg.joints.get(name)
    if not entry:
        return bounds
    where = 'robot_description_planning/joint_limits/%s' % name
    if entry.get('has_position_limits') and not bounds.continuous:
        bounds.lower = _number(entry.get('min_position', bounds.lower), where + '/min_position')
        bounds.upper = _number(entry.get('max_position', bounds.upper), where + '/max_position')
    if entry.get('has_velocity_limits') and 'max_velocity' in entry:
        bounds.max_velocity = abs(_number(entry['max_velocity'], where + '/max_velocity'))
    if entry.get('has_acceleration_limits') and 'max_acceleration' in entry:
        bounds.max_acceleration = abs(
            _number(entry['max_acceleration'], where + '/max_acceleration')
        )
    return bounds


@dataclass
class PlannerConfig:
    """One configuration of ompl_planning.yaml: an OMPL planner type and its parameters."""

    name: str
    type: str
    params: Dict[str, Any] = field(default_factory=dict)


@dataclass
class GroupPlanning:
    """ompl_planning.yaml's entry for a group."""

    planner_configs: List[str] = field(default_factory=list)
    default_planner_config: str = ''
    longest_valid_segment_fraction: float = 0.005
    params: Dict[str, Any] = field(default_factory=dict)


@dataclass
class OmplConfig:
    planner_configs: Dict[str, PlannerConfig] = field(default_factory=dict)
    groups: Dict[str, GroupPlanning] = field(default_factory=dict)
    simplify_solutions: bool = True
    minimum_waypoint_count: int = 2
    maximum_waypoint_distance: float = 0.0

    def planner_for(self, group: str, planner_id: str) -> Optional[PlannerConfig]:
        """The configuration a request names, as MoveIt's PlanningContextManager picks it:
        ``planner_id`` as given or as 'group[planner_id]', else the group's default."""
        if planner_id:
            for key in (planner_id, '%s[%s]' % (group, planner_id)):
                if key in self.planner_configs:
                    return self.planner_configs[key]
            if planner_id.startswith(group + '[') and planner_id.endswith(']'):
                inner = planner_id[len(group) + 1 : -1]
                if inner in self.planner_configs:
                    return self.planner_configs[inner]
        entry = self.groups.get(group)
        if entry and entry.default_planner_config in self.planner_configs:
            return self.planner_configs[entry.default_planner_config]
        return None


GROUP_KEYS = ('planner_configs', 'default_planner_config', 'longest_valid_segment_fraction')


def ompl_config(params: Mapping[str, Any], groups: List[str]) -> OmplConfig:
    """move_group's private parameters: planner_configs/<name>/{type, ...} and
    <group>/{planner_configs, default_planner_config, longest_valid_segment_fraction, ...}."""
    params = params or {}
    cfg = OmplConfig(
        simplify_solutions=bool(params.get('simplify_solutions', True)),
        minimum_waypoint_count=int(
            _number(params.get('minimum_waypoint_count', 2), 'minimum_waypoint_count')
        ),
        maximum_waypoint_distance=_number(
            params.get('maximum_waypoint_distance', 0.0), 'maximum_waypoint_distance'
        ),
    )
    for name, entry in (params.get('planner_configs') or {}).items():
        if not isinstance(entry, Mapping) or 'type' not in entry:
            raise ConfigError('planner_configs/%s has no type' % name)
        cfg.planner_configs[name] = PlannerConfig(
            name, str(entry['type']), {k: v for k, v in entry.items() if k != 'type'}
        )
    for group in groups:
        entry = params.get(group)
        if not isinstance(entry, Mapping):
            continue
        where = '%s/longest_valid_segment_fraction' % group
        cfg.groups[group] = GroupPlanning(
            planner_configs=[str(p) for p in entry.get('planner_configs') or []],
            default_planner_config=str(entry.get('default_planner_config', '')),
            longest_valid_segment_fraction=_number(
                entry.get('longest_valid_segment_fraction', 0.005), where
            ),
            params={k: v for k, v in entry.items() if k not in GROUP_KEYS},
        )
    return cfg


@dataclass
class ControllerConfig:
    """An entry of the controller list (moveit_simple_controller_manager, fake manager)."""

    name: str
    type: str  # FollowJointTrajectory, GripperCommand, or a fake controller's type
    joints: List[str]
    action_ns: str = ''
    default: bool = False
    max_effort: float = 0.0
    allowed_execution_duration_scaling: Optional[float] = None
    allowed_goal_duration_margin: Optional[float] = None


def controller_list(entries: Any) -> List[ControllerConfig]:
    out = []
    for i, entry in enumerate(entries or []):
        if not isinstance(entry, Mapping) or 'name' not in entry:
            raise ConfigError('controller_list[%d] has no name' % i)
        joints = entry.get('joints') or []
        if not isinstance(joints, list) or not joints:
            raise ConfigError("controller_list: controller '%s' lists no joints" % entry['name'])
        where = 'controller_list/%s' % entry['name']
        out.append(
            ControllerConfig(
                name=str(entry['name']),
                type=str(entry.get('type', 'FollowJointTrajectory')),
                joints=[str(j) for j in joints],
                action_ns=str(entry.get('action_ns', '')),
                default=bool(entry.get('default', False)),
                max_effort=_number(entry.get('max_effort', 0.0), where + '/max_effort'),
                allowed_execution_duration_scaling=(
                    _number(entry['allowed_execution_duration_scaling'], where)
                    if 'allowed_execution_duration_scaling' in entry
                    else None
                ),
                allowed_goal_duration_margin=(
                    _number(entry['allowed_goal_duration_margin'], where)
                    if 'allowed_goal_duration_margin' in entry
                    else None
                ),
            )
        )
    return out


@dataclass
class ExecutionConfig:
    """trajectory_execution/* of move_group (trajectory_execution.launch.xml), MoveIt's
    defaults."""

    execution_duration_monitoring: bool = True
    allowed_execution_duration_scaling: float = 1.1
    allowed_goal_duration_margin: float = 0.5
    allowed_start_tolerance: float = 0.01


def execution_config(params: Mapping[str, Any]) -> ExecutionConfig:
    params = params or {}
    d = ExecutionConfig()
    return ExecutionConfig(
        execution_duration_monitoring=bool(
            params.get('execution_duration_monitoring', d.execution_duration_monitoring)
        ),
        allowed_execution_duration_scaling=_number(
            params.get('allowed_execution_duration_scaling', d.allowed_execution_duration_scaling),
            'trajectory_execution/allowed_execution_duration_scaling',
        ),
        allowed_goal_duration_margin=_number(
            params.get('allowed_goal_duration_margin', d.allowed_goal_duration_margin),
            'trajectory_execution/allowed_goal_duration_margin',
        ),
        allowed_start_tolerance=_number(
            params.get('allowed_start_tolerance', d.allowed_start_tolerance),
            'trajectory_execution/allowed_start_tolerance',
        ),
    )
