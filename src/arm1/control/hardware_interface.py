"""Joint handles and effort saturation, as hardware_interface and joint_limits_interface have them."""
import math
from dataclasses import dataclass, field

EFFORT_JOINT_INTERFACE = 'hardware_interface/EffortJointInterface'
POSITION_JOINT_INTERFACE = 'hardware_interface/PositionJointInterface'
VELOCITY_JOINT_INTERFACE = 'hardware_interface/VelocityJointInterface'


def canonical_interface(name):
    """Transmissions may name the interface with or without the ``hardware_interface/`` prefix."""
    name = (name or '').strip()
    return name if '/' in name else 'hardware_interface/' + name


@dataclass
class JointLimits:
    """The URDF ``<limit>`` of a joint; a missing bound is None."""
    lower: float = None
    upper: float = None
    effort: float = None
    velocity: float = None

    @property
    def has_position_limits(self):
        return self.lower is not None and self.upper is not None


@dataclass
class JointHandle:
    """State read from the simulation and the command a controller writes."""
    name: str
    type: str  # 'revolute', 'continuous' or 'prismatic'
    limits: JointLimits = field(default_factory=JointLimits)
    interface: str = EFFORT_JOINT_INTERFACE
    position: float = 0.0
    velocity: float = 0.0
    effort: float = 0.0
    command: float = 0.0
    claimed_by: str = None


def saturation_bounds(limits):
    """``(max effort, lower, upper, max velocity)`` of JointLimits, inf where there is none."""
    inf = math.inf
    return (limits.effort if limits.effort is not None and limits.effort > 0 else inf,
            limits.lower if limits.has_position_limits else -inf,
            limits.upper if limits.has_position_limits else inf,
            limits.velocity if limits.velocity is not None and limits.velocity > 0 else inf)


def enforce_effort_limits(command, position, velocity, limits):
    """gazebo_ros_control's effort saturation for EffortJointInterface joints (see saturate_effort)."""
    return saturate_effort(command, position, velocity, *saturation_bounds(limits))


def saturate_effort(command, position, velocity, max_effort, lower, upper, max_velocity):
    """Clamp to +-max_effort; zero any effort pushing further beyond a position limit or
    further beyond the velocity limit. Bounds come from saturation_bounds, once per joint."""
    if not math.isfinite(command):
        return 0.0
    hi = 0.0 if position > upper or velocity > max_velocity else max_effort
    lo = 0.0 if position < lower or velocity < -max_velocity else -max_effort
    return hi if command > hi else lo if command < lo else command
