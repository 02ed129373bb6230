"""What a URDF says of how a joint may move and how it is driven: its <limit> and the
hardware interface its transmission names. Control builds its joint handles on these."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

EFFORT_JOINT_INTERFACE = 'hardware_interface/EffortJointInterface'
POSITION_JOINT_INTERFACE = 'hardware_interface/PositionJointInterface'
VELOCITY_JOINT_INTERFACE = 'hardware_interface/VelocityJointInterface'


def canonical_interface(name: Optional[str]) -> str:
    """Transmissions may name the interface with or without the ``hardware_interface/`` prefix."""
    name = (name or '').strip()
    return name if '/' in name else 'hardware_interface/' + name


@dataclass
class SoftLimits:
    """A URDF ``<safety_controller>``: soft position limits and the gains that keep a joint
    inside them (joint_limits_interface's SoftJointLimits)."""

    lower: float = 0.0
    upper: float = 0.0
    k_position: float = 0.0
    k_velocity: float = 0.0


@dataclass
class JointLimits:
    """The URDF ``<limit>`` of a joint; a missing bound is None. ``soft``: its
    ``<safety_controller>``, when it has one and a ``<limit>``."""

    lower: Optional[float] = None
    upper: Optional[float] = None
    effort: Optional[float] = None
    velocity: Optional[float] = None
    soft: Optional[SoftLimits] = None

    @property
    def has_position_limits(self) -> bool:
        return self.lower is not None and self.upper is not None
