"""Joint handles and effort saturation, as hardware_interface and joint_limits_interface
have them."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Sequence, Tuple

from ..description.joint_limits import (
    EFFORT_JOINT_INTERFACE,
    POSITION_JOINT_INTERFACE,
    VELOCITY_JOINT_INTERFACE,
    JointLimits,
)

__all__ = [
    'EFFORT_JOINT_INTERFACE',
    'POSITION_JOINT_INTERFACE',
    'VELOCITY_JOINT_INTERFACE',
    'JointHandle',
    'JointLimits',
    'SaturationBounds',
    'saturation_bounds',
    'enforce_effort_limits',
    'saturate_effort',
    'saturate_handles',
]


@dataclass
class JointHandle:
    """One joint of the hardware: its state, read from the simulation, and ``command``, the
    hardware command a controller writes (ros_control's setCommand), in the unit of the
    joint's ``interface``: an effort, a position or a velocity."""

    name: str
    type: str  # 'revolute', 'continuous' or 'prismatic'
    limits: JointLimits = field(default_factory=JointLimits)
    interface: str = EFFORT_JOINT_INTERFACE
    position: float = 0.0
    velocity: float = 0.0
    effort: float = 0.0  # the effort last applied, after saturation
    command: float = 0.0


# (max effort, lower, upper, max velocity)
SaturationBounds = Tuple[float, float, float, float]


def saturation_bounds(limits: JointLimits) -> SaturationBounds:
    """``(max effort, lower, upper, max velocity)`` of JointLimits, inf where there is none."""
    inf = math.inf
    lower, upper = (
        (limits.lower, limits.upper)
        if limits.lower is not None and limits.upper is not None
        else (-inf, inf)
    )
    return (
        limits.effort if limits.effort is not None and limits.effort > 0 else inf,
        lower,
        upper,
        limits.velocity if limits.velocity is not None and limits.velocity > 0 else inf,
    )


def enforce_effort_limits(
    command: float, position: float, velocity: float, limits: JointLimits
) -> float:
    """gazebo_ros_control's effort saturation for EffortJointInterface joints
    (see saturate_effort)."""
    return saturate_effort(command, position, velocity, *saturation_bounds(limits))


def saturate_effort(
    command: float,
    position: float,
    velocity: float,
    max_effort: float,
    lower: float,
    upper: float,
    max_velocity: float,
) -> float:
    """Clamp to +-max_effort; zero any effort pushing further beyond a position limit or
    further beyond the velocity limit. Bounds come from saturation_bounds, once per joint.
    This is saturate_handles over one joint."""
    joint = JointHandle('', 'revolute', position=position, velocity=velocity, command=command)
    return saturate_handles(((joint, max_effort, lower, upper, max_velocity),))[0]


# A joint with its SaturationBounds, as saturate_handles takes them
SaturatedJoint = Tuple[JointHandle, float, float, float, float]


def saturate_handles(joints: Sequence[SaturatedJoint]) -> List[float]:
    """saturate_effort of each joint's command, in one pass: sets each handle's ``effort``
    and returns them. The one implementation of the saturation: one call a step for all the
    joints, not one per joint (per-joint calls were most of a step's Python time)."""
    isfinite = math.isfinite
    efforts = []
    for h, max_effort, lower, upper, max_velocity in joints:
        command = h.command
        if isfinite(command):
            position, velocity = h.position, h.velocity
            hi = 0.0 if position > upper or velocity > max_velocity else max_effort
            lo = 0.0 if position < lower or velocity < -max_velocity else -max_effort
            effort = hi if command > hi else lo if command < lo else command
        else:
            effort = 0.0
        h.effort = effort
        efforts.append(effort)
    return efforts
