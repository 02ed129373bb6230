"""The controller types a controller manager can load, by their ``type`` parameter.

What pluginlib's controller_plugins.xml is to ros_control: a new type is its own module
(a Controller subclass naming its ``type_name`` and ``interface``), imported here and
listed in CONTROLLER_CLASSES; a vendor's are listed in its room's manifest
(vendors/__init__.py) and added here.
"""

from __future__ import annotations

from typing import Dict, Tuple, Type

from ..vendors import load, rooms
from .controller import Controller
from .forward_command_controller import FORWARD_CONTROLLERS
from .gripper_action_controller import GripperActionController, PositionGripperActionController
from .joint_position_controller import JointPositionController
from .joint_state_controller import JointStateController
from .joint_trajectory_controller import (
    JointTrajectoryController,
    PositionJointTrajectoryController,
    VelocityJointTrajectoryController,
)
from .joint_velocity_controller import JointVelocityController

CONTROLLER_CLASSES: Tuple[Type[Controller], ...] = (
    JointPositionController,
    JointStateController,
    JointTrajectoryController,
    PositionJointTrajectoryController,
    VelocityJointTrajectoryController,
    JointVelocityController,
    *FORWARD_CONTROLLERS,
    GripperActionController,
    PositionGripperActionController,
)
VENDOR_CONTROLLER_CLASSES: Tuple[Type[Controller], ...] = tuple(
    load(room, ref) for room in rooms() for ref in room.controllers
)

# Controller packages that are C++ plugins only (pluginlib libraries): no Python manager
# can load them. Package -> the repository that ships it, for the error message.
CPP_ONLY_PACKAGES = {
    package: repository
    for room in rooms()
    for package, repository in room.cpp_only_packages.items()
}


def by_type_name(classes: Tuple[Type[Controller], ...]) -> Dict[str, Type[Controller]]:
    types: Dict[str, Type[Controller]] = {}
    for cls in classes:
        if not cls.type_name or cls.type_name in types:
            raise TypeError(
                '%s: type_name %r is empty or already taken' % (cls.__name__, cls.type_name)
            )
        types[cls.type_name] = cls
    return types


CONTROLLER_TYPES = by_type_name(CONTROLLER_CLASSES + VENDOR_CONTROLLER_CLASSES)


def cpp_only(type_name: str) -> str:
    """The repository shipping ``type_name`` when it is a known C++-only controller, else ''."""
    return CPP_ONLY_PACKAGES.get(type_name.split('/', 1)[0], '')
