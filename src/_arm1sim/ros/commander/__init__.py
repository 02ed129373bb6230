"""The moveit_commander Python API (noetic) on Debian 12, where MoveIt does not exist: the
generated `moveit_commander` catkin package re-exports this package, so that
`import moveit_commander` in a user's script finds it. Everything talks to move_group (or
its stand-in, moveit_ros_move_group) through MoveIt's own actions, services and topics.
"""

from .exception import MoveItCommanderException
from .move_group import MoveGroupCommander
from .planning_scene_interface import PlanningSceneInterface
from .robot import RobotCommander
from .roscpp_initializer import roscpp_initialize, roscpp_shutdown

__all__ = [
    'MoveGroupCommander',
    'MoveItCommanderException',
    'PlanningSceneInterface',
    'RobotCommander',
    'roscpp_initialize',
    'roscpp_shutdown',
]
