"""Vendor rooms: one subpackage per robot vendor, plugged in through the registries alone.

As franka_gazebo lives in franka's repository and gazebo_ros_control finds its RobotHWSim
by ``<robotSimType>`` through pluginlib, the core (description/, physics/, control/, sim/,
ros/) names no vendor. Each room's ``__init__`` is its manifest, as a pluginlib plugin
description XML is: a ``ROOM`` (a ``Room``) naming what it offers, as ``'module:Class'``
strings inside the room. A manifest imports nothing but this module, so reading every
room's (``rooms()``) costs nothing; a class is imported when it is first asked for
(``load``), so no vendor's code, and none of its message packages, loads for a robot that
does not use it. The registries read the manifests:

- ``robot_hw_sims``: robotSimType -> its RobotHWSim (sim/robot_hw_sims.py);
- ``controllers``: Controller classes by their ``type_name`` (control/registry.py), each
  registering the message types it uses (control/message_types.py) when it is imported;
- ``cpp_only_packages``: controller packages that are C++ only, named in the error.

Adding a vendor: a folder here with an ``__init__`` defining ``ROOM`` (docs/architecture.md,
"Where to add").
"""

from __future__ import annotations

import importlib
import pkgutil
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Tuple


@dataclass(frozen=True)
class Room:
    """A vendor room's manifest: plain data, classes named as ``'module:Class'``."""

    name: str  # the room's package under vendors/
    robot_hw_sims: Mapping[str, str] = field(default_factory=dict)  # robotSimType -> class
    controllers: Tuple[str, ...] = ()  # Controller subclasses
    cpp_only_packages: Mapping[str, str] = field(default_factory=dict)  # package -> repository


_rooms: Optional[List[Room]] = None


def rooms() -> List[Room]:
    """Every room's manifest, in name order; read once. A robotSimType offered twice is
    refused here, as a controller type_name taken twice is (control/registry.py)."""
    global _rooms
    if _rooms is None:
        found: List[Room] = []
        for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
            if not info.ispkg:
                continue
            module = importlib.import_module('%s.%s' % (__name__, info.name))
            room = getattr(module, 'ROOM', None)
            if not isinstance(room, Room) or room.name != info.name:
                raise TypeError(
                    'vendors/%s: its __init__ must define ROOM = Room(%r, ...)'
                    % (info.name, info.name)
                )
            found.append(room)
        _check_unique(found)
        _rooms = found
    return _rooms


def _check_unique(found: List[Room]) -> None:
    owner: Dict[str, str] = {}
    for room in found:
        for sim_type in room.robot_hw_sims:
            if not sim_type or sim_type in owner:
                raise TypeError(
                    'vendors/%s: robotSimType %r is empty or already offered by %s'
                    % (room.name, sim_type, owner.get(sim_type, 'another room'))
                )
            owner[sim_type] = room.name


def load(room: Room, ref: str) -> Any:
    """The object ``'module:Name'`` of ``room``, imported now."""
    module, _, name = ref.partition(':')
    return getattr(importlib.import_module('%s.%s.%s' % (__name__, room.name, module)), name)


def robot_sim_types() -> Dict[str, Tuple[Room, str]]:
    """robotSimType -> (room, class reference), over every room."""
    return {t: (room, ref) for room in rooms() for t, ref in room.robot_hw_sims.items()}
