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
class JointLimits:
    """The URDF ``<limit>`` of a joint; a missing bound is None."""

    lower: Optional[float] = None
    upper: Optional[float] = None
    effort: Optional[float] = None
    velocity: Optional[float] = None

    @property
    def has_position_limits(self) -> bool:
        return self.lower is not None and self.upper is not None
