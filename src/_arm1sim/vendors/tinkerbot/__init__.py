"""Tinkerbot: a toy vendor of our own, the smallest room that plugs in (docs/architecture.md).

- ``hw_sim``: TinkerHWSim, the RobotHWSim of ``<robotSimType>tinkerbot_gazebo/TinkerHWSim``:
  every joint effort-driven through a gearbox whose ratio comes from the parameter server.

Used by test/unit/test_vendor_rooms.py. This file is the room's manifest (see
vendors/__init__.py): it imports nothing else.
"""

from .. import Room

ROOM = Room('tinkerbot', robot_hw_sims={'tinkerbot_gazebo/TinkerHWSim': 'hw_sim:TinkerHWSim'})
